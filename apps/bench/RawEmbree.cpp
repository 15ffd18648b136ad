#include "RawEmbree.hpp"

#include "BenchSupport.hpp"

#include <embree3/rtcore.h>

#include <atomic>
#include <cstring>

namespace spatter::bench {

namespace {

bool countBytes(void* user, ssize_t bytes, bool /*post*/) {
    static_cast<std::atomic<int64_t>*>(user)->fetch_add(int64_t(bytes), std::memory_order_relaxed);
    return true;
}

struct UserData {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
};

void userBounds(const RTCBoundsFunctionArguments* args) {
    const auto* d = static_cast<const UserData*>(args->geometryUserPtr);
    const uint32_t* tri = &d->indices[size_t(args->primID) * 3];
    const glm::vec3 lo = glm::min(glm::min(d->positions[tri[0]], d->positions[tri[1]]), d->positions[tri[2]]);
    const glm::vec3 hi = glm::max(glm::max(d->positions[tri[0]], d->positions[tri[1]]), d->positions[tri[2]]);
    args->bounds_o->lower_x = lo.x;
    args->bounds_o->lower_y = lo.y;
    args->bounds_o->lower_z = lo.z;
    args->bounds_o->upper_x = hi.x;
    args->bounds_o->upper_y = hi.y;
    args->bounds_o->upper_z = hi.z;
}

} // namespace

struct RawEmbree::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::atomic<int64_t> bytes{0};
    int64_t bytesAfterBuild = 0;
    double seconds = 0.0;
    UserData user;
    std::vector<RTCRayHit> single;
    std::vector<RTCRayHit16> packets;
    std::vector<int> packetLanes; // active lanes of each packet

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

RawEmbree::RawEmbree(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
RawEmbree::RawEmbree(RawEmbree&&) noexcept = default;
RawEmbree& RawEmbree::operator=(RawEmbree&&) noexcept = default;
RawEmbree::~RawEmbree() = default;

Result<RawEmbree> RawEmbree::build(const Mesh& mesh, RawGeometry geometry, const std::string& deviceConfig) {
    auto impl = std::make_unique<Impl>();
    impl->device = rtcNewDevice(deviceConfig.empty() ? nullptr : deviceConfig.c_str());
    if (!impl->device)
        return fail("raw Embree: cannot create a device with configuration \"" + deviceConfig + "\"");
    rtcSetDeviceMemoryMonitorFunction(impl->device, countBytes, &impl->bytes);
    impl->scene = rtcNewScene(impl->device);
    rtcSetSceneFlags(impl->scene, RTC_SCENE_FLAG_ROBUST);
    const size_t triangles = mesh.triangleCount();
    RTCGeometry g;
    if (geometry == RawGeometry::Triangles) {
        g = rtcNewGeometry(impl->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), mesh.positions.size()));
        auto* t = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangles));
        if (!v || !t) {
            rtcReleaseGeometry(g);
            return fail("raw Embree: cannot allocate the geometry buffers");
        }
        std::memcpy(v, mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
        std::memcpy(t, mesh.indices.data(), triangles * 3 * sizeof(uint32_t));
    } else {
        impl->user.positions = mesh.positions;
        impl->user.indices.assign(mesh.indices.begin(), mesh.indices.begin() + std::ptrdiff_t(triangles * 3));
        g = rtcNewGeometry(impl->device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(g, unsigned(triangles));
        rtcSetGeometryUserData(g, &impl->user);
        rtcSetGeometryBoundsFunction(g, userBounds, nullptr);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(impl->scene, g);
    rtcReleaseGeometry(g);
    const double start = now();
    rtcCommitScene(impl->scene);
    impl->seconds = now() - start;
    if (rtcGetDeviceError(impl->device) != RTC_ERROR_NONE) return fail("raw Embree: the scene did not build");
    impl->bytesAfterBuild = impl->bytes.load();
    return RawEmbree(std::move(impl));
}

size_t RawEmbree::deviceBytes() const {
    return size_t(std::max<int64_t>(0, impl_->bytesAfterBuild));
}

double RawEmbree::buildSeconds() const {
    return impl_->seconds;
}

void RawEmbree::prepare(const std::vector<Ray>& rays) {
    impl_->single.assign(rays.size(), RTCRayHit{});
    impl_->packets.assign((rays.size() + 15) / 16, RTCRayHit16{});
    impl_->packetLanes.assign(impl_->packets.size(), 0);
    for (size_t i = 0; i < rays.size(); ++i) {
        const glm::dvec3 d = glm::normalize(rays[i].direction);
        RTCRayHit& r = impl_->single[i];
        r.ray.org_x = float(rays[i].origin.x);
        r.ray.org_y = float(rays[i].origin.y);
        r.ray.org_z = float(rays[i].origin.z);
        r.ray.dir_x = float(d.x);
        r.ray.dir_y = float(d.y);
        r.ray.dir_z = float(d.z);
        r.ray.tnear = 0.0f;
        r.ray.tfar = std::numeric_limits<float>::infinity();
        r.ray.mask = 0xFFFFFFFFu;
        r.ray.id = unsigned(i);
        r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        r.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        RTCRayHit16& p = impl_->packets[i / 16];
        const size_t k = i % 16;
        p.ray.org_x[k] = r.ray.org_x;
        p.ray.org_y[k] = r.ray.org_y;
        p.ray.org_z[k] = r.ray.org_z;
        p.ray.dir_x[k] = r.ray.dir_x;
        p.ray.dir_y[k] = r.ray.dir_y;
        p.ray.dir_z[k] = r.ray.dir_z;
        p.ray.tnear[k] = 0.0f;
        p.ray.tfar[k] = r.ray.tfar;
        p.ray.mask[k] = 0xFFFFFFFFu;
        p.ray.id[k] = unsigned(i);
        p.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        p.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        impl_->packetLanes[i / 16] = int(k + 1);
    }
}

size_t RawEmbree::traceSingle() const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    size_t hits = 0;
    for (const RTCRayHit& prepared : impl_->single) {
        RTCRayHit rh = prepared;
        rtcIntersect1(impl_->scene, &ctx, &rh);
        hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    return hits;
}

size_t RawEmbree::tracePackets() const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    size_t hits = 0;
    alignas(64) int valid[16];
    for (size_t p = 0; p < impl_->packets.size(); ++p) {
        const int lanes = impl_->packetLanes[p];
        for (int k = 0; k < 16; ++k)
            valid[k] = k < lanes ? -1 : 0;
        RTCRayHit16 rh = impl_->packets[p];
        rtcIntersect16(valid, impl_->scene, &ctx, &rh);
        for (int k = 0; k < lanes; ++k)
            hits += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    }
    return hits;
}

} // namespace spatter::bench
