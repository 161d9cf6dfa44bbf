// layered_reference.h - the layered ground truth of OpenPBR's surface: light transport through
// the stack the specification describes (spec "Model": fuzz over coat over the base substrate,
// the film at the base's interface; "Layering": "complete conformance" is all inter-layer
// transport), by position-free Monte Carlo (Guo, Hasan & Zhao 2018, "Position-Free Monte Carlo
// Simulation for Arbitrary Layered BSDFs", SIGGRAPH Asia): a path is a list of vertical steps
// between the stack's components, with no lateral position (the layers are laterally infinite
// and homogeneous), and a depth only inside the one layer that scatters in its volume (the fuzz).
// Double precision throughout; docs/layering-accuracy.md has what it finds about the model.
//
// The stack, top to bottom (z up, light arrives from above; exterior IOR 1):
//   fuzz      a volume of fiber-like SGGX microflakes (Heitz et al. 2015), unit density and
//             unit thickness, non-absorbing specular flakes, index-matched: the very medium the
//             fuzz lobe's LTC table was fitted to (host/tables/fuzz_fit.h, simulate_fuzz_layer),
//             now over the real stack instead of a black base. fuzz_color tints what the
//             specification says it tints, the fuzz's own reflection (spec "Fuzz": "fuzz_color
//             tints only the fuzz lobe", transmittance grey): light leaving the top without
//             having passed below the fuzz is multiplied by fuzz_color, the rest is not.
//   coat      a GGX dielectric interface (coat_roughness, _anisotropy; IOR coat_ior / 1) over a
//             purely absorbing medium whose normal-incidence round trip is coat_color (spec
//             "Coat", view-dependent absorption): a pass at cosine mu inside the coat transmits
//             coat_color^(1 / (2 mu)).
//   base      metal: a GGX conductor with F82-tint (F0 = base_weight base_color, edge tint
//             specular_color), specular_weight once per hit of the metal (spec 1.1.1: "the
//             entire metallic lobe" is scaled); or dielectric: a GGX interface of relative IOR
//             specular_ior / (coat_ior or 1), modulated by specular_weight (eq. modulated_ior),
//             specular_color multiplying its reflection of light from above only (spec "Base
//             Substrate"), and below it
//               glossy-diffuse  an index-matched EON diffuse of roughness base_diffuse_roughness
//                               and weight base_weight; its albedo rho is what makes the slab
//                               meet the spec's definition of base_color at normal incidence,
//                               E_diffuse = (1 - E_spec) C (eq. glossy_diffuse_albedo_constraint,
//                               "in the Lambertian case of zero roughness"): with tau the share
//                               of Lambertian light from below that leaves through the interface
//                               and T_in the share of normal light that enters,
//                               rho = C' / (tau + C' (1 - tau)), C' = C (1 - E_spec) / T_in, both
//                               walked through the interface itself (layered_calibrate_diffuse);
//               translucent /   the interior (semi-infinite): light crossing the interface is
//               subsurface      transmitted (the BSDF's transmission; the volume is not part of
//                               it), tinted by transmission_color when transmission_depth = 0
//                               (spec "Translucent base": then a constant tint of the refraction).
//   The film (thin_film_*) replaces the base interface's Fresnel factor by the Airy reflectance
//   of the film over the dielectric or the conductor (from above and, for the dielectric, from
//   below at the matching outside angle: a lossless stack reflects the same from both sides),
//   with the coat or the exterior above it.
//   Thin-walled (spec "Thin-walled case": the structure mirrored about the base): the
//   translucent base is a sheet of medium between the base interface and its mirror image,
//   absorbing transmission_color^(1 / mu) per pass; the subsurface base a thin scattering sheet
//   that reflects 1/2 S (1 - g) and transmits 1/2 S (1 + g) with EON shapes of albedo 1; the
//   film, coat and fuzz are mirrored below it too. Metal and glossy-diffuse stay opaque.
//
// Parameters that are mixture weights (spec "Mixing": statistical area fractions) make a
// mixture of pure stacks, each walked on its own and combined linearly with its weight, which
// is the spec's lerp of BSDFs: geometry_opacity (the rest passes straight through),
// fuzz_weight, coat_weight, base_metalness, transmission_weight, subsurface_weight and
// thin_film_weight ("a linear blend of the BSDF with and without the film"). Where the model
// blends a parameter by a weight instead (the base's IOR and roughness by coat_weight), the
// reference has each pure stack's own. Parameters that steer the model's approximation, not the
// physics, have no effect here: coat_darkening (the physics darkens as it does; the study
// compares the model at coat_darkening = 1, see layering_accuracy.h), and the coat's roughening
// of the base (transport roughens by itself). Flat geometry: the normals and tangents of the
// inputs are not read (the base and coat frames are both the +z frame, tangent +x).
//
// Output: the directional albedo per channel, reflected and transmitted, and the BSDF times
// |cos| averaged over the bins of a direction grid (LayeredGrid: equal solid angle, both
// hemispheres), each with its standard error from the spread of the paths. Bin averages are unbiased estimates of integrals
// of the BSDF, so a model integrated over the same bins compares with them like with like, delta lobes included.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "host/references/layered_formulas.h"
#include "host/tables/microsurface.h"
#include "slang/openpbr_resolved_inputs.h"

namespace openpbr::host {

enum class LayeredComponentKind
{
    fuzz,       // the SGGX fuzz volume (cross_section)
    interface,  // a rough interface (microsurface walk) with tints
    absorber,   // a purely absorbing medium: a pass at cosine mu transmits exp(log_transmittance / mu)
    diffuse,    // an opaque EON diffuse (rho, sigma, weight), lit from above only
    sheet,      // a thin scattering sheet: EON-shaped reflection and transmission of albedo 1, scaled
};

struct LayeredComponent
{
    LayeredComponentKind kind = LayeredComponentKind::interface;
    std::string name;  // e.g. "coat interface"
    // fuzz: the SGGX cross section c = max(fuzz_roughness^2, 0.01) (host/tables/fuzz_fit.h)
    double cross_section = 0.25;
    // interface
    MicrosurfaceInterface interface;
    std::shared_ptr<const MicrosurfaceFresnel> fresnel;  // owned; interface.fresnel points to it
    bool outer_side_up = true;  // the side light of the exterior reaches it from (false: a mirrored copy)
    LayeredColor reflect_outer_tint{1.0, 1.0, 1.0};  // on reflections of light from the outer side (specular_color)
    LayeredColor enter_tint{1.0, 1.0, 1.0};          // on transmission from the outer side (transmission_color at depth 0)
    LayeredColor per_hit_scale{1.0, 1.0, 1.0};       // on every hit (specular_weight on the metal)
    // absorber: ln of the transmittance of one pass at normal incidence
    LayeredColor log_transmittance{0.0, 0.0, 0.0};
    // diffuse (rho, sigma, weight) and sheet (reflection and transmission albedos, sigma)
    LayeredColor rho{0.0, 0.0, 0.0};
    double sigma = 0.0;
    double weight = 1.0;
    LayeredColor sheet_reflection{0.0, 0.0, 0.0};
    LayeredColor sheet_transmission{0.0, 0.0, 0.0};
};

// One pure stack of the mixture.
struct LayeredStack
{
    std::string name;                          // e.g. "fuzz + coat + metal + film"
    double weight = 1.0;                       // its share of the mixture
    bool pass_through = false;                 // geometry_opacity's transparent share: straight through, weight 1
    std::vector<LayeredComponent> components;  // top to bottom
    LayeredColor fuzz_tint{1.0, 1.0, 1.0};     // fuzz_color, when components[0] is the fuzz
};

struct LayeredMaterial
{
    // Per channel when the IOR is dispersive (each channel refracts its own way), otherwise one
    // mixture for all three channels (stacks[0]).
    bool per_channel = false;
    std::array<std::vector<LayeredStack>, 3> stacks;
    std::string description;  // the mixture, e.g. "1.00 coat + glossy-diffuse (rho 0.10 0.60 0.90)"
};

struct LayeredBuildOptions
{
    std::uint64_t calibration_paths = 1u << 17;  // walks per glossy-diffuse calibration integral, e.g. 131072
    std::uint64_t seed = 0x1a7e5edull;           // seed of the calibration walks
};

// The mixture of pure stacks for the inputs (after the model's input contract, so both see the
// same clamped values). Throws std::invalid_argument for non-finite inputs the contract cannot
// repair (none today).
LayeredMaterial layered_material_from_inputs(const OpenPBR_ResolvedInputs& raw_inputs,
                                             const LayeredBuildOptions& options = {});

// The glossy-diffuse calibration (see above) of C through `interface`: rho per channel.
LayeredColor layered_calibrate_diffuse(const LayeredComponent& interface, const LayeredColor& color, std::uint64_t paths,
                                       std::uint64_t seed);

// ---- Direction grid ----

// Equal-solid-angle bins without a pole: each hemisphere is mapped to the unit disk by
// Lambert's equal-area projection (r = sqrt(1 - |cos theta|), the azimuth kept) and the disk to
// the square [-1, 1]^2 by the inverse of Shirley & Chiu's concentric map (1997, "A Low
// Distortion Map Between Disk and Square"), both area-preserving, and the square cut into
// resolution x resolution cells of solid angle 2 pi / resolution^2. With an odd resolution the
// normal and every direction of the plane of incidence (y = 0) lie inside a cell, not on an edge
// (a mirror reflection of a view in the x-z plane, a delta lobe, stays in one bin).
struct LayeredGrid
{
    int resolution = 9;  // cells per side of each hemisphere's square, e.g. 9 (81 bins per hemisphere)

    int bins_per_hemisphere() const { return resolution * resolution; }
    int bin_count() const { return 2 * bins_per_hemisphere(); }  // reflection first, then transmission
    double bin_solid_angle() const;                              // 2 pi / resolution^2
    // The bin of a unit direction (z > 0 reflection, z < 0 transmission), -1 for z = 0 or NaN.
    int bin_of(const glm::dvec3& direction) const;
    // The direction of a point (u, v) in [0, 1]^2 of a bin (u = v = 0.5: its centre): uniform
    // (u, v) give directions uniform in solid angle over the bin.
    glm::dvec3 bin_direction(int bin, double u, double v) const;
};

struct LayeredEstimate
{
    LayeredColor albedo{0.0, 0.0, 0.0};  // reflected + transmitted
    LayeredColor reflected{0.0, 0.0, 0.0};
    LayeredColor transmitted{0.0, 0.0, 0.0};
    LayeredColor albedo_error{0.0, 0.0, 0.0};  // standard errors
    LayeredColor reflected_error{0.0, 0.0, 0.0};
    LayeredColor transmitted_error{0.0, 0.0, 0.0};
    std::vector<LayeredColor> bins;        // bin averages of f |cos| (sr^-1), grid.bin_count() of them
    std::vector<LayeredColor> bin_errors;  // their standard errors
    std::uint64_t paths = 0;               // walked in all (every stack and channel)
    std::uint64_t capped = 0;              // paths stopped after the event limit (counted as absorbed)
    double seconds = 0.0;                  // wall time of the walks (one thread)
    double cpu_seconds = 0.0;              // CPU time of the walks' thread (what they cost on a shared machine)
    double luminance_error = 0.0;          // standard error of the albedo's Rec. 709 luminance
};

// Albedo and bin averages at view cosine mu in (0, 1] (view in the x-z plane, +x side, i.e.
// along the tangent), from `paths` paths per channel set, spread over the stacks by weight
// (each at least 1/16 of them; a pass-through stack needs one). One thread. Throws
// std::invalid_argument for mu outside (0, 1] or paths = 0.
LayeredEstimate estimate_layered(const LayeredMaterial& material, double mu, const LayeredGrid& grid, std::uint64_t paths,
                                 std::uint64_t seed);

// The reciprocity integral Q(a -> b) = integral over view directions in bin a and light
// directions in bin b of f(view, light) |cos view| |cos light|, estimated with view directions
// drawn uniformly over bin a (stratified). A reciprocal BSDF has Q(a -> b) = Q(b -> a).
// Reflection bins only. Returns the mean and its standard error per channel.
std::array<LayeredColor, 2> layered_bin_transfer(const LayeredMaterial& material, const LayeredGrid& grid, int from_bin,
                                                 int to_bin, std::uint64_t paths, std::uint64_t seed);

// One path of a stack from the view direction (unit, z > 0): where it leaves (or not), with its
// weight. Exposed for the pictures (host/studies/layering_pictures.cpp), which light the exit
// direction by an environment.
struct LayeredExit
{
    bool left = false;  // false: absorbed (or stopped after the event limit)
    glm::dvec3 direction{0.0, 0.0, 0.0};
    LayeredColor weight{0.0, 0.0, 0.0};
    bool capped = false;
};
LayeredExit layered_trace(const LayeredStack& stack, const glm::dvec3& view, SplitMix64& random);

// One path of the whole mixture: a stack drawn with probability its weight (the weights sum to
// 1), and for a per-channel material a channel drawn uniformly, the other two weighted 0 and it
// 3: an unbiased sample of the mixture's BSDF (what a renderer would trace).
LayeredExit layered_trace_material(const LayeredMaterial& material, const glm::dvec3& view, SplitMix64& random);

}  // namespace openpbr::host
