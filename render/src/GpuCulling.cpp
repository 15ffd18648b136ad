#include "GpuCulling.hpp"

#include "ProjectorVariants.hpp"

#include <algorithm>

namespace spatter::render_detail {

namespace {

constexpr uint32_t kCullGroup = 256; // local size of the classify and scatter passes

// Binding points of the culling passes (shaders/cull*.comp).
constexpr GLuint kClassesBinding = 0, kGroupsBinding = 2, kDrawsBinding = 5, kOrderBinding = 6,
                 kVisibleOutBinding = 7;
// The indirect draw, then the occluded, invalid and host-drawn counts (Counters in cull.comp).
constexpr size_t kDrawsBytes = 8 * sizeof(uint32_t);
constexpr size_t kCountOffset = sizeof(uint32_t); // DrawElementsIndirectCommand::instanceCount
constexpr size_t kCountersOffset = 5 * sizeof(uint32_t);
constexpr size_t kCounters = 3;

} // namespace

Status GpuCulling::prepare() {
    if (scatter_) return {};
    Result<GlProgram> classify = projectorComputeProgram("cull.comp");
    if (!classify) return fail(classify.error());
    Result<GlProgram> scan = projectorComputeProgram("cull_scan.comp");
    if (!scan) return fail(scan.error());
    Result<GlProgram> scatter = projectorComputeProgram("cull_scatter.comp");
    if (!scatter) return fail(scatter.error());
    classify_ = std::move(classify.value());
    scan_ = std::move(scan.value());
    scatter_ = std::move(scatter.value());
    draws_ = createBuffer();
    glNamedBufferStorage(draws_.get(), GLsizeiptr(kDrawsBytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    return {};
}

size_t GpuCulling::updateDrawOrder(const std::vector<uint32_t>& entries,
                                   const std::vector<std::pair<size_t, size_t>>& runs) {
    entries_ = uint32_t(entries.size());
    const size_t bytes = std::max<size_t>(1, entries.size()) * sizeof(uint32_t);
    if (bytes > orderCapacity_ || !order_) { // sized as the order is: it has room to grow of its own
        order_ = createBuffer();
        orderCapacity_ = bytes;
        glNamedBufferStorage(order_.get(), GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glNamedBufferSubData(order_.get(), 0, GLsizeiptr(entries.size() * sizeof(uint32_t)), entries.data());
        return entries.size() * sizeof(uint32_t);
    }
    size_t sent = 0;
    for (const auto& [begin, end] : runs) {
        glNamedBufferSubData(order_.get(), GLintptr(begin * sizeof(uint32_t)),
                             GLsizeiptr((end - begin) * sizeof(uint32_t)), &entries[begin]);
        sent += (end - begin) * sizeof(uint32_t);
    }
    return sent;
}

void GpuCulling::run(size_t decals, bool reversedZ, bool clipMinusOne, const Occlusion& occlusion,
                     GlBuffer& visible, size_t& visibleCapacity) {
    const uint32_t count = entries_;
    const uint32_t groups = std::max<uint32_t>(1, (count + kCullGroup - 1) / kCullGroup);
    reserveBuffer(classes_, classesCapacity_, size_t(groups) * kCullGroup / 8, 4096); // a bit per entry
    reserveBuffer(groups_, groupsCapacity_, size_t(groups) * sizeof(uint32_t), 4096);
    reserveBuffer(order_, orderCapacity_, sizeof(uint32_t), 4096); // bound even when empty
    if (reserveBuffer(visible, visibleCapacity, decals * sizeof(uint32_t), 4096)) {
        const uint32_t zero = 0; // an earlier draw's count may reach past this run's list (overlays)
        glClearNamedBufferData(visible.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kClassesBinding, classes_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGroupsBinding, groups_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDrawsBinding, draws_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOrderBinding, order_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleOutBinding, visible.get());

    const uint32_t zero = 0;
    glClearNamedBufferSubData(draws_.get(), GL_R32UI, GLintptr(kCountersOffset), kCounters * sizeof zero,
                              GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glUseProgram(classify_.get());
    glUniform1ui(0, count);
    glUniform4f(1, 0.0f, reversedZ ? 1.0f : 0.0f, clipMinusOne ? 1.0f : 0.0f, 0.0f);
    glUniform4i(2, occlusion.texture ? occlusion.levels : 0, occlusion.convention, occlusion.size.x,
                occlusion.size.y);
    glBindTextureUnit(0, occlusion.texture);
    glBindSampler(0, 0);
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
    counts_.copy(draws_.get(), kCountOffset, 0, 1);
    counts_.copy(draws_.get(), kCountersOffset, 1, kCounters);
    counts_.fence();
}

uint32_t GpuCulling::visibleCount(bool wait) {
    return counts_.latest(wait)[0];
}

} // namespace spatter::render_detail
