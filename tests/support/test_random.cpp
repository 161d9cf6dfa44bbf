// The host's one 64-bit mixer (host/support/random.h) against published SplitMix64 values
// (Steele, Lea & Flood 2014; the reference C code by Vigna): the generator seeded with 0 gives
// 0xe220a8397b1dcdaf, 0x6e789e6aa1b965f4, 0x06c45d188009454f first; the finalizer is a
// bijection that keeps 0 at 0.
#include <gtest/gtest.h>

#include "host/support/random.h"
#include "host/support/stopwatch.h"

namespace {

using namespace openpbr::host;

TEST(SplitMix64, FirstOutputsOfSeedZero)
{
    SplitMix64 generator{0};
    EXPECT_EQ(generator.next_bits(), 0xe220a8397b1dcdafull);
    EXPECT_EQ(generator.next_bits(), 0x6e789e6aa1b965f4ull);
    EXPECT_EQ(generator.next_bits(), 0x06c45d188009454full);
    EXPECT_EQ(splitmix64(0), 0xe220a8397b1dcdafull);
    EXPECT_EQ(splitmix64(splitmix64_increment), 0x6e789e6aa1b965f4ull);
    EXPECT_EQ(mix64_finalize(0), 0u);
}

TEST(SplitMix64, UnitValuesStayBelowOne)
{
    EXPECT_EQ(unit_float_from_bits(0), 0.0f);
    EXPECT_LT(unit_float_from_bits(~0ull), 1.0f);
    EXPECT_EQ(unit_float_from_bits(1ull << 63), 0.5f);
    EXPECT_LT(unit_double_from_bits(~0ull), 1.0);
    EXPECT_EQ(unit_double_from_bits(1ull << 63), 0.5);
}

TEST(Stopwatch, NeverRunsBackwards)
{
    const Stopwatch stopwatch;
    const double first = stopwatch.seconds();
    const double second = stopwatch.seconds();
    EXPECT_GE(first, 0.0);
    EXPECT_GE(second, first);
}

}  // namespace
