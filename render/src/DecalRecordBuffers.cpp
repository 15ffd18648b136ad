#include "DecalRecordBuffers.hpp"

#include "SphereCull.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace spatter::render_detail {

namespace {

// The high half of the bits of a float at least `radius`: the next such value up unless the low half
// is zero. Past the largest float it is infinite, a sphere no plane culls; 0 (not drawable) unless
// `radius` is positive, so that the sign bit stays free (kBoundsWideObject).
uint32_t radiusBits(double radius) {
    if (!(radius > 0.0)) return 0u;
    float f = float(radius);
    if (double(f) < radius) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    uint32_t bits = 0;
    std::memcpy(&bits, &f, sizeof bits);
    if ((bits & 0xffffu) != 0u) bits += 0x10000u;
    return bits & 0xffff0000u;
}

template <typename T, typename F> std::vector<T> parts(const std::vector<DecalRecordGpu>& records, F part) {
    std::vector<T> out;
    out.reserve(records.size());
    for (const DecalRecordGpu& r : records)
        out.push_back(part(r));
    return out;
}

template <typename T> void storeExactly(GlBuffer& buffer, size_t& capacity, const std::vector<T>& items) {
    buffer = createBuffer();
    capacity = items.size() * sizeof(T);
    glNamedBufferStorage(buffer.get(), GLsizeiptr(capacity), items.data(), 0);
}

// The object index in 24 bits: past them, their largest value, which names no object
// (kMaxProjectorObjects).
uint32_t objectField(const DecalRecordGpu& r) {
    return std::min(r.info.x, kMaxProjectorObjects);
}

} // namespace

DecalBoundsGpu recordBounds(const DecalRecordGpu& r) {
    const bool drawable = r.centerDepth.w > 0.0f;
    const uint32_t object = objectField(r);
    return {glm::vec3(r.centerDepth), (drawable ? radiusBits(recordRadius(r)) : 0u) | (object & 0xffffu) |
                                          (object > 0xffffu ? kBoundsWideObject : 0u)};
}

DecalBodyGpu recordBody(const DecalRecordGpu& r) {
    const uint32_t look = (r.info.y & 0xff00ffffu) | (objectField(r) >> 16) << 16;
    return {{r.frame.x, r.frame.y}, {r.halfSize.x, r.halfSize.y}, r.centerDepth.w, look, r.info.z};
}

void DecalRecordBuffers::reserve(size_t count, size_t keep) {
    growBuffer(bounds_, boundsCapacity_, count * sizeof(DecalBoundsGpu), 64 * sizeof(DecalBoundsGpu),
               keep * sizeof(DecalBoundsGpu));
    growBuffer(bodies_, bodiesCapacity_, count * sizeof(DecalBodyGpu), 64 * sizeof(DecalBodyGpu),
               keep * sizeof(DecalBodyGpu));
}

size_t DecalRecordBuffers::upload(size_t begin, const std::vector<DecalRecordGpu>& records) {
    const std::vector<DecalBoundsGpu> bounds = parts<DecalBoundsGpu>(records, recordBounds);
    const std::vector<DecalBodyGpu> bodies = parts<DecalBodyGpu>(records, recordBody);
    glNamedBufferSubData(bounds_.get(), GLintptr(begin * sizeof(DecalBoundsGpu)),
                         GLsizeiptr(bounds.size() * sizeof(DecalBoundsGpu)), bounds.data());
    glNamedBufferSubData(bodies_.get(), GLintptr(begin * sizeof(DecalBodyGpu)),
                         GLsizeiptr(bodies.size() * sizeof(DecalBodyGpu)), bodies.data());
    return records.size() * (sizeof(DecalBoundsGpu) + sizeof(DecalBodyGpu));
}

void DecalRecordBuffers::assign(const std::vector<DecalRecordGpu>& records) {
    static const std::vector<DecalRecordGpu> kNoDecal(1); // a buffer is never empty
    const std::vector<DecalRecordGpu>& some = records.empty() ? kNoDecal : records;
    storeExactly(bounds_, boundsCapacity_, parts<DecalBoundsGpu>(some, recordBounds));
    storeExactly(bodies_, bodiesCapacity_, parts<DecalBodyGpu>(some, recordBody));
}

void bindDecalRecords(GLuint bounds, GLuint bodies) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDecalBoundsBuffer, bounds);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDecalBuffer, bodies);
}

} // namespace spatter::render_detail
