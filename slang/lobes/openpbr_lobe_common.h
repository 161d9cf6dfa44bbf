// What every lobe shares: the sample record, the lobe-type bits and the shape of a lobe.
// A lobe is a struct (OpenPBR_<Kind>Lobe) plus free functions with the same shape for every lobe:
//   openpbr_<use>_lobe_prepare(inputs, layer weight, ..., view, out albedo) -> struct
//       one use of the lobe in OpenPBR 1.1 (e.g. the coat, the metal, the thin-walled sheet),
//       set up from the resolved inputs, the weight the layers above leave it and the view;
//       `albedo` receives its directional-albedo estimate at the view (each prepare says which
//       weights it includes), which openpbr_bsdf.h feeds to layering and lobe selection (the
//       interface seen from inside, selected by opacity alone, has none).
//       A lobe file holds the prepare of every use of its lobe.
//   openpbr_<kind>_lobe_init(weight, ..., view) -> struct, from numbers already derived (what
//       prepare calls; tests call it directly)
//   openpbr_<kind>_lobe_empty(...)              -> the weight-0 struct of an absent lobe
//   openpbr_<kind>_lobe_eval(lobe, view, light) -> BSDF x |cos(light)| (vec3), local frame
//   openpbr_<kind>_lobe_pdf(lobe, view, light)  -> solid-angle density of _sample
//   openpbr_<kind>_lobe_sample(lobe, view, u)   -> OpenPBR_LobeSample
//   openpbr_<kind>_lobe_albedo(lobe, view)      -> vec3, where the struct alone gives it (fuzz)
// openpbr_bsdf.h composes the prepared lobes (layering, darkening, selection weights) and
// dispatches eval, pdf and sample over them. Directions are unit vectors in the lobe's local
// frame pointing away from the surface.
#ifndef OPENPBR_LOBE_COMMON_H
#define OPENPBR_LOBE_COMMON_H

#include "../math/openpbr_math.h"

// OpenPBR_BsdfLobeType: scattering-kind flags in the low byte, the lobe's identity above.
// A type where the language has typedef (so it reaches Slang importers, which see no macros);
// GLSL has none: a macro there.
#if defined(OPENPBR_LANGUAGE_TARGET_GLSL)
#define OpenPBR_BsdfLobeType uint
#else
OPENPBR_NAMESPACE_BEGIN
typedef uint OpenPBR_BsdfLobeType;
OPENPBR_NAMESPACE_END
#endif
#define OPENPBR_LOBE_TYPE_NONE 0u
#define OPENPBR_LOBE_TYPE_REFLECTION 1u
#define OPENPBR_LOBE_TYPE_TRANSMISSION 2u
#define OPENPBR_LOBE_TYPE_DIFFUSE 4u
#define OPENPBR_LOBE_TYPE_GLOSSY 8u
#define OPENPBR_LOBE_TYPE_SPECULAR 16u  // a delta lobe: eval and pdf are 0 for it
#define OPENPBR_LOBE_ID_SHIFT 8u
#define OPENPBR_LOBE_ID_DIFFUSE 1u
#define OPENPBR_LOBE_ID_SPECULAR_REFLECTION 2u
#define OPENPBR_LOBE_ID_METAL 3u
#define OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION 4u
#define OPENPBR_LOBE_ID_COAT 5u
#define OPENPBR_LOBE_ID_FUZZ 6u
#define OPENPBR_LOBE_ID_DIFFUSE_TRANSMISSION 7u
#define OPENPBR_LOBE_ID_INTERFACE_FROM_INSIDE 8u
#define OPENPBR_LOBE_ID_PASS_THROUGH 9u

OPENPBR_NAMESPACE_BEGIN

struct OpenPBR_LobeSample OPENPBR_DIFFERENTIABLE
{
    vec3 direction;                  // sampled light direction, local frame
    vec3 delta_weight;               // for delta lobes only: the lobe's value / its discrete probability 1
    OpenPBR_BsdfLobeType lobe_type;  // OPENPBR_LOBE_TYPE_NONE when no sample was produced
};

OPENPBR_FUNC OpenPBR_LobeSample openpbr_make_lobe_sample(vec3 direction, OpenPBR_BsdfLobeType lobe_type)
{
    OpenPBR_LobeSample lobe_sample;
    lobe_sample.direction = direction;
    lobe_sample.delta_weight = vec3(0.0f);
    lobe_sample.lobe_type = lobe_type;
    return lobe_sample;
}

OPENPBR_FUNC OpenPBR_LobeSample openpbr_make_no_lobe_sample()
{
    return openpbr_make_lobe_sample(vec3(0.0f, 0.0f, 1.0f), OPENPBR_LOBE_TYPE_NONE);
}

OPENPBR_FUNC OpenPBR_BsdfLobeType openpbr_lobe_type(uint lobe_id, uint flags)
{
    return (lobe_id << OPENPBR_LOBE_ID_SHIFT) | flags;
}

// Flag tests of a lobe type. A lobe type carries the lobe id above its flags, e.g. 521 =
// OPENPBR_LOBE_ID_SPECULAR_REFLECTION << 8 | GLOSSY | REFLECTION, so comparing it with ==
// against a flag fails; test the flags with these, e.g.
// openpbr_lobe_type_is_specular(bsdf_sample.lobe_type).
OPENPBR_FUNC bool openpbr_lobe_type_is_reflection(OpenPBR_BsdfLobeType lobe_type)
{
    return (lobe_type & OPENPBR_LOBE_TYPE_REFLECTION) != 0u;
}
OPENPBR_FUNC bool openpbr_lobe_type_is_transmission(OpenPBR_BsdfLobeType lobe_type)
{
    return (lobe_type & OPENPBR_LOBE_TYPE_TRANSMISSION) != 0u;
}
OPENPBR_FUNC bool openpbr_lobe_type_is_diffuse(OpenPBR_BsdfLobeType lobe_type)
{
    return (lobe_type & OPENPBR_LOBE_TYPE_DIFFUSE) != 0u;
}
OPENPBR_FUNC bool openpbr_lobe_type_is_glossy(OpenPBR_BsdfLobeType lobe_type)
{
    return (lobe_type & OPENPBR_LOBE_TYPE_GLOSSY) != 0u;
}
OPENPBR_FUNC bool openpbr_lobe_type_is_specular(OpenPBR_BsdfLobeType lobe_type)
{
    return (lobe_type & OPENPBR_LOBE_TYPE_SPECULAR) != 0u;
}
// The lobe's identity (OPENPBR_LOBE_ID_*), 0 for OPENPBR_LOBE_TYPE_NONE.
OPENPBR_FUNC uint openpbr_lobe_type_id(OpenPBR_BsdfLobeType lobe_type) { return lobe_type >> OPENPBR_LOBE_ID_SHIFT; }

OPENPBR_NAMESPACE_END

#endif
