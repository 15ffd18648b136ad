#pragma once
// SurfaceProbe: where lines meet the surface the host drew, found in its depth on the GPU
// (shaders/surface_probe.comp) and read back once the GPU has finished, without a stall unless asked
// (DecalProjector::findSurface). Each request has its results buffer and a fence; a request not taken
// is dropped once kMaxPending newer ones wait.

#include "GlObjects.hpp"

#include "spatter/core/Result.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace spatter::render_detail {

class SurfaceProbe {
public:
    static constexpr size_t kMaxPending = 16;

    // Queues the search along `lines` (world space) in `frame`'s depth and object IDs, read through
    // `sampler`; the frame has passed the projector's checks. Returns the request's number (from 1).
    // Fails, queuing nothing, on a line that is not finite or a program that does not build.
    Result<uint64_t> find(const HostFrame& frame, const std::vector<SurfaceLine>& lines, GLuint sampler);
    // The points of request `number`, in its lines' order, once the GPU has finished it (at once with
    // `wait`); empty while it has not, and for a request taken already, dropped or never made.
    std::optional<std::vector<SurfacePoint>> take(uint64_t number, bool wait);
    // Bytes of the buffers of the requests waiting.
    size_t gpuBytes() const;

private:
    struct SyncDeleter {
        void operator()(GLsync sync) const { glDeleteSync(sync); }
    };
    struct Request {
        uint64_t number = 0;
        size_t lines = 0;
        GlBuffer points;
        std::unique_ptr<std::remove_pointer_t<GLsync>, SyncDeleter> fence;
        glm::dmat4 viewToWorld{1.0};
        glm::dmat3 normalToWorld{1.0};
    };
    Status prepare(const HostFrame& frame);
    // Binds the frame's face normal texture and the matrix that takes its normals to view space.
    void bindFaceNormals(const HostFrame& frame, GLuint sampler);
    // Runs the search of the first `lines` lines of `gpuLines` (view space, two entries a line, at least
    // two entries) into the buffer `points`.
    void dispatch(const HostFrame& frame, const std::vector<glm::vec4>& gpuLines, size_t lines, GLuint points,
                  GLuint sampler);
    std::vector<SurfacePoint> read(const Request& r) const;

    // By variant bits: the host's depth conventions and the face normals' encoding (ProjectorVariants).
    std::map<uint32_t, GlProgram> programs_;
    GlBuffer frameBlock_; // the projector's frame block, with view space as its "world"
    std::deque<Request> pending_;
    uint64_t requests_ = 0;
};

} // namespace spatter::render_detail
