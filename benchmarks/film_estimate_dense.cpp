// film_estimate_dense: the thin film's lobe-averaged reflectance estimate (openpbr_base_film_estimate)
// against the dense reference of docs/thin-film-estimate.md, over its three grids of 10,980 stacks.
//
// The reference averages over the visible normals of the GGX lobe (n x n nodes of the
// spherical-cap sampler, Dupuy & Benyoub 2023; weights the reflected fraction G2 / G1, Heitz 2014)
//   the dielectric's change F_film - F_plain (base IOR 1.5) and
//   the filmed F82 metal's factor (F0 = (1, 0.78, 0.34)),
// the two quantities the estimate returns. Stacks: outside IOR 1, 1.15, 1.3, 1.33, 1.4, 1.45,
// 1.565, 1.6, 1.7, 1.8; films of IOR 1.2, 1.4, 2 and 0.1-1.5 um; grid A roughness 0.1, 0.1158,
// 0.1316, 0.4, 0.8 and grid B 0.2, 0.25, 0.3, 0.35, 0.6 at view cos 1, 0.5, 0.3, 0.1; grid C
// roughness 0.2, 0.3, 0.4 at view cos 0.9 to 0.3. Printed per regime (no critical cosine in the
// stack, or past one): the stacks whose change is low (the layers below gain) by more than 0.01 /
// 0.005 and high by more than 0.01, the extremes, and the metal's factor off by more than 0.01.
//
// The estimate is the one these headers compile to: build the program with the estimate's
// settings to measure them, e.g. -DOPENPBR_FILM_ESTIMATE_PLAIN_SEGMENTS=1. The reference does not
// depend on them; it is cached in a file (the second argument, with its NODES) so a variant costs
// seconds.
//
// Usage: film_estimate_dense [NODES [CACHE]]   e.g. film_estimate_dense 128 /tmp/film-dense-128.bin
//   NODES: n of the n x n reference nodes per stack, e.g. 128 (the default; about 10 minutes on one core).
#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "host/studies/film_dense_reference.h"
#include "slang/openpbr.h"

namespace {

using namespace openpbr;

struct Stack
{
    float outside_ior;
    float film_ior;
    float thickness_um;
    float roughness;
    float view_cosine;
};

std::vector<Stack> stacks()
{
    const float outside_iors[] = {1.0f, 1.15f, 1.3f, 1.33f, 1.4f, 1.45f, 1.565f, 1.6f, 1.7f, 1.8f};
    const float film_iors[] = {1.2f, 1.4f, 2.0f};
    const float thicknesses[] = {0.1f, 0.3f, 0.6f, 0.9f, 1.2f, 1.5f};
    struct Grid
    {
        std::vector<float> roughness;
        std::vector<float> cosines;
    };
    const Grid grids[] = {{{0.1f, 0.1158f, 0.1316f, 0.4f, 0.8f}, {1.0f, 0.5f, 0.3f, 0.1f}},
                          {{0.2f, 0.25f, 0.3f, 0.35f, 0.6f}, {1.0f, 0.5f, 0.3f, 0.1f}},
                          {{0.2f, 0.3f, 0.4f}, {0.9f, 0.8f, 0.7f, 0.6f, 0.5f, 0.4f, 0.3f}}};
    std::vector<Stack> result;
    for (const Grid& grid : grids)
    {
        for (const float outside_ior : outside_iors)
        {
            for (const float film_ior : film_iors)
            {
                for (const float thickness : thicknesses)
                {
                    for (const float roughness : grid.roughness)
                    {
                        for (const float cosine : grid.cosines)
                        {
                            result.push_back({outside_ior, film_ior, thickness, roughness, cosine});
                        }
                    }
                }
            }
        }
    }
    return result;
}

// The stack's filmed bases (a dielectric of IOR 1.5 and the F82 metal) and its dense reference
// (host/studies/film_dense_reference.h, shared with the accuracy study's film-estimate family).
host::FilmedBases filmed_bases(const Stack& stack)
{
    return host::filmed_bases(stack.outside_ior, stack.film_ior, stack.thickness_um, 1.5f);
}

std::array<double, 6> dense_average(const Stack& stack, const int n)
{
    return host::dense_film_average(filmed_bases(stack), stack.roughness, stack.view_cosine, n);
}

std::vector<std::array<double, 6>> reference(const std::vector<Stack>& all, const int n, const std::string& cache)
{
    std::vector<std::array<double, 6>> values(all.size());
    if (!cache.empty())
    {
        // The cache holds n, then the values; one of another n or size is computed again.
        if (FILE* file = std::fopen(cache.c_str(), "rb"))
        {
            int cached_n = 0;
            const bool same_n = std::fread(&cached_n, sizeof(cached_n), 1, file) == 1 && cached_n == n;
            const std::size_t read = same_n ? std::fread(values.data(), sizeof(values[0]), values.size(), file) : 0;
            std::fclose(file);
            if (read == values.size())
            {
                return values;
            }
        }
    }
    for (std::size_t k = 0; k < all.size(); ++k)
    {
        values[k] = dense_average(all[k], n);
    }
    if (!cache.empty())
    {
        FILE* file = std::fopen(cache.c_str(), "wb");
        if (file == nullptr || std::fwrite(&n, sizeof(n), 1, file) != 1 ||
            std::fwrite(values.data(), sizeof(values[0]), values.size(), file) != values.size())
        {
            std::fprintf(stderr, "film_estimate_dense: could not write the cache %s\n", cache.c_str());
        }
        if (file != nullptr)
        {
            std::fclose(file);
        }
    }
    return values;
}

struct Tally
{
    int stacks = 0;
    int low_large = 0;    // change low by more than 0.01
    int low_small = 0;    // low by more than 0.005
    int high_large = 0;   // high by more than 0.01
    int metal_large = 0;  // metal's factor off by more than 0.01
    double lowest = 0.0;
    double highest = 0.0;
    double metal_largest = 0.0;
    Stack lowest_stack{};
    Stack highest_stack{};
};

void print_stack(const char* what, const double error, const Stack& stack)
{
    std::printf("  %s %+.4f: outside IOR %g, film %g of %g um, roughness %g, view cos %g\n", what, error,
                double(stack.outside_ior), double(stack.film_ior), double(stack.thickness_um), double(stack.roughness),
                double(stack.view_cosine));
}

void print(const char* name, const Tally& tally)
{
    std::printf("%s, %d stacks: change low by > 0.01 / > 0.005, high by > 0.01: %d / %d / %d (extremes %+.4f / %+.4f); "
                "metal off by > 0.01: %d (largest %.4f)\n",
                name, tally.stacks, tally.low_large, tally.low_small, tally.high_large, tally.lowest, tally.highest,
                tally.metal_large, tally.metal_largest);
    print_stack("lowest change", tally.lowest, tally.lowest_stack);
    print_stack("highest change", tally.highest, tally.highest_stack);
}

}  // namespace

int main(int argc, char** argv)
{
    const int n = argc > 1 ? std::atoi(argv[1]) : 128;
    if (n < 8 || n > 1024)
    {
        std::fprintf(stderr, "usage: %s [NODES (8-1024, e.g. 128) [CACHE]]\n", argv[0]);
        return 2;
    }
    const std::vector<Stack> all = stacks();
    const std::vector<std::array<double, 6>> dense = reference(all, n, argc > 2 ? argv[2] : "");
    Tally regimes[2];
    for (std::size_t k = 0; k < all.size(); ++k)
    {
        const Stack& stack = all[k];
        const host::FilmedBases bases = filmed_bases(stack);
        const OpenPBR_FresnelPair estimate =
            openpbr_base_film_estimate(bases.dielectric, true, bases.metal, true, host::film_view(stack.view_cosine),
                                       openpbr_ggx_alpha(stack.roughness, 0.0f));
        const bool critical = stack.outside_ior > stack.film_ior || stack.outside_ior > 1.5f;
        Tally& tally = regimes[critical ? 1 : 0];
        ++tally.stacks;
        double low = 0.0, high = 0.0, metal = 0.0;
        for (int c = 0; c < 3; ++c)
        {
            const double error = estimate.first[c] - dense[k][std::size_t(c)];
            low = std::min(low, error);
            high = std::max(high, error);
            metal = std::max(metal, std::abs(estimate.second[c] - dense[k][std::size_t(c) + 3]));
        }
        tally.low_large += low < -0.01 ? 1 : 0;
        tally.low_small += low < -0.005 ? 1 : 0;
        tally.high_large += high > 0.01 ? 1 : 0;
        tally.metal_large += metal > 0.01 ? 1 : 0;
        tally.lowest_stack = low < tally.lowest ? stack : tally.lowest_stack;
        tally.highest_stack = high > tally.highest ? stack : tally.highest_stack;
        tally.lowest = std::min(tally.lowest, low);
        tally.highest = std::max(tally.highest, high);
        tally.metal_largest = std::max(tally.metal_largest, metal);
    }
    std::printf("film estimate against the dense reference (%d x %d visible normals per stack)\n", n, n);
    print("no critical cosine", regimes[0]);
    print("past a critical cosine", regimes[1]);
    return 0;
}
