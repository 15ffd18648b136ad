#pragma once
// RawEmbree: a mesh traced with Embree directly (one triangle geometry, no spatter code between),
// the baseline that the placement benchmarks compare spawning with. Also measures how many bytes
// Embree allocates for a BVH (its device memory monitor).

#include "spatter/core/Mesh.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/placement/Ray.hpp"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace spatter::bench {

enum class RawGeometry {
    Triangles, // Embree's own triangles (RTC_GEOMETRY_TYPE_TRIANGLE)
    User,      // user geometry with one box per triangle, as CollisionWorld builds it (memory only)
};

class RawEmbree {
public:
    // Builds a ROBUST scene of `mesh` (static, medium build quality, as CollisionWorld's static
    // scene). User geometry can be measured but not traced. `deviceConfig` goes to rtcNewDevice.
    static Result<RawEmbree> build(const Mesh& mesh, RawGeometry geometry = RawGeometry::Triangles,
                                   const std::string& deviceConfig = "");

    RawEmbree(RawEmbree&&) noexcept;
    RawEmbree& operator=(RawEmbree&&) noexcept;
    ~RawEmbree();

    // Bytes Embree's device holds (allocations minus frees reported to its memory monitor) after the
    // build: the BVH and Embree's own copies, not the caller's vertex and index arrays.
    size_t deviceBytes() const;
    // Seconds rtcCommitScene took.
    double buildSeconds() const;

    // Converts `rays` into Embree's layouts, single rays and packets of 16 (rays taken in order;
    // the last packet is padded with inactive lanes). Directions are normalised in double.
    void prepare(const std::vector<Ray>& rays);
    // Traces every prepared ray with rtcIntersect1; returns the number of hits.
    size_t traceSingle() const;
    // Traces the prepared packets with rtcIntersect16; returns the number of hits.
    size_t tracePackets() const;

private:
    struct Impl;
    explicit RawEmbree(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

} // namespace spatter::bench
