#pragma once
// Rng: a small seeded generator (PCG32, O'Neill 2014) whose output is the same on every platform,
// so the same seed gives bit-identical decals and scenes.

#include <cstdint>

namespace spatter {

class Rng {
public:
    explicit Rng(uint64_t seed = 0x853c49e6748fea9bULL, uint64_t stream = 0xda3e39cb94b95bdbULL) {
        inc_ = (stream << 1u) | 1u;
        next();
        state_ += seed;
        next();
    }
    // The generator as it stands: `state` and the odd `increment` (twice the stream, plus one), which
    // fromState() takes back. A generator restored from them continues with the same numbers.
    uint64_t state() const { return state_; }
    uint64_t increment() const { return inc_; }
    // The generator with `state` and `increment` (forced odd, as every increment of PCG32 is).
    static Rng fromState(uint64_t state, uint64_t increment) {
        Rng r;
        r.state_ = state;
        r.inc_ = increment | 1u;
        return r;
    }

    // Uniform 32-bit value.
    uint32_t next() {
        uint64_t old = state_;
        state_ = old * 6364136223846793005ULL + inc_;
        uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }
    // Uniform in [0, 1).
    float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }
    // Uniform in [lo, hi).
    float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
    // Uniform integer in [0, n); n > 0.
    uint32_t below(uint32_t n) { return uint32_t((uint64_t(next()) * n) >> 32); }

private:
    uint64_t state_ = 0;
    uint64_t inc_ = 0;
};

} // namespace spatter
