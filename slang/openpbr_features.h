// Feature toggles: simulate only the effects a scene calls for.
//
// Each costly effect of the BSDF has a toggle, on by default. A toggle that is off acts
// exactly like the effect's weight being zero (the field listed below is forced to its
// "absent" value right after the input contract), so
//   - a material that does not use the effect renders bit-identically with the toggle off, and
//   - every use in prepare/eval/sample is guarded as `if (inputs.coat_weight > 0.0f)`: once the
//     toggle is a constant (a specialized pipeline, a function constant, a -D permutation) the
//     compiler folds the guard and the effect's code is gone; with the toggle on, a zero weight
//     still skips the work at run time.
// A material that needs an effect the pipeline switched off would render without it, so hosts
// check openpbr_required_feature_mask(material) against the pipeline's mask first
// (host/scene/features.h refuses with the material and feature named).
//
// Toggle (spec constant name, stable SPIR-V constant_id / Metal function_constant index):
//   EnableCoat          0  coat_weight -> 0                      (spec "Coat")
//   EnableFuzz          1  fuzz_weight -> 0                      (spec "Fuzz")
//   EnableMetal         2  base_metalness -> 0                   (spec "Metal")
//   EnableTransmission  3  transmission_weight -> 0              (spec "Translucent base")
//   EnableDispersion    4  transmission_dispersion_scale -> 0    (spec "Dispersion")
//   EnableThinFilm      5  thin_film_weight -> 0                 (spec "Thin-film iridescence")
//   EnableThinWalled    6  geometry_thin_walled -> false         (spec "Thin-walled case")
//   EnableSubsurface    7  subsurface_weight -> 0                (spec "Subsurface")
//   EnableEmission      8  emission_luminance -> 0               (spec "Emission")
//   EnableAnisotropy    9  specular/coat_roughness_anisotropy -> 0 (spec "Microfacet model")
// Legacy names, kept working as aliases (each ANDed into the toggles it covers):
//   EnableSheenAndCoat 10  coat and fuzz
//   EnableTranslucency 11  transmission
//   EnableMetallic     12  metal
//
// How each language gets its constants (the interop backend defines
// OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(name) and OPENPBR_GET_SPECIALIZATION_CONSTANT(name)):
//   Slang -> SPIR-V, GLSL: [vk::constant_id(id)] / layout(constant_id = id) const bool, set
//       through VkSpecializationInfo (host/scene/features.h builds the map entries).
//   Metal: [[function_constant(id)]], set through MTLFunctionConstantValues; undefined = on.
//   HLSL, CUDA (and Slang when it emits them, -DOPENPBR_SPECIALIZATION_CONSTANTS=0): no spec
//       constants (Slang would turn them into uniforms, which fold nothing); compile-time
//       permutations instead, e.g. -DOPENPBR_FEATURE_COAT=0.
//   C++: compile-time, e.g. -DOPENPBR_FEATURE_COAT=0 (the code is gone); or run-time through
//       openpbr::openpbr_runtime_feature_mask (interop/openpbr_interop_cpp.h).
// Every language also takes the compile-time form: defining OPENPBR_FEATURE_<NAME> before
// including openpbr.h overrides the constant, e.g. -DOPENPBR_FEATURE_THIN_FILM=0.
#ifndef OPENPBR_FEATURES_H
#define OPENPBR_FEATURES_H

#include "openpbr_resolved_inputs.h"

#define OPENPBR_SPECIALIZATION_ID_EnableCoat 0
#define OPENPBR_SPECIALIZATION_ID_EnableFuzz 1
#define OPENPBR_SPECIALIZATION_ID_EnableMetal 2
#define OPENPBR_SPECIALIZATION_ID_EnableTransmission 3
#define OPENPBR_SPECIALIZATION_ID_EnableDispersion 4
#define OPENPBR_SPECIALIZATION_ID_EnableThinFilm 5
#define OPENPBR_SPECIALIZATION_ID_EnableThinWalled 6
#define OPENPBR_SPECIALIZATION_ID_EnableSubsurface 7
#define OPENPBR_SPECIALIZATION_ID_EnableEmission 8
#define OPENPBR_SPECIALIZATION_ID_EnableAnisotropy 9
#define OPENPBR_SPECIALIZATION_ID_EnableSheenAndCoat 10
#define OPENPBR_SPECIALIZATION_ID_EnableTranslucency 11
#define OPENPBR_SPECIALIZATION_ID_EnableMetallic 12
// Ids 0-15 are reserved for the module's toggles; a consumer's own constants start at 16
// (examples/shade_batch.slang). Number of toggle constants (ids 0 .. count - 1), e.g. for the
// host's map entries.
#define OPENPBR_SPECIALIZATION_CONSTANT_COUNT 13

// Bits of a feature mask: bit k is the toggle with constant id k (the legacy bits 10-12 never
// appear in a required mask; they only switch features off).
#define OPENPBR_FEATURE_BIT_COAT (1u << 0)
#define OPENPBR_FEATURE_BIT_FUZZ (1u << 1)
#define OPENPBR_FEATURE_BIT_METAL (1u << 2)
#define OPENPBR_FEATURE_BIT_TRANSMISSION (1u << 3)
#define OPENPBR_FEATURE_BIT_DISPERSION (1u << 4)
#define OPENPBR_FEATURE_BIT_THIN_FILM (1u << 5)
#define OPENPBR_FEATURE_BIT_THIN_WALLED (1u << 6)
#define OPENPBR_FEATURE_BIT_SUBSURFACE (1u << 7)
#define OPENPBR_FEATURE_BIT_EMISSION (1u << 8)
#define OPENPBR_FEATURE_BIT_ANISOTROPY (1u << 9)
// The ten features (bits 0-9), e.g. the mask of the full pipeline.
#define OPENPBR_FEATURE_MASK_ALL 1023u

OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableCoat)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableFuzz)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableMetal)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableTransmission)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableDispersion)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableThinFilm)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableThinWalled)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableSubsurface)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableEmission)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableAnisotropy)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableSheenAndCoat)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableTranslucency)
OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(EnableMetallic)

// The toggles as the BSDF reads them; each may be predefined (compile-time form), e.g. 0.
#ifndef OPENPBR_FEATURE_COAT
#define OPENPBR_FEATURE_COAT \
    (OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableCoat) && OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableSheenAndCoat))
#endif
#ifndef OPENPBR_FEATURE_FUZZ
#define OPENPBR_FEATURE_FUZZ \
    (OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableFuzz) && OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableSheenAndCoat))
#endif
#ifndef OPENPBR_FEATURE_METAL
#define OPENPBR_FEATURE_METAL \
    (OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableMetal) && OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableMetallic))
#endif
#ifndef OPENPBR_FEATURE_TRANSMISSION
#define OPENPBR_FEATURE_TRANSMISSION \
    (OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableTransmission) && OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableTranslucency))
#endif
#ifndef OPENPBR_FEATURE_DISPERSION
#define OPENPBR_FEATURE_DISPERSION OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableDispersion)
#endif
#ifndef OPENPBR_FEATURE_THIN_FILM
#define OPENPBR_FEATURE_THIN_FILM OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableThinFilm)
#endif
#ifndef OPENPBR_FEATURE_THIN_WALLED
#define OPENPBR_FEATURE_THIN_WALLED OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableThinWalled)
#endif
#ifndef OPENPBR_FEATURE_SUBSURFACE
#define OPENPBR_FEATURE_SUBSURFACE OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableSubsurface)
#endif
#ifndef OPENPBR_FEATURE_EMISSION
#define OPENPBR_FEATURE_EMISSION OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableEmission)
#endif
#ifndef OPENPBR_FEATURE_ANISOTROPY
#define OPENPBR_FEATURE_ANISOTROPY OPENPBR_GET_SPECIALIZATION_CONSTANT(EnableAnisotropy)
#endif

OPENPBR_NAMESPACE_BEGIN

// Forces every switched-off effect to its absent value (after the input contract, so the
// values compared with zero are already clamped). The identity for a material whose required
// mask is inside the enabled toggles.
OPENPBR_FUNC OpenPBR_ResolvedInputs openpbr_apply_feature_toggles(OPENPBR_IN(OpenPBR_ResolvedInputs) contracted)
{
    OpenPBR_ResolvedInputs inputs = contracted;
    inputs.coat_weight = OPENPBR_FEATURE_COAT ? inputs.coat_weight : 0.0f;
    inputs.fuzz_weight = OPENPBR_FEATURE_FUZZ ? inputs.fuzz_weight : 0.0f;
    inputs.base_metalness = OPENPBR_FEATURE_METAL ? inputs.base_metalness : 0.0f;
    inputs.transmission_weight = OPENPBR_FEATURE_TRANSMISSION ? inputs.transmission_weight : 0.0f;
    inputs.transmission_dispersion_scale = OPENPBR_FEATURE_DISPERSION ? inputs.transmission_dispersion_scale : 0.0f;
    inputs.thin_film_weight = OPENPBR_FEATURE_THIN_FILM ? inputs.thin_film_weight : 0.0f;
    inputs.geometry_thin_walled = OPENPBR_FEATURE_THIN_WALLED ? inputs.geometry_thin_walled : false;
    inputs.subsurface_weight = OPENPBR_FEATURE_SUBSURFACE ? inputs.subsurface_weight : 0.0f;
    inputs.emission_luminance = OPENPBR_FEATURE_EMISSION ? inputs.emission_luminance : 0.0f;
    inputs.specular_roughness_anisotropy = OPENPBR_FEATURE_ANISOTROPY ? inputs.specular_roughness_anisotropy : 0.0f;
    inputs.coat_roughness_anisotropy = OPENPBR_FEATURE_ANISOTROPY ? inputs.coat_roughness_anisotropy : 0.0f;
    return inputs;
}

// The features a material needs (OPENPBR_FEATURE_BIT_*): the toggles whose field
// openpbr_apply_feature_toggles would change, less those prepare provably ignores (the coat's
// anisotropy without a coat, dispersion on a thin-walled surface). `contracted` must have
// passed the input contract (host::required_feature_mask does both).
OPENPBR_FUNC uint openpbr_required_feature_mask(OPENPBR_IN(OpenPBR_ResolvedInputs) contracted)
{
    uint mask = 0u;
    mask |= contracted.coat_weight > 0.0f ? OPENPBR_FEATURE_BIT_COAT : 0u;
    mask |= contracted.fuzz_weight > 0.0f ? OPENPBR_FEATURE_BIT_FUZZ : 0u;
    mask |= contracted.base_metalness > 0.0f ? OPENPBR_FEATURE_BIT_METAL : 0u;
    mask |= contracted.transmission_weight > 0.0f ? OPENPBR_FEATURE_BIT_TRANSMISSION : 0u;
    // Thin-walled surfaces do not disperse (prepare takes scale 0 there).
    mask |= (contracted.transmission_dispersion_scale > 0.0f && !contracted.geometry_thin_walled)
                ? OPENPBR_FEATURE_BIT_DISPERSION
                : 0u;
    mask |= contracted.thin_film_weight > 0.0f ? OPENPBR_FEATURE_BIT_THIN_FILM : 0u;
    mask |= contracted.geometry_thin_walled ? OPENPBR_FEATURE_BIT_THIN_WALLED : 0u;
    mask |= contracted.subsurface_weight > 0.0f ? OPENPBR_FEATURE_BIT_SUBSURFACE : 0u;
    mask |= contracted.emission_luminance > 0.0f ? OPENPBR_FEATURE_BIT_EMISSION : 0u;
    // The coat's anisotropy matters only where there is a coat.
    mask |= (contracted.specular_roughness_anisotropy > 0.0f ||
             (contracted.coat_weight > 0.0f && contracted.coat_roughness_anisotropy > 0.0f))
                ? OPENPBR_FEATURE_BIT_ANISOTROPY
                : 0u;
    return mask;
}

OPENPBR_NAMESPACE_END

#endif
