// random.h - the host's one 64-bit mixer: SplitMix64 (Steele, Lea & Flood 2014, "Fast
// splittable pseudorandom number generators", OOPSLA). Counter-based streams (a seed and an
// index mixed into one value) keep every check, study and table generator reproducible whatever
// the thread partition. Header-only; includes nothing from host/.
#pragma once

#include <cstdint>

namespace openpbr::host {

// The golden-ratio increment of SplitMix64: 2^64 / phi, rounded to odd.
constexpr std::uint64_t splitmix64_increment = 0x9e3779b97f4a7c15ull;

// SplitMix64's output function (variant 13 of Stafford's mixers): a bijection of 64-bit values
// that spreads every input bit over the output, e.g. 0 -> 0, 1 -> 0x5692161d100b05e5.
constexpr std::uint64_t mix64_finalize(std::uint64_t x)
{
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// One SplitMix64 step as a pure function: the output of a generator whose state was x, e.g.
// splitmix64(0) = 0xe220a8397b1dcdaf (the first output of SplitMix64 seeded with 0).
constexpr std::uint64_t splitmix64(const std::uint64_t x) { return mix64_finalize(x + splitmix64_increment); }

// The top 24 bits of a 64-bit value as a float in [0, 1): every value exact, strictly below 1.
constexpr float unit_float_from_bits(const std::uint64_t bits) { return float(bits >> 40) * (1.0f / 16777216.0f); }

// The top 53 bits as a double in [0, 1).
constexpr double unit_double_from_bits(const std::uint64_t bits) { return double(bits >> 11) * (1.0 / 9007199254740992.0); }

// The SplitMix64 generator: each call advances the state by the increment and mixes it.
struct SplitMix64
{
    std::uint64_t state = 0;

    std::uint64_t next_bits()
    {
        state += splitmix64_increment;
        return mix64_finalize(state);
    }
    double next_double() { return unit_double_from_bits(next_bits()); }
};

}  // namespace openpbr::host
