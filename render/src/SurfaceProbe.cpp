#include "SurfaceProbe.hpp"

#include "ProjectorLayouts.hpp"
#include "ProjectorVariants.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

namespace spatter::render_detail {

namespace {

constexpr GLuint kLinesBuffer = 5, kPointsBuffer = 6; // surface_probe.comp's storage bindings
constexpr GLuint kDepthUnit = 0, kIdUnit = 2, kFaceUnit = 3;
constexpr float kAnyObject = 256.0f; // a line's ID that any object's surface matches (surface_probe.comp)

// The search's variant: the host's depth conventions and, where the frame has face normals, the
// encoding they share with its normals (the projector's convention bits, the face normal texture
// taking the normals' place; kVariantNoNormals without one).
uint32_t probeBits(const HostFrame& f) {
    HostFrame faces = f;
    faces.normals.texture = f.faceNormalTexture;
    return conventionBits(faces);
}

std::vector<std::string> probeDefines(uint32_t bits) {
    std::vector<std::string> defines = variantDefines(bits);
    if (!(bits & kVariantNoNormals)) defines.push_back("FACE_NORMALS");
    return defines;
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The frame block with view space as the projector's camera-relative world.
ProjectorFrameGpu viewSpaceFrame(const HostFrame& f) {
    ProjectorFrameGpu g{};
    g.viewProj = glm::mat4(f.projection);
    g.view = glm::mat4(1.0f);
    g.invView = glm::mat4(1.0f);
    g.invProjection = glm::mat4(glm::inverse(f.projection));
    g.viewport = glm::vec4(float(f.x), float(f.y), 1.0f / float(f.width), 1.0f / float(f.height));
    return g;
}

} // namespace

Status SurfaceProbe::prepare(const HostFrame& frame) {
    const uint32_t bits = probeBits(frame);
    if (!frameBlock_) {
        frameBlock_ = createBuffer();
        glNamedBufferStorage(frameBlock_.get(), sizeof(ProjectorFrameGpu), nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    if (programs_.count(bits)) return {};
    Result<GlProgram> p = projectorComputeProgram("surface_probe.comp", probeDefines(bits));
    if (!p) return fail(p.error());
    programs_.emplace(bits, std::move(p.value()));
    return {};
}

Result<uint64_t> SurfaceProbe::find(const HostFrame& frame, const std::vector<SurfaceLine>& lines,
                                    GLuint sampler) {
    if (lines.size() > kMaxSurfaceLines)
        return fail("projector: " + std::to_string(lines.size()) + " surface lines, more than the " +
                    std::to_string(kMaxSurfaceLines) + " one search takes");
    std::vector<glm::vec4> gpuLines;
    gpuLines.reserve(2 * lines.size() + 2);
    for (size_t i = 0; i < lines.size(); ++i) {
        const SurfaceLine& l = lines[i];
        if (!finite(l.from) || !finite(l.to))
            return fail("projector: surface line " + std::to_string(i) + " is not finite");
        glm::vec3 from(frame.view * glm::dvec4(l.from, 1.0)), to(frame.view * glm::dvec4(l.to, 1.0));
        if (!finite(glm::dvec3(from)) || !finite(glm::dvec3(to)))
            from = to = glm::vec3(0.0f); // past float's range: a point at the eye, which meets nothing
        gpuLines.emplace_back(from, l.anyObject ? kAnyObject : float(l.objectId));
        gpuLines.emplace_back(to, 0.0f);
    }
    if (Status s = prepare(frame); !s) return fail(s.error());
    gpuLines.resize(std::max<size_t>(gpuLines.size(), 2));
    Request r;
    r.number = ++requests_;
    r.lines = lines.size();
    r.points = createBuffer();
    glNamedBufferStorage(r.points.get(), GLsizeiptr(gpuLines.size() * sizeof(glm::vec4)), nullptr, 0);
    r.viewToWorld = glm::inverse(frame.view);
    r.normalToWorld = glm::transpose(glm::dmat3(frame.view)); // normals pull back by the transpose
    dispatch(frame, gpuLines, r.lines, r.points.get(), sampler);
    r.fence.reset(glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0));
    pending_.push_back(std::move(r));
    if (pending_.size() > kMaxPending) pending_.pop_front();
    return pending_.back().number;
}

void SurfaceProbe::bindFaceNormals(const HostFrame& frame, GLuint sampler) {
    glBindTextureUnit(kFaceUnit, frame.faceNormalTexture);
    glBindSampler(kFaceUnit, sampler);
    // Face normals decode to world space but for view-space encodings; the search runs in view space.
    const bool inView = frame.normals.encoding == NormalEncoding::ViewUnorm;
    const glm::mat3 faceToView = inView ? glm::mat3(1.0f) : glm::mat3(glm::dmat3(frame.view));
    glUniformMatrix3fv(4, 1, GL_FALSE, &faceToView[0][0]);
}

void SurfaceProbe::dispatch(const HostFrame& frame, const std::vector<glm::vec4>& gpuLines, size_t lines,
                            GLuint points, GLuint sampler) {
    const ProjectorFrameGpu block = viewSpaceFrame(frame);
    glNamedBufferSubData(frameBlock_.get(), 0, sizeof block, &block);
    GlBuffer lineBuffer = createBuffer(); // deleted once the dispatch is done with it
    glNamedBufferStorage(lineBuffer.get(), GLsizeiptr(gpuLines.size() * sizeof(glm::vec4)), gpuLines.data(),
                         0);
    glUseProgram(programs_.at(probeBits(frame)).get());
    glBindBufferBase(GL_UNIFORM_BUFFER, kProjectorFrameBlock, frameBlock_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLinesBuffer, lineBuffer.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPointsBuffer, points);
    glBindTextureUnit(kDepthUnit, frame.depth.texture);
    glBindSampler(kDepthUnit, sampler);
    glBindTextureUnit(kIdUnit, frame.objectIdTexture);
    glBindSampler(kIdUnit, sampler);
    if (frame.faceNormalTexture != 0) bindFaceNormals(frame, sampler);
    glUniform1ui(0, GLuint(lines));
    glUniform4i(1, frame.x, frame.y, frame.width, frame.height);
    glUniform1i(2, frame.objectIdTexture != 0 ? 1 : 0);
    // A pixel's height in view units at view z: the clip w there (z * P[2][3] + P[3][3]) over P[1][1],
    // times the 2 / height of a pixel in normalised device units.
    const double perW = 2.0 / (std::abs(frame.projection[1][1]) * double(frame.height));
    glUniform2f(3, float(frame.projection[2][3] * perW), float(frame.projection[3][3] * perW));
    glDispatchCompute(GLuint((lines + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

std::vector<SurfacePoint> SurfaceProbe::read(const Request& r) const {
    std::vector<glm::vec4> raw(2 * r.lines);
    if (!raw.empty())
        glGetNamedBufferSubData(r.points.get(), 0, GLsizeiptr(raw.size() * sizeof(glm::vec4)), raw.data());
    std::vector<SurfacePoint> out(r.lines);
    for (size_t i = 0; i < r.lines; ++i) {
        const glm::vec4 p = raw[2 * i], n = raw[2 * i + 1];
        const glm::dvec3 normal = r.normalToWorld * glm::dvec3(n);
        if (!(p.w > 0.5f) || !(glm::length(normal) > 0.0)) continue;
        out[i].found = true;
        out[i].point = glm::dvec3(r.viewToWorld * glm::dvec4(glm::dvec3(p), 1.0));
        out[i].normal = glm::normalize(normal);
        out[i].objectId = uint8_t(std::clamp(n.w, 0.0f, 255.0f));
    }
    return out;
}

std::optional<std::vector<SurfacePoint>> SurfaceProbe::take(uint64_t number, bool wait) {
    for (auto it = pending_.begin(); it != pending_.end(); ++it) {
        if (it->number != number) continue;
        const GLbitfield flush = wait ? GL_SYNC_FLUSH_COMMANDS_BIT : 0;
        constexpr GLuint64 kSecond = 1000000000ull;
        GLenum state = glClientWaitSync(it->fence.get(), flush, wait ? kSecond : 0);
        while (wait && state == GL_TIMEOUT_EXPIRED)
            state = glClientWaitSync(it->fence.get(), flush, kSecond);
        if (state != GL_ALREADY_SIGNALED && state != GL_CONDITION_SATISFIED) return std::nullopt;
        std::vector<SurfacePoint> points = read(*it);
        pending_.erase(it);
        return points;
    }
    return std::nullopt;
}

size_t SurfaceProbe::gpuBytes() const {
    size_t bytes = 0;
    for (const Request& r : pending_)
        bytes += 2 * std::max<size_t>(r.lines, 1) * sizeof(glm::vec4);
    return bytes;
}

} // namespace spatter::render_detail
