// film_dense_reference.h - the dense reference of the thin film's lobe-averaged reflectance
// (docs/thin-film-estimate.md), shared by the accuracy study's film-estimate family
// (accuracy_families.cpp) and benchmarks/film_estimate_dense.cpp: what openpbr_base_film_estimate
// approximates, averaged over the visible normals of the GGX lobe (n x n nodes of the spherical-cap
// sampler, Dupuy & Benyoub 2023) weighted by the reflected fraction G2 / G1 (Heitz 2014):
//   the dielectric's change F_film - F_plain, and the filmed F82 metal's factor.
// Header-only, so a program that compiles the headers with an estimate's settings (the benchmark)
// shares it without the host library; the reference does not depend on those settings.
#pragma once

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)

#include <algorithm>
#include <array>
#include <cmath>

#include "slang/openpbr.h"

namespace openpbr::host {

// The film on a dielectric base and on a gold-coloured F82 metal (F0 = (1, 0.78, 0.34)), as
// openpbr_prepare builds a filmed base's Fresnel factors.
struct FilmedBases
{
    OpenPBR_Fresnel dielectric;
    OpenPBR_Fresnel metal;
};

// e.g. filmed_bases(1.3f, 1.4f, 0.5f, 1.5f): seen from a coat of IOR 1.3, a film of 1.4 and 0.5 um
// on a base of IOR 1.5.
inline FilmedBases filmed_bases(const float outside_ior, const float film_ior, const float thickness_um,
                                const float base_ior)
{
    return {openpbr_add_thin_film(openpbr_make_dielectric_fresnel(base_ior / outside_ior, glm::vec3(1.0f)), 1.0f,
                                  thickness_um, film_ior, outside_ior),
            openpbr_add_thin_film(openpbr_make_f82_fresnel(glm::vec3(1.0f, 0.78f, 0.34f), glm::vec3(1.0f), glm::vec3(1.0f)),
                                  1.0f, thickness_um, film_ior, outside_ior)};
}

// The view at this cosine in the lobe's frame, in the x-z plane.
inline glm::vec3 film_view(const float view_cosine)
{
    return glm::vec3(std::sqrt(std::max(0.0f, 1.0f - view_cosine * view_cosine)), 0.0f, view_cosine);
}

// The dielectric's change (0-2) and the metal's factor (3-5) averaged over n x n visible normals of
// the isotropic GGX lobe of this roughness, e.g. n = 128 (converged: 256 gives the same counts).
inline std::array<double, 6> dense_film_average(const FilmedBases& bases, const float roughness, const float view_cosine,
                                                const int n)
{
    const glm::vec2 alpha = openpbr_ggx_alpha(roughness, 0.0f);
    const glm::vec3 view = film_view(view_cosine);
    const float lambda_view = openpbr_ggx_lambda(view, alpha);
    std::array<double, 6> sum{};
    double weight_sum = 0.0;
    for (int i = 0; i < n; ++i)
    {
        for (int j = 0; j < n; ++j)
        {
            const glm::vec3 microfacet =
                openpbr_sample_vndf_spherical_cap(view, alpha, glm::vec2((i + 0.5f) / n, (j + 0.5f) / n));
            const float cosine = glm::dot(view, microfacet);
            const glm::vec3 light = 2.0f * cosine * microfacet - view;
            if (light.z <= 0.0f)
            {
                continue;
            }
            const double weight = (1.0f + lambda_view) / (1.0f + lambda_view + openpbr_ggx_lambda(light, alpha));
            const glm::vec3 change = openpbr_fresnel_evaluate(bases.dielectric, cosine) -
                                     glm::vec3(openpbr_fresnel_dielectric(cosine, bases.dielectric.eta));
            const glm::vec3 metal = openpbr_fresnel_evaluate(bases.metal, cosine);
            for (int c = 0; c < 3; ++c)
            {
                sum[std::size_t(c)] += weight * change[c];
                sum[std::size_t(c) + 3] += weight * metal[c];
            }
            weight_sum += weight;
        }
    }
    for (double& value : sum)
    {
        value /= std::max(weight_sum, 1e-30);
    }
    return sum;
}

}  // namespace openpbr::host
