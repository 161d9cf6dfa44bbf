// The thin film against the values it had before its four-lane evaluation: the cases of
// tests/bsdf/thin_film_regression_cases.h (4,096 film evaluations: thickness 0-3 um, film IOR
// 1-3, outside IOR 1 / 1.3 / 1.6, path spread 0 / 0.03 um, dielectric bases 1.5 / 2.4, a
// copper-like and a white metal, the evanescent film among them) against the stored table of
// the working space this test is built for (tests/data/thin_film_regression_acescg.f32 or
// _lin_rec709.f32: the spectral lobes' RGB weights are per space), made from commit 2878fe2's
// headers (tests/bsdf/thin_film_regression_table.cpp says how).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "tests/bsdf/thin_film_regression_cases.h"

namespace {

namespace regression = openpbr::thin_film_regression;

// The stored table of this build's working space (float32 little-endian, as on every platform
// the tests run on), read here without the host library: a program's objects must all be
// compiled for one working space, and test_bsdf_lin_rec709 links only the header library.
std::vector<float> stored_table()
{
#if OPENPBR_WORKING_SPACE == OPENPBR_WORKING_SPACE_LIN_REC709
    const char* const path = OPENPBR_SOURCE_DIR "/tests/data/thin_film_regression_lin_rec709.f32";
#else
    const char* const path = OPENPBR_SOURCE_DIR "/tests/data/thin_film_regression_acescg.f32";
#endif
    std::ifstream file(path, std::ios::binary);
    std::vector<float> values(std::size_t(regression::case_count) * regression::floats_per_case);
    file.read(reinterpret_cast<char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
    if (!file || file.peek() != std::ifstream::traits_type::eof())
    {
        ADD_FAILURE() << path << ": not " << values.size() << " float32 values";
        return {};
    }
    return values;
}

// Every value within 1e-5 of the stored one: measured 9.5e-7 (ACEScg) and 3.6e-7 (Rec.709) with
// the four-lane evaluation, which reorders sums and drops harmonics only where they add less than
// 2e-6; 6.0e-8 (ACEScg) with the one-lane form (OPENPBR_FILM_FOUR_LANES=0, one_lane.* tests).
TEST(ThinFilmRegression, MatchesTheValuesBeforeTheFourLaneEvaluation)
{
    const std::vector<float> stored = stored_table();
    ASSERT_EQ(stored.size(), std::size_t(regression::case_count) * regression::floats_per_case);
    const std::vector<float> today = regression::evaluate_all();
    double largest = 0.0;
    int worst = 0;
    for (std::size_t index = 0; index < stored.size(); ++index)
    {
        ASSERT_TRUE(std::isfinite(today[index])) << "case " << index / regression::floats_per_case;
        const double difference = std::fabs(double(today[index]) - double(stored[index]));
        if (difference > largest)
        {
            largest = difference;
            worst = int(index);
        }
    }
    const regression::Case c = regression::make_case(worst / regression::floats_per_case);
    std::printf("[ info ] largest difference %.3g (case %d value %d: cos %.4f, n_o %.2f, n_f %.3f, d %.3f um)\n", largest,
                worst / regression::floats_per_case, worst % regression::floats_per_case, c.cos_theta, c.outside_ior,
                c.film_ior, c.thickness_um);
    EXPECT_LE(largest, 1e-5);
}

// The cases cover what they claim: both bases alone and together, the evanescent film, spread
// paths, grazing views and zero thickness, each in at least 100 cases (measured 1,353 / 1,324 /
// 1,419 by bases, 364 evanescent, 2,067 spread, 1,125 below cos 0.1, 191 of zero thickness).
TEST(ThinFilmRegression, CasesCoverTheAxes)
{
    int both = 0;
    int dielectric_alone = 0;
    int metal_alone = 0;
    int evanescent = 0;
    int spread = 0;
    int grazing = 0;
    int zero_thickness = 0;
    for (int index = 0; index < regression::case_count; ++index)
    {
        const regression::Case c = regression::make_case(index);
        both += c.with_dielectric && c.with_conductor ? 1 : 0;
        dielectric_alone += c.with_dielectric && !c.with_conductor ? 1 : 0;
        metal_alone += !c.with_dielectric && c.with_conductor ? 1 : 0;
        const float sine_squared = 1.0f - c.cos_theta * c.cos_theta;
        evanescent += c.outside_ior * c.outside_ior * sine_squared >= c.film_ior * c.film_ior ? 1 : 0;
        spread += c.path_spread_um > 0.0f ? 1 : 0;
        grazing += c.cos_theta < 0.1f ? 1 : 0;
        zero_thickness += c.thickness_um == 0.0f ? 1 : 0;
    }
    std::printf("[ info ] both %d, dielectric %d, metal %d, evanescent %d, spread %d, grazing %d, zero thickness %d\n", both,
                dielectric_alone, metal_alone, evanescent, spread, grazing, zero_thickness);
    for (const int count : {both, dielectric_alone, metal_alone, evanescent, spread, grazing, zero_thickness})
    {
        EXPECT_GE(count, 100);
    }
}

}  // namespace
