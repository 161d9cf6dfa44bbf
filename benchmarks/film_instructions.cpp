// film_instructions: a fixed number of thin-film evaluations (openpbr_thin_film_model_bases, the
// call every filmed lobe makes), for instruction counts under callgrind
// (benchmarks/count_film_instructions.sh): a film of IOR 1.4 and 0.5 um under an outside medium
// of the given IOR, over a dielectric base of IOR 1.5 and a metal of reflectance 0.8 (edge tint
// 1, openpbr_gulbrandsen_n / _k), at the microfacet cosines sqrt((i + 0.5) / 256), i = 0..255
// (cosine-weighted, as the benchmark views of benchmark_instructions are).
//
// Usage: film_instructions <outside_ior> <both|dielectric|metal> <calls>
//   e.g. film_instructions 1.3 both 1024
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/math/openpbr_thin_film.h"

int main(int argc, char** argv)
{
    using namespace openpbr;
    const std::string bases = argc == 4 ? argv[2] : "";
    if (argc != 4 || (bases != "both" && bases != "dielectric" && bases != "metal"))
    {
        std::fprintf(stderr, "usage: %s <outside_ior> <both|dielectric|metal> <calls>\n", argv[0]);
        return 2;
    }
    char* end = nullptr;
    const float outside_ior = std::strtof(argv[1], &end);
    const long calls = std::strtol(argv[3], nullptr, 10);
    if (end == argv[1] || !(outside_ior >= 1.0f) || calls < 0)
    {
        std::fprintf(stderr, "the outside IOR must be at least 1 and the calls a non-negative count\n");
        return 2;
    }
    const bool with_dielectric = bases != "metal";
    const bool with_conductor = bases != "dielectric";
    const glm::vec3 reflectance(0.8f);
    const glm::vec3 n = openpbr_gulbrandsen_n(reflectance, glm::vec3(1.0f));
    const glm::vec3 k = openpbr_gulbrandsen_k(reflectance, n);
    // The results feed a volatile sum so the calls cannot be optimized away; the thickness is
    // read through it too, so nothing is folded into constants.
    volatile float sink = 0.0f;
    volatile float thickness_um = 0.5f;
    for (long call = 0; call < calls; ++call)
    {
        const float cos_theta = std::sqrt((float(call & 255) + 0.5f) / 256.0f);
        const OpenPBR_ThinFilmInputs inputs = openpbr_thin_film_inputs(cos_theta, outside_ior, 1.4f, thickness_um);
        const OpenPBR_ThinFilmBasePair pair =
            openpbr_thin_film_model_bases(inputs, with_dielectric, 1.5f, with_conductor, n, k);
        sink = sink + pair.dielectric.x + pair.conductor.y;
    }
    return 0;
}
