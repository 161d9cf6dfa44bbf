// thin_film_regression_cases.h - the cases of the thin film's regression table
// (tests/data/thin_film_regression_<working space>.f32): one film evaluation per case, over the axes the film's
// cost work was held to: thickness 0-3 um, film IOR 1-3, view cosine 0-1 (more of it near
// grazing and near the film's critical cosine), outside IOR 1, 1.3 or 1.6, path spread 0 or
// 0.03 um, a dielectric base of IOR 1.5 or 2.4, a copper-like or a white metal, and both bases,
// the dielectric alone or the metal alone. The evanescent film (outside IOR above the film's,
// past its critical cosine) is among them.
//
// The table holds what slang/math/openpbr_thin_film.h computed for these cases, six floats per
// case (the dielectric's RGB, then the metal's; 0 for a base not evaluated), float32
// little-endian. tests/bsdf/test_thin_film_regression.cpp holds today's film to it; the program
// tests/bsdf/thin_film_regression_table.cpp writes it from whichever headers it is compiled
// with (its header says how the shipped table was made).
//
// Header-only; needs only the thin film header (which exists with the same public functions in
// the commit the table was made from) and GLM.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/math/openpbr_thin_film.h"

namespace openpbr::thin_film_regression {

// How many cases the table holds, e.g. 4096: 96 KiB of floats.
constexpr int case_count = 4096;
constexpr int floats_per_case = 6;

struct Case
{
    float cos_theta;
    float outside_ior;
    float film_ior;
    float thickness_um;
    float path_spread_um;
    bool with_dielectric;
    float dielectric_ior;
    bool with_conductor;
    bool white_metal;  // false: the copper-like metal
};

// SplitMix64 over the case index and a draw number: the cases do not depend on anything else.
inline float draw(int case_index, int draw_index)
{
    std::uint64_t x = std::uint64_t(case_index) * 64u + std::uint64_t(draw_index) + 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    x ^= x >> 31;
    return float(x >> 40) * (1.0f / 16777216.0f);  // [0, 1)
}

inline Case make_case(int index)
{
    static const float outside_iors[3] = {1.0f, 1.3f, 1.6f};
    Case c;
    c.outside_ior = outside_iors[int(draw(index, 0) * 3.0f)];
    c.film_ior = 1.0f + 2.0f * draw(index, 1);
    c.thickness_um = draw(index, 2) < 0.05f ? 0.0f : 3.0f * draw(index, 3);
    c.path_spread_um = draw(index, 4) < 0.5f ? 0.0f : 0.03f;
    const int bases = int(draw(index, 5) * 3.0f);  // 0 both, 1 the dielectric alone, 2 the metal alone
    c.with_dielectric = bases != 2;
    c.with_conductor = bases != 1;
    c.dielectric_ior = draw(index, 6) < 0.5f ? 1.5f : 2.4f;
    c.white_metal = draw(index, 7) < 0.5f;
    // The view: uniform, near grazing, or within 0.05 of the film's critical cosine
    // sqrt(1 - (n_f / n_o)^2) where the film has one (else uniform).
    const float kind = draw(index, 8);
    const float u = draw(index, 9);
    const float film_ratio = c.film_ior / c.outside_ior;
    if (kind < 0.2f)
    {
        c.cos_theta = 0.1f * u;
    }
    else if (kind < 0.4f && film_ratio < 1.0f)
    {
        c.cos_theta = glm::clamp(std::sqrt(1.0f - film_ratio * film_ratio) + 0.1f * (u - 0.5f), 0.0f, 1.0f);
    }
    else
    {
        c.cos_theta = u;
    }
    return c;
}

// The metals: copper-like (n, k per RGB channel) and white (reflectance 0.9999, edge tint 1,
// through openpbr_gulbrandsen_n / _k).
inline void metal(bool white, glm::vec3& n, glm::vec3& k)
{
    if (white)
    {
        n = openpbr::openpbr_gulbrandsen_n(glm::vec3(0.9999f), glm::vec3(1.0f));
        k = openpbr::openpbr_gulbrandsen_k(glm::vec3(0.9999f), n);
        return;
    }
    n = glm::vec3(0.27105f, 0.67693f, 1.31640f);
    k = glm::vec3(3.60920f, 2.62480f, 2.29210f);
}

// The film's six values for one case: the dielectric's RGB, then the metal's.
inline void evaluate(const Case& c, float* values)
{
    glm::vec3 n;
    glm::vec3 k;
    metal(c.white_metal, n, k);
    openpbr::OpenPBR_ThinFilmInputs inputs =
        openpbr::openpbr_thin_film_inputs(c.cos_theta, c.outside_ior, c.film_ior, c.thickness_um);
    inputs.optical_path_spread_um = c.path_spread_um;
    const openpbr::OpenPBR_ThinFilmBasePair pair =
        openpbr::openpbr_thin_film_fresnel_bases(inputs, c.with_dielectric, c.dielectric_ior, c.with_conductor, n, k);
    for (int channel = 0; channel < 3; ++channel)
    {
        values[channel] = pair.dielectric[channel];
        values[3 + channel] = pair.conductor[channel];
    }
}

// Every case's six values, case after case.
inline std::vector<float> evaluate_all()
{
    std::vector<float> values(std::size_t(case_count) * floats_per_case);
    for (int index = 0; index < case_count; ++index)
    {
        evaluate(make_case(index), &values[std::size_t(index) * floats_per_case]);
    }
    return values;
}

}  // namespace openpbr::thin_film_regression
