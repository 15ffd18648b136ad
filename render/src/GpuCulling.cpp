#include "GpuCulling.hpp"

#include "ProjectorShaders.hpp"
#include "ShaderProgram.hpp"

#include <algorithm>

namespace spatter::render_detail {

namespace {

constexpr uint32_t kGroup = 256; // local size of the classify and scatter passes

// Binding points of the culling passes (shaders/cull*.comp).
constexpr GLuint kClassesBinding = 0, kGroupsBinding = 2, kDrawsBinding = 5, kVisibleOutBinding = 6;
constexpr size_t kTotalsOffset = 2 * 4 * sizeof(uint32_t), kTotalsBytes = 4 * sizeof(uint32_t);
constexpr size_t kDrawsBytes = kTotalsOffset + kTotalsBytes;

Result<GlProgram> computeProgram(const char* file) {
    Result<GlProgram> p = buildProgram(shaderLibrary(kProjectorShaders), {{GL_COMPUTE_SHADER, file}}, {});
    if (!p) return fail("projector: " + p.error());
    return p;
}

} // namespace

GpuCulling::~GpuCulling() {
    if (fence_) glDeleteSync(fence_);
}

Status GpuCulling::prepare() {
    if (scatter_) return {};
    Result<GlProgram> classify = computeProgram("cull.comp");
    if (!classify) return fail(classify.error());
    Result<GlProgram> scan = computeProgram("cull_scan.comp");
    if (!scan) return fail(scan.error());
    Result<GlProgram> scatter = computeProgram("cull_scatter.comp");
    if (!scatter) return fail(scatter.error());
    classify_ = std::move(classify.value());
    scan_ = std::move(scan.value());
    scatter_ = std::move(scatter.value());
    draws_ = createBuffer();
    glNamedBufferStorage(draws_.get(), GLsizeiptr(kDrawsBytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    readback_ = createBuffer();
    glNamedBufferStorage(readback_.get(), GLsizeiptr(kTotalsBytes), nullptr, GL_CLIENT_STORAGE_BIT);
    return {};
}

void GpuCulling::run(uint32_t count, double nearRadius, bool reversedZ, bool clipMinusOne, GlBuffer& visible,
                     size_t& visibleCapacity) {
    const uint32_t groups = std::max<uint32_t>(1, (count + kGroup - 1) / kGroup);
    reserveBuffer(classes_, classesCapacity_, size_t(count) * sizeof(uint32_t), 4096);
    reserveBuffer(groups_, groupsCapacity_, size_t(groups) * 2 * sizeof(uint32_t), 4096);
    if (reserveBuffer(visible, visibleCapacity, size_t(count) * sizeof(uint32_t), 4096)) {
        const uint32_t zero = 0; // an earlier draw's count may reach past this run's list (overlays)
        glClearNamedBufferData(visible.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kClassesBinding, classes_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGroupsBinding, groups_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDrawsBinding, draws_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleOutBinding, visible.get());

    glUseProgram(classify_.get());
    glUniform1ui(0, count);
    glUniform4f(1, float(nearRadius * 1.01), reversedZ ? 1.0f : 0.0f, clipMinusOne ? 1.0f : 0.0f, 0.0f);
    glDispatchCompute(groups, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(scan_.get());
    glUniform1ui(0, groups);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(scatter_.get());
    glUniform1ui(0, count);
    glDispatchCompute(groups, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glCopyNamedBufferSubData(draws_.get(), readback_.get(), GLintptr(kTotalsOffset), 0,
                             GLsizeiptr(kTotalsBytes));
    if (fence_) glDeleteSync(fence_);
    fence_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

glm::uvec2 GpuCulling::totals(bool wait) {
    if (!fence_) return latest_;
    const GLenum state =
        glClientWaitSync(fence_, wait ? GL_SYNC_FLUSH_COMMANDS_BIT : 0, wait ? ~GLuint64(0) : 0);
    if (state != GL_ALREADY_SIGNALED && state != GL_CONDITION_SATISFIED) return latest_;
    uint32_t t[4] = {0, 0, 0, 0};
    glGetNamedBufferSubData(readback_.get(), 0, sizeof t, t);
    latest_ = glm::uvec2(t[0], t[1]);
    glDeleteSync(fence_);
    fence_ = nullptr;
    return latest_;
}

} // namespace spatter::render_detail
