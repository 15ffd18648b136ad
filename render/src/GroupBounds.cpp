#include "GroupBounds.hpp"

#include "ProjectorVariants.hpp"

#include <algorithm>
#include <utility>

namespace spatter::render_detail {

namespace {

constexpr size_t kGroupBoundsBytes = 4 * 32; // kGroupBoxes GroupBox records (cull_group_bounds.glsl)
constexpr GLuint kListedBinding = 0, kBoundsBinding = 10;
constexpr uint32_t kTestGroupSize = 64; // cull_groups.comp's local size

} // namespace

Status GroupBounds::prepare() {
    if (test_) return {};
    Result<GlProgram> write = projectorComputeProgram("cull_bounds.comp");
    if (!write) return fail(write.error());
    Result<GlProgram> test = projectorComputeProgram("cull_groups.comp");
    if (!test) return fail(test.error());
    write_ = std::move(write.value());
    test_ = std::move(test.value());
    return {};
}

void GroupBounds::markEntries(size_t begin, size_t end) {
    if (all_ || begin >= end) return;
    const size_t last = (end - 1) / kGroupPlaces;
    if (marked_.size() <= last / 64) marked_.resize(last / 64 + 1, 0);
    for (size_t g = begin / kGroupPlaces; g <= last; ++g)
        marked_[g / 64] |= uint64_t(1) << (g % 64);
}

void GroupBounds::markDecals(const DrawOrder& order, const std::vector<StagedRecords>& staged) {
    if (order.relaid()) all_ = true; // every group: no need to look the decals up
    for (const StagedRecords& run : staged)
        for (size_t i = run.begin; i < run.begin + run.records.size() && !all_; ++i) {
            const uint32_t entry = order.entryOf(i);
            if (entry != DrawOrder::kEmpty) markEntry(entry);
        }
}

void GroupBounds::write(uint32_t places, uint32_t groups) {
    listed_.clear();
    for (size_t w = 0; w < marked_.size() && !all_; ++w)
        for (size_t b = 0; b < 64 && marked_[w] != 0; ++b)
            if ((marked_[w] >> b & 1) != 0 && w * 64 + b < groups) listed_.push_back(uint32_t(w * 64 + b));
    std::fill(marked_.begin(), marked_.end(), 0);
    const bool all = std::exchange(all_, false);
    if (!all && listed_.empty()) return;
    if (!all) {
        reserveBuffer(list_, listCapacity_, listed_.size() * sizeof(uint32_t), 4096);
        glNamedBufferSubData(list_.get(), 0, GLsizeiptr(listed_.size() * sizeof(uint32_t)), listed_.data());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kListedBinding, list_.get());
    }
    glUseProgram(write_.get());
    glUniform1ui(0, places);
    glUniform1ui(1, all ? 0u : 1u);
    glDispatchCompute(all ? groups : uint32_t(listed_.size()), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void GroupBounds::update(uint32_t places, uint32_t groups) {
    // Sized exactly: the groups change with a new layout alone, which writes every group's bounds.
    const size_t bytes = size_t(groups) * kGroupBoundsBytes;
    if (bytes > boundsCapacity_ || !bounds_) {
        bounds_ = dynamicBuffer(bytes);
        boundsCapacity_ = bytes;
        all_ = true;
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBoundsBinding, bounds_.get());
    write(places, groups);
}

void GroupBounds::list(uint32_t groups) {
    glUseProgram(test_.get());
    glUniform1ui(0, groups);
    glDispatchCompute((groups + kTestGroupSize - 1) / kTestGroupSize, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

} // namespace spatter::render_detail
