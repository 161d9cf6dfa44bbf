// The polynomial helpers of slang/math/openpbr_math.h against double-precision libm, over their
// whole domain and at its ends (where the series are evaluated furthest from their centre).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/math/openpbr_math.h"

namespace {

// Largest error over 2^20 + 1 evenly spaced t in [0, 1], ends included: measured 1.5e-7 (sine)
// and 1.7e-7 (cosine; float rounding of the Horner steps, the series' truncation being 6e-8),
// bound 3e-7; |sin^2 + cos^2 - 1| measured 3.4e-7.
TEST(SinCosPi, MatchesDoublePrecisionOverHalfATurn)
{
    constexpr int steps = 1 << 20;
    double largest_sine_error = 0.0;
    double largest_cosine_error = 0.0;
    double largest_norm_error = 0.0;
    for (int step = 0; step <= steps; ++step)
    {
        const float t = float(step) / float(steps);
        const glm::vec2 value = openpbr::openpbr_sin_cos_pi(t);
        const double angle = 3.14159265358979323846 * double(t);
        largest_sine_error = std::max(largest_sine_error, std::abs(double(value.x) - std::sin(angle)));
        largest_cosine_error = std::max(largest_cosine_error, std::abs(double(value.y) - std::cos(angle)));
        largest_norm_error =
            std::max(largest_norm_error, std::abs(double(value.x) * value.x + double(value.y) * value.y - 1.0));
    }
    std::printf("[ info ] sin(pi t) error %.3g, cos(pi t) error %.3g, |sin^2 + cos^2 - 1| %.3g\n", largest_sine_error,
                largest_cosine_error, largest_norm_error);
    EXPECT_LE(largest_sine_error, 3e-7);
    EXPECT_LE(largest_cosine_error, 3e-7);
    // The film builds its phasor e^{i phi} from these; a unit phasor keeps the Airy series
    // energy-conserving. Bound: twice the component bound.
    EXPECT_LE(largest_norm_error, 6e-7);
}

// The ends and the middle: the film's 1 - phasor = 2 sin^2(phi / 2) must vanish at a zero phase
// (t = 0) without a negative value, and the half turn t = 1 gives sin 0, cos -1.
TEST(SinCosPi, EndsAndMiddle)
{
    const glm::vec2 at_zero = openpbr::openpbr_sin_cos_pi(0.0f);
    EXPECT_NEAR(at_zero.x, 0.0f, 3e-7f);
    EXPECT_NEAR(at_zero.y, 1.0f, 3e-7f);
    const glm::vec2 at_half = openpbr::openpbr_sin_cos_pi(0.5f);
    EXPECT_EQ(at_half.x, 1.0f);
    EXPECT_EQ(at_half.y, 0.0f);
    const glm::vec2 at_one = openpbr::openpbr_sin_cos_pi(1.0f);
    EXPECT_NEAR(at_one.x, 0.0f, 3e-7f);
    EXPECT_NEAR(at_one.y, -1.0f, 3e-7f);
}

// The four-lane forms the thin film's lobes use: openpbr_sin_pi / openpbr_cos_pi equal
// openpbr_sin_cos_pi lane by lane (the same polynomials).
TEST(SinCosPi, FourLanesEqualTheScalarForm)
{
    constexpr int steps = 1 << 12;
    for (int step = 0; step <= steps; step += 4)
    {
        const openpbr::vec4 t(float(step) / steps, float(step + 1) / steps, float(step + 2) / steps,
                              float(step + 3) / steps);
        const openpbr::vec4 sine = openpbr::openpbr_sin_pi(t);
        const openpbr::vec4 cosine = openpbr::openpbr_cos_pi(t);
        for (int lane = 0; lane < 4; ++lane)
        {
            const glm::vec2 scalar = openpbr::openpbr_sin_cos_pi(t[lane]);
            EXPECT_EQ(sine[lane], scalar.x) << t[lane];
            EXPECT_EQ(cosine[lane], scalar.y) << t[lane];
        }
    }
}

// The channel helpers the per-channel loops use (openpbr_dielectric_compensation, the dielectric
// lobe's eval and pdf): every channel read and written, the others untouched, and an infinite
// value kept in its own channel (a mask product would turn the others into NaN).
TEST(ChannelHelpers, ReadAndReplaceOneChannel)
{
    const glm::vec3 v(1.0f, 2.0f, 3.0f);
    const float infinity = std::numeric_limits<float>::infinity();
    for (int channel = 0; channel < 3; ++channel)
    {
        EXPECT_EQ(openpbr::openpbr_channel_of(v, channel), v[channel]);
        const glm::vec3 replaced = openpbr::openpbr_with_channel(v, channel, infinity);
        for (int other = 0; other < 3; ++other)
        {
            EXPECT_EQ(replaced[other], other == channel ? infinity : v[other]) << channel << " " << other;
        }
        EXPECT_EQ(openpbr::openpbr_channel_mask(channel)[channel], 1.0f);
        EXPECT_EQ(glm::dot(openpbr::openpbr_channel_mask(channel), glm::vec3(1.0f)), 1.0f);
    }
    const openpbr::vec4 four(1.0f, 2.0f, 3.0f, 4.0f);
    for (int channel = 0; channel < 4; ++channel)
    {
        const openpbr::vec4 replaced = openpbr::openpbr_with_channel(four, channel, infinity);
        for (int other = 0; other < 4; ++other)
        {
            EXPECT_EQ(replaced[other], other == channel ? infinity : four[other]) << channel << " " << other;
        }
    }
}

}  // namespace
