// microsurface.h - ground truth for the accuracy study (docs/accuracy-vs-time.md): directional
// albedos of isotropic GGX microsurfaces by a random walk on the microsurface, in double
// precision, following Heitz, Hanika, d'Eon & Dachsbacher 2016, "Multiple-Scattering
// Microfacet BSDFs with the Smith Model" (SIGGRAPH 2016), with uncorrelated uniform heights
// (C1(h) = (h + 1) / 2 on [-1, 1]; the albedo does not depend on the height distribution):
//   - the next height along a ray from the Smith shadowing (escape probability G1 = C1(h)^Lambda
//     upwards; the hit height by inverting the survival function);
//   - the next direction from the microfacet normal, drawn from the distribution of normals
//     visible from the incoming direction, which may point below the horizon inside the walk
//     (the spherical-cap construction of Dupuy & Benyoub 2023 covers that case unchanged: the
//     cap z in [-v_std.z, 1]);
//   - conductors carry the Fresnel factor as an energy weight; dielectrics reflect with
//     probability F and otherwise refract into the other side, which the walk continues on by
//     flipping the frame (heights and directions negated, eta inverted).
// The walk restricted to one bounce is the single-scattering BSDF with height-correlated Smith
// masking-shadowing (Heitz 2014, eq. 99 for reflection), which
// microsurface_single_scattering_albedo integrates by quadrature; tests/studies checks both.
// Anisotropic GGX (alpha_x along the tangent x, alpha_y along y) enters through the stretch of
// the configuration (Heitz 2014, section 5.3): Lambda and the visible normals see the direction
// scaled by (alpha_x, alpha_y, 1).
// microsurface_scatter is one walk as a scattering routine with any Fresnel factor (per RGB
// channel, e.g. F82-tint or a thin film): the single-interface step of the layered reference
// (host/references/layered_reference.h); microsurface_albedo is its average over walks.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "host/support/random.h"

namespace openpbr::host {

// ---- One walk on one interface, any Fresnel factor ----

using MicrosurfaceColor = std::array<double, 3>;  // a factor per RGB channel

// How the Fresnel factor F acts at each microfacet event of a walk.
enum class MicrosurfaceResponse
{
    reflect,             // reflect, weight x F (a conductor; F = 1 when no Fresnel is given)
    reflect_or_refract,  // reflect with probability p = mean of F over the channels (F itself when grey),
                         // weight x F / p, else refract with weight x (1 - F) / (1 - p)
    refract,             // refract with weight 1; an event that would reflect totally ends the path
};

// The reflectance of a microfacet at cos_incident = cos(direction back towards the light, m) in
// (0, 1], on the interface's upper side (from_above) or lower side.
class MicrosurfaceFresnel
{
  public:
    virtual ~MicrosurfaceFresnel() = default;
    virtual MicrosurfaceColor reflectance(double cos_incident, bool from_above) const = 0;
};

struct MicrosurfaceInterface
{
    double alpha_x = 0.25;  // GGX alpha along the tangent x, e.g. 0.25 for roughness 0.5; floored at 1e-4
    double alpha_y = 0.25;  // GGX alpha along the bitangent y; equal to alpha_x when isotropic
    double eta = 1.5;       // n_below / n_above: the refraction (read by reflect_or_refract and refract only)
    MicrosurfaceResponse response = MicrosurfaceResponse::reflect;
    // nullptr: F = 1 for reflect, the unpolarized dielectric Fresnel of the side's eta otherwise.
    const MicrosurfaceFresnel* fresnel = nullptr;
};

struct MicrosurfaceScattering
{
    glm::dvec3 direction{0.0, 0.0, 0.0};      // leaving direction, unit, in the interface's frame (z up)
    bool transmitted = false;                 // left on the side opposite to the one light came from
    bool absorbed = true;                     // no leaving direction (order limit, degenerate normal, E_T0's reflection)
    MicrosurfaceColor weight{0.0, 0.0, 0.0};  // energy weight of the leaving light per channel
};

// One random walk (Heitz et al. 2016, Algorithm 1) for light travelling along `travel` (unit;
// travel.z < 0 arrives from above, > 0 from below; the walk from below is the walk from above
// in the frame turned upside down, eta inverted). max_order: scattering events kept (0: all,
// up to 1000). Uses random.next_double() in a fixed order per event: height, two for the
// normal, one more for reflect_or_refract.
MicrosurfaceScattering microsurface_scatter(const MicrosurfaceInterface& interface, const glm::dvec3& travel, int max_order,
                                            SplitMix64& random);

// Unpolarized reflectance of a smooth dielectric interface, eta = n_transmitted / n_incident; 1
// under total internal reflection (the walk's default Fresnel factor).
double microsurface_fresnel_dielectric(double cos_incident, double eta);

// ---- Directional albedos of single interfaces (the accuracy study's ground truth) ----

enum class MicrosurfaceKind
{
    conductor_white,     // F = 1: nothing is absorbed, the albedo of all orders is 1
    conductor_schlick,   // F = Schlick(f0), an energy weight per bounce
    dielectric_reflect,  // F = exact dielectric Fresnel of eta as an energy weight, reflection only
                         // (the single-scattering table E_R of slang/openpbr_lut.h)
    dielectric,          // reflect with probability F, refract otherwise (E_RT's walk)
    dielectric_refract,  // always refract, weight 1 (E_T0's walk: no Fresnel factor)
};

struct MicrosurfaceMaterial
{
    MicrosurfaceKind kind = MicrosurfaceKind::conductor_white;
    double alpha = 0.25;  // GGX alpha (isotropic), e.g. 0.25 for roughness 0.5; floored at 1e-4
    double f0 = 1.0;      // conductor_schlick: normal-incidence reflectance, e.g. 0.9
    double eta = 1.5;     // dielectrics: n_below / n_above seen from the view's side, e.g. 1.5
};

struct MicrosurfaceAlbedo
{
    double reflected = 0.0;          // energy leaving on the view's side
    double transmitted = 0.0;        // energy leaving on the other side (dielectrics)
    double reflected_error = 0.0;    // standard error of `reflected`
    double transmitted_error = 0.0;  // standard error of `transmitted`
};

// Directional albedo at view cosine mu (in (0, 1]) by `paths` random walks seeded by `seed`.
// max_order: scattering events kept (1 = single scattering; 0 = all, up to 1000 per path).
// Throws std::invalid_argument for mu outside (0, 1], paths = 0, max_order < 0.
MicrosurfaceAlbedo microsurface_albedo(const MicrosurfaceMaterial& material, double mu, int max_order, std::uint64_t paths,
                                       std::uint64_t seed);

// Single-scattering albedo at view cosine mu by an n x n midpoint quadrature over the visible
// normal sampler's unit square (reflection kinds only: conductor_*, dielectric_reflect):
// E = integral of F(wo.h) G2(wo, wi) / G1(wo) over h ~ D_wo, G2 height-correlated. Throws
// std::invalid_argument for the refracting kinds, mu outside (0, 1] or n < 1.
double microsurface_single_scattering_albedo(const MicrosurfaceMaterial& material, double mu, int n);

struct MicrosurfaceQuery
{
    MicrosurfaceMaterial material;
    double mu = 1.0;
    int max_order = 0;
    std::uint64_t paths = 1u << 16;
    std::uint64_t seed = 1;
};

// A cache of walk results in a JSON file, {"version": 1, "entries": {key: [reflected,
// transmitted, reflected_error, transmitted_error]}}; the key names the material, mu, order,
// paths and seed, so a changed grid simply misses.
class MicrosurfaceCache
{
  public:
    // Empty path: memory only. An unreadable or malformed file is ignored (recomputed).
    explicit MicrosurfaceCache(std::filesystem::path path);
    // The results of the queries, cached ones read back and the rest walked in parallel (TBB).
    std::vector<MicrosurfaceAlbedo> albedos(const std::vector<MicrosurfaceQuery>& queries);
    // Writes the file (atomically) when something was added. Throws std::runtime_error naming
    // the path when it cannot be written.
    void save() const;
    std::size_t hits() const { return hit_count; }
    std::size_t misses() const { return miss_count; }

  private:
    std::filesystem::path file;
    std::map<std::string, MicrosurfaceAlbedo> entries;
    bool dirty = false;
    std::size_t hit_count = 0;
    std::size_t miss_count = 0;
};

}  // namespace openpbr::host
