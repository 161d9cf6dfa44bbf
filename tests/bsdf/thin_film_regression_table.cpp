// thin_film_regression_table: writes the thin film's regression table
// (tests/bsdf/thin_film_regression_cases.h) from the headers it is compiled with.
//
//   thin_film_regression_table OUT.f32
//
// The shipped tables hold the film as it was computed one lane at a time, before the four-lane
// evaluation (commit 2878fe2, GLM without SIMD), one per working space (the spectral lobes'
// RGB weights depend on it, slang/openpbr_working_space.h):
//   git archive 2878fe2 slang interop host/support | tar -x -C /tmp/film_base
//   for space in ACESCG LIN_REC709; do
//     g++ -std=gnu++17 -O2 -DOPENPBR_WORKING_SPACE=OPENPBR_WORKING_SPACE_$space -I /tmp/film_base -I .
//         tests/bsdf/thin_film_regression_table.cpp /tmp/film_base/host/support/files.cpp -o /tmp/table
//     /tmp/table tests/data/thin_film_regression_<acescg|lin_rec709>.f32; done
// (the first -I wins, so the film and the support code are that commit's, the cases this one's).
// The build's own thin_film_regression_table writes today's film the same way, e.g. to see
// what an intended change of the film changes.
#include <cstdio>
#include <exception>

#include "host/support/files.h"
#include "tests/bsdf/thin_film_regression_cases.h"

int main(int argc, char** argv)
{
    if (argc != 2)
    {
        std::fprintf(stderr, "usage: %s OUT.f32\n", argv[0]);
        return 2;
    }
    try
    {
        openpbr::host::write_float32_file(argv[1], openpbr::thin_film_regression::evaluate_all());
    }
    catch (const std::exception& error)
    {
        std::fprintf(stderr, "%s\n", error.what());
        return 1;
    }
    return 0;
}
