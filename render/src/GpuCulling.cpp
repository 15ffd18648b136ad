#include "GpuCulling.hpp"

#include "ProjectorVariants.hpp"

#include <algorithm>
#include <array>

namespace spatter::render_detail {

namespace {

constexpr uint32_t kGroupPlaces = GroupBounds::kGroupPlaces; // the local size of the test by place
// Groups of a block (cull_layout.glsl): the scatter sums the blocks before a group's, then the groups.
constexpr uint32_t kBlockGroups = 256;

// Binding points of the culling passes (shaders/cull*.comp).
constexpr GLuint kClassesBinding = 0, kReadbackBinding = 1, kGroupsBinding = 2, kCountersBinding = 5,
                 kOrderBinding = 6, kListBinding = 7;
// Counters in shaders/cull_layout.glsl as a run starts: the indirect draw (the cube's 36 indices, no
// instance yet), the occluded, invalid and host-drawn counts, the exact test's candidates and the
// indirect dispatch of the test by place (no group yet).
constexpr std::array<uint32_t, 12> kCountersAtStart = {36, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1};
constexpr GLintptr kTestedDispatchOffset = 9 * sizeof(uint32_t);
// The test by place is dispatched indirectly, a work group for each group the first pass listed (on llvmpipe,
// work groups looping over the listed groups, whose bodies hold barriers, took 3 to 10 times as long by wall
// time), unless the latest count read back listed more than half the groups: then it tests every group,
// dispatched directly, each work group culling its group whole (and counting it: the few groups culled
// whole are counted, not the many tested, whose one counter took the spread row 3 to 4 us on an H100) or
// testing it, and neither the first pass nor a command barrier comes before it (the decals in view spread
// through the draw order, or most of a smaller world in view: 10,000 decals all in view take 4% less on an
// H200). The corner test and the scatter
// are dispatched directly, not indirectly at this run's counts: an indirect dispatch needs a command barrier,
// which costs a GPU more than work groups that find no work. A software rasteriser pays for every work group,
// so they are sized by the latest counts read back, with room to spare; their invocations stride over the
// work, so a run whose counts outgrow an earlier one's is still whole, only slower. The corner test takes
// 2,048 work groups of 64 at most (512 made the rows with 100,000 decals in view 3 to 4 us slower on an
// H200), and twice the boxes in the frustum, which its candidates hardly exceed, plus a margin; the scatter
// takes a work group for each group tested by place at most, and half the visible decals plus a margin (a
// work group writes the groups it finds with a visible one one after the other, two on average where every
// visible decal has a group of its own; decals in view side by side share groups).
constexpr uint32_t kExactGroupsMost = 2048, kExactGroupsMargin = 64, kScatterGroupsMargin = 16;
constexpr uint64_t kExactGroupSize = 64; // cull_exact.comp's local size

} // namespace

Status GpuCulling::prepare() {
    if (scatter_) return {};
    if (Status groups = groupBounds_.prepare(); !groups) return groups;
    Result<GlProgram> classify = projectorComputeProgram("cull.comp");
    if (!classify) return fail(classify.error());
    Result<GlProgram> exact = projectorComputeProgram("cull_exact.comp");
    if (!exact) return fail(exact.error());
    Result<GlProgram> scatter = projectorComputeProgram("cull_scatter.comp");
    if (!scatter) return fail(scatter.error());
    Result<GlProgram> write = projectorComputeProgram("order_write.comp");
    if (!write) return fail(write.error());
    classify_ = std::move(classify.value());
    exact_ = std::move(exact.value());
    scatter_ = std::move(scatter.value());
    write_ = std::move(write.value());
    counters_ = createBuffer();
    glNamedBufferStorage(counters_.get(), GLsizeiptr(sizeof kCountersAtStart), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    return {};
}

size_t GpuCulling::updateDrawOrder(const DrawOrder& order, const DrawOrder::Changes& changes) {
    entries_ = uint32_t(order.size());
    const std::vector<uint32_t>& entries = order.entries();
    const size_t bytes = std::max<size_t>(1, order.size()) * sizeof(uint32_t);
    // Sized as the order is (it has room to grow of its own): only a new layout, whose changes are
    // all of its entries, makes it longer.
    if (bytes > orderCapacity_ || !order_) {
        order_ = createBuffer();
        orderCapacity_ = bytes;
        glNamedBufferStorage(order_.get(), GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    if (changes.all) {
        groupBounds_.markAll();
        glNamedBufferSubData(order_.get(), 0, GLsizeiptr(entries.size() * sizeof(uint32_t)), entries.data());
        return entries.size() * sizeof(uint32_t);
    }
    for (const glm::uvec2& w : changes.writes)
        groupBounds_.markEntry(w.x);
    if (!changes.writes.empty()) return writeDrawOrder(changes.writes);
    size_t sent = 0;
    for (const auto& [begin, end] : changes.runs) {
        groupBounds_.markEntries(begin, end);
        glNamedBufferSubData(order_.get(), GLintptr(begin * sizeof(uint32_t)),
                             GLsizeiptr((end - begin) * sizeof(uint32_t)), &entries[begin]);
        sent += (end - begin) * sizeof(uint32_t);
    }
    return sent;
}

size_t GpuCulling::writeDrawOrder(const std::vector<glm::uvec2>& writes) {
    const size_t bytes = writes.size() * sizeof(glm::uvec2);
    reserveBuffer(writes_, writesCapacity_, bytes, 4096);
    glNamedBufferSubData(writes_.get(), 0, GLsizeiptr(bytes), writes.data());
    // Over bindings the culling binds its own buffers to again (bind()).
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kClassesBinding, writes_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOrderBinding, order_.get());
    glUseProgram(write_.get());
    glUniform1ui(0, uint32_t(writes.size()));
    glDispatchCompute(uint32_t((writes.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    return bytes;
}

uint32_t GpuCulling::reserve(size_t decals, GlBuffer& visible, size_t& visibleCapacity) {
    const uint32_t groups = std::max<uint32_t>(1, (entries_ + kGroupPlaces - 1) / kGroupPlaces);
    reserveBuffer(classes_, classesCapacity_, size_t(groups) * kGroupPlaces / 8, 4096); // a bit a place
    // A count a group and a block, then the list of the groups to test by place.
    const size_t blocks = (size_t(groups) + kBlockGroups - 1) / kBlockGroups;
    reserveBuffer(groups_, groupsCapacity_, (2 * size_t(groups) + blocks) * sizeof(uint32_t), 4096);
    reserveBuffer(order_, orderCapacity_, sizeof(uint32_t), 4096); // bound even when empty
    // The visible list, and the exact test's candidates before it.
    if (reserveBuffer(visible, visibleCapacity, decals * sizeof(uint32_t), 4096)) {
        const uint32_t zero = 0; // an earlier draw's count may reach past this run's list (overlays)
        glClearNamedBufferData(visible.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    }
    return groups;
}

void GpuCulling::bind(const GlBuffer& visible) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kClassesBinding, classes_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGroupsBinding, groups_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCountersBinding, counters_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOrderBinding, order_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kListBinding, visible.get());
}

void GpuCulling::run(const CullRun& what, const Occlusion& occlusion, GlBuffer& visible,
                     size_t& visibleCapacity) {
    const uint32_t groups = reserve(what.decals, visible, visibleCapacity);
    glNamedBufferSubData(counters_.get(), 0, GLsizeiptr(sizeof kCountersAtStart), kCountersAtStart.data());
    bind(visible);
    const bool every = testsEveryGroup(groups);
    groupBounds_.update(entries_, groups);
    if (!every) groupBounds_.list(groups);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kClassesBinding, classes_.get()); // where it listed groups
    glUseProgram(classify_.get());
    glUniform1ui(0, entries_);
    glUniform1ui(1, what.checkTypes ? 1u : 0u);
    glUniform1ui(2, groups);
    glUniform1ui(3, every ? 1u : 0u);
    if (every) {
        glDispatchCompute(groups, 1, 1);
    } else {
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, counters_.get());
        glDispatchComputeIndirect(kTestedDispatchOffset);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(exact_.get());
    glUniform1ui(0, groups);
    glUniform4f(1, 0.0f, what.reversedZ ? 1.0f : 0.0f, what.clipMinusOne ? 1.0f : 0.0f, 0.0f);
    glUniform4i(2, occlusion.texture ? occlusion.levels : 0, occlusion.convention, occlusion.size.x,
                occlusion.size.y);
    glBindTextureUnit(0, occlusion.texture);
    glBindSampler(0, 0);
    glDispatchCompute(exactGroups(), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    // The scatter writes the counts read back where the other passes read the projector's objects.
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kReadbackBinding, counts_.target());
    glUseProgram(scatter_.get());
    glUniform1ui(0, groups);
    glUniform1ui(1, every ? 1u : 0u);
    glDispatchCompute(scatterGroups(groups), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

bool GpuCulling::testsEveryGroup(uint32_t groups) const {
    return counts_.hasRead() && uint64_t(counts_.values()[4]) * 2 > groups;
}

uint32_t GpuCulling::exactGroups() const {
    const uint64_t places =
        std::max<uint64_t>(1, (uint64_t(entries_) + kExactGroupSize - 1) / kExactGroupSize);
    if (!counts_.hasRead()) return uint32_t(std::min<uint64_t>(kExactGroupsMost, places));
    const uint64_t inFrustum = uint64_t(counts_.values()[0]) + counts_.values()[1];
    return uint32_t(
        std::min<uint64_t>({kExactGroupsMost, places,
                            (2 * inFrustum + kExactGroupSize - 1) / kExactGroupSize + kExactGroupsMargin}));
}

// At least one: the first work group writes the counts read back.
uint32_t GpuCulling::scatterGroups(uint32_t groups) const {
    if (!counts_.hasRead()) return groups;
    const uint64_t tested = uint64_t(counts_.values()[4]) + kScatterGroupsMargin;
    return uint32_t(
        std::min<uint64_t>({groups, tested, uint64_t(counts_.values()[0]) / 2 + kScatterGroupsMargin}));
}

void GpuCulling::readBack() {
    counts_.mark();
}

uint32_t GpuCulling::visibleCount(bool wait) {
    if (wait) readBack();
    return counts_.latest(wait)[0];
}

} // namespace spatter::render_detail
