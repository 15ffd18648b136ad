#include "SaveBytes.hpp"

namespace spatter::save {

namespace {

using Tables = std::array<std::array<uint32_t, 256>, 8>;

// tables[0] the byte-wise table; tables[k][b] the CRC of byte b followed by k zero bytes.
Tables makeTables() {
    Tables t{};
    for (uint32_t b = 0; b < 256; ++b) {
        uint32_t c = b;
        for (int k = 0; k < 8; ++k)
            c = (c & 1u) ? (c >> 1) ^ 0xEDB88320u : c >> 1;
        t[0][b] = c;
    }
    for (uint32_t b = 0; b < 256; ++b)
        for (size_t k = 1; k < 8; ++k)
            t[k][b] = (t[k - 1][b] >> 8) ^ t[0][t[k - 1][b] & 0xFFu];
    return t;
}

const Tables& tables() {
    static const Tables t = makeTables();
    return t;
}

} // namespace

void Crc32::update(const uint8_t* p, size_t n) {
    const Tables& t = tables();
    uint32_t c = crc_;
    for (; n >= 8; n -= 8, p += 8) {
        const uint32_t lo = c ^ loadU32(p);
        const uint32_t hi = loadU32(p + 4);
        c = t[7][lo & 0xFFu] ^ t[6][(lo >> 8) & 0xFFu] ^ t[5][(lo >> 16) & 0xFFu] ^ t[4][lo >> 24] ^
            t[3][hi & 0xFFu] ^ t[2][(hi >> 8) & 0xFFu] ^ t[1][(hi >> 16) & 0xFFu] ^ t[0][hi >> 24];
    }
    for (; n > 0; --n, ++p)
        c = (c >> 8) ^ t[0][(c ^ *p) & 0xFFu];
    crc_ = c;
}

} // namespace spatter::save
