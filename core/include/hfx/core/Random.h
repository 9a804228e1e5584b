#pragma once
// SplitMix64: a fully specified generator, so a seed gives the same numbers with every standard
// library and platform (std::uniform_real_distribution does not promise that).
//
// Owns its state. Thread: one generator per thread.

#include <cstdint>

namespace hfx {

class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
    std::uint64_t nextBits() {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1).
    double next() { return double(nextBits() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * next(); }

private:
    std::uint64_t state_;
};

} // namespace hfx
