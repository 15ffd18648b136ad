#pragma once
// Opacity: how much of a decal shows, in [0, 1], kept in one byte: steps of 1/255, which is what an
// 8-bit render target resolves and finer than a fade of a few hundred frames steps. A Decal keeps
// the bytes a float would take for its projection axis (DecalProjection.hpp).
//
// It converts to and from float: `d.opacity = 0.5f` stores the nearest step (128 / 255), and
// `float(d.opacity)` reads it back. A value that is not finite stores 0; values outside [0, 1] are
// clamped. So every stored opacity is one a renderer can use.

#include <cmath>
#include <cstdint>

namespace spatter {

class Opacity {
public:
    constexpr Opacity() = default;
    Opacity(float value) : bits_(quantize(value)) {} // NOLINT: converts as a float field did
    operator float() const { return float(bits_) * (1.0f / 255.0f); }

    uint8_t bits() const { return bits_; }
    static Opacity fromBits(uint8_t bits) {
        Opacity o;
        o.bits_ = bits;
        return o;
    }

private:
    static uint8_t quantize(float v) {
        if (!std::isfinite(v) || !(v > 0.0f)) return 0;
        if (!(v < 1.0f)) return 255;
        return uint8_t(std::lround(v * 255.0f));
    }

    uint8_t bits_ = 255;
};

} // namespace spatter
