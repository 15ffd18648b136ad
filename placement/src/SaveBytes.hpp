#pragma once
// SaveBytes: the little-endian byte layer of decal saves (DecalSaveFormat.hpp): stores and loads of
// fixed-width values that compile to plain moves on little-endian machines and stay correct on
// others, a writer that appends to a byte vector, a bounds-checked reader, and CRC-32.

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace spatter::save {

inline void storeU16(uint8_t* p, uint16_t v) {
    p[0] = uint8_t(v);
    p[1] = uint8_t(v >> 8);
}
inline void storeU32(uint8_t* p, uint32_t v) {
    for (int i = 0; i < 4; ++i)
        p[i] = uint8_t(v >> (8 * i));
}
inline void storeU64(uint8_t* p, uint64_t v) {
    for (int i = 0; i < 8; ++i)
        p[i] = uint8_t(v >> (8 * i));
}
inline void storeF32(uint8_t* p, float v) {
    uint32_t u;
    std::memcpy(&u, &v, 4);
    storeU32(p, u);
}
inline void storeF64(uint8_t* p, double v) {
    uint64_t u;
    std::memcpy(&u, &v, 8);
    storeU64(p, u);
}

inline uint16_t loadU16(const uint8_t* p) {
    return uint16_t(p[0] | (p[1] << 8));
}
inline uint32_t loadU32(const uint8_t* p) {
    uint32_t v = 0;
    for (int i = 3; i >= 0; --i)
        v = (v << 8) | p[i];
    return v;
}
inline uint64_t loadU64(const uint8_t* p) {
    uint64_t v = 0;
    for (int i = 7; i >= 0; --i)
        v = (v << 8) | p[i];
    return v;
}
inline float loadF32(const uint8_t* p) {
    const uint32_t u = loadU32(p);
    float v;
    std::memcpy(&v, &u, 4);
    return v;
}
inline double loadF64(const uint8_t* p) {
    const uint64_t u = loadU64(p);
    double v;
    std::memcpy(&v, &u, 8);
    return v;
}

// Appends to `out`.
class ByteWriter {
public:
    explicit ByteWriter(std::vector<uint8_t>& out) : out_(out) {}
    // `n` new bytes at the end, to be filled by the caller.
    uint8_t* grow(size_t n) {
        const size_t at = out_.size();
        out_.resize(at + n);
        return out_.data() + at;
    }
    void u8(uint8_t v) { out_.push_back(v); }
    void u16(uint16_t v) { storeU16(grow(2), v); }
    void u32(uint32_t v) { storeU32(grow(4), v); }
    void u64(uint64_t v) { storeU64(grow(8), v); }
    void f32(float v) { storeF32(grow(4), v); }
    void f64(double v) { storeF64(grow(8), v); }
    void text(const std::string& s) {
        u32(uint32_t(s.size()));
        std::memcpy(grow(s.size()), s.data(), s.size());
    }
    size_t size() const { return out_.size(); }
    uint8_t* at(size_t offset) { return out_.data() + offset; }

private:
    std::vector<uint8_t>& out_;
};

// Reads [data, data + size); every read checks the bytes left first.
class ByteReader {
public:
    ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
    size_t remaining() const { return size_ - pos_; }
    // The next `n` bytes, or nullptr (and nothing consumed) when fewer remain.
    const uint8_t* take(size_t n) {
        if (n > remaining()) return nullptr;
        const uint8_t* p = data_ + pos_;
        pos_ += n;
        return p;
    }
    bool u8(uint8_t& v) {
        return read(v, 1, [](const uint8_t* p) { return *p; });
    }
    bool u16(uint16_t& v) { return read(v, 2, loadU16); }
    bool u32(uint32_t& v) { return read(v, 4, loadU32); }
    bool u64(uint64_t& v) { return read(v, 8, loadU64); }
    bool f32(float& v) { return read(v, 4, loadF32); }
    bool f64(double& v) { return read(v, 8, loadF64); }
    // A string of u32 length and that many bytes; false when the bytes are not there.
    bool text(std::string& s) {
        uint32_t n = 0;
        const size_t start = pos_;
        if (!u32(n) || n > remaining()) {
            pos_ = start;
            return false;
        }
        s.assign(reinterpret_cast<const char*>(take(n)), n);
        return true;
    }

private:
    template <class T, class Load> bool read(T& v, size_t n, Load load) {
        const uint8_t* p = take(n);
        if (!p) return false;
        v = T(load(p));
        return true;
    }
    const uint8_t* data_;
    size_t size_;
    size_t pos_ = 0;
};

// CRC-32 (ISO-HDLC: reflected polynomial 0xEDB88320, initial and final value 0xFFFFFFFF, the
// checksum of zlib and PNG), eight bytes at a time (slicing-by-8).
class Crc32 {
public:
    void update(const uint8_t* p, size_t n);
    uint32_t value() const { return ~crc_; }

private:
    uint32_t crc_ = 0xFFFFFFFFu;
};

} // namespace spatter::save
