// The fast-math hooks of slang/math/openpbr_math.h, compiled on in their own namespace
// (OPENPBR_CPP_VARIANT_NAMESPACE), stay within their stated error: openpbr_rsqrt <= 1.8e-3
// relative (Lomont 2003 with one Newton step), openpbr_sqrt and openpbr_normalize the same,
// and infinity / zero keep their meaning.
#define OPENPBR_CPP_VARIANT_NAMESPACE fast_math_test
#define OPENPBR_FAST_RCP_SQRT 1
#define OPENPBR_FAST_SQRT 1
#define OPENPBR_FAST_NORMALIZE 1
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/math/openpbr_math.h"

namespace {

namespace fast = openpbr::fast_math_test;

constexpr double stated_relative_error = 1.8e-3;

class FastMathHooks : public testing::TestWithParam<int>
{
};

// One decade of arguments per parameter, 1e-30 to 1e30.
TEST_P(FastMathHooks, StayWithinTheStatedError)
{
    const int decade = GetParam();
    for (int step = 0; step < 1000; ++step)
    {
        const double x = std::pow(10.0, decade + step / 1000.0);
        const float xf = float(x);
        const double exact_rsqrt = 1.0 / std::sqrt(double(xf));
        EXPECT_NEAR(fast::openpbr_rsqrt(xf) / exact_rsqrt, 1.0, stated_relative_error) << x;
        EXPECT_NEAR(fast::openpbr_sqrt(xf) / std::sqrt(double(xf)), 1.0, stated_relative_error) << x;
        const glm::vec3 v(xf, 0.5f * xf, -0.25f * xf);
        if (std::isfinite(glm::dot(v, v)) && glm::dot(v, v) > 1e-36f)
        {
            EXPECT_NEAR(glm::length(fast::openpbr_normalize(v)), 1.0, stated_relative_error) << x;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Decades, FastMathHooks, testing::Range(-30, 30, 3), [](const testing::TestParamInfo<int>& info) {
    return "decade_" + std::string(info.param < 0 ? "m" : "") + std::to_string(std::abs(info.param));
});

TEST(FastMathHooksEdges, ZeroAndInfinityKeepTheirMeaning)
{
    EXPECT_EQ(fast::openpbr_sqrt(0.0f), 0.0f);
    EXPECT_EQ(fast::openpbr_sqrt(-1.0f), 0.0f);
    EXPECT_EQ(fast::openpbr_sqrt(std::numeric_limits<float>::infinity()), std::numeric_limits<float>::infinity());
    EXPECT_EQ(fast::openpbr_safe_normalize(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f)), glm::vec3(0.0f, 0.0f, 1.0f));
}

}  // namespace
