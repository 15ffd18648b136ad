#include "ForwardBins.hpp"

#include "ProjectorVariants.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <string>
#include <vector>

namespace spatter::render_detail {

namespace {

constexpr GLuint kGroup = 64;               // local size of the per-decal and per-tile passes
constexpr GLuint kTileReadbackBinding = 10; // TileReadback of forward_prepare.comp and forward_sort.comp
// TileReadback's first word when a tile held more than forwardTileCapacity (forward_sort.comp); 1 when
// the buffers were short (forward_prepare.comp).
constexpr uint32_t kTileOverflowed = 2;

GLuint groups(uint32_t n) {
    return GLuint((n + kGroup - 1) / kGroup);
}

// The tile holding window position `ndc` of a viewport `size` pixels wide, widened by a pixel for
// the float rounding of the GPU's box test, clamped to the grid.
int tileOf(double ndc, int size, int tileSize, int tiles, double widen) {
    const double pixel = (ndc * 0.5 + 0.5) * size + widen;
    return std::clamp(int(std::floor(pixel / tileSize)), 0, tiles - 1);
}

} // namespace

Status ForwardBins::prepare() {
    if (sort_) return {};
    Result<GlProgram> prepare = projectorComputeProgram("forward_prepare.comp");
    if (!prepare) return fail(prepare.error());
    Result<GlProgram> scan = projectorComputeProgram("forward_scan.comp");
    if (!scan) return fail(scan.error());
    Result<GlProgram> fill = projectorComputeProgram("forward_fill.comp");
    if (!fill) return fail(fill.error());
    Result<GlProgram> sort = projectorComputeProgram("forward_sort.comp");
    if (!sort) return fail(sort.error());
    Result<GlProgram> prepareCulled = projectorComputeProgram("forward_prepare.comp", {"FORWARD_CULLED"});
    if (!prepareCulled) return fail(prepareCulled.error());
    Result<GlProgram> prepareShown =
        projectorComputeProgram("forward_prepare.comp", {"FORWARD_CULLED", "SHOWN_ONLY"});
    if (!prepareShown) return fail(prepareShown.error());
    Result<GlProgram> sortCulled = projectorComputeProgram("forward_sort.comp", {"FORWARD_CULLED"});
    if (!sortCulled) return fail(sortCulled.error());
    Result<GlProgram> sortCulledByTile =
        projectorComputeProgram("forward_sort.comp", {"FORWARD_CULLED", "SORT_BY_TILE"});
    if (!sortCulledByTile) return fail(sortCulledByTile.error());
    prepareCulled_ = std::move(prepareCulled.value());
    prepareShown_ = std::move(prepareShown.value());
    sortCulled_ = std::move(sortCulled.value());
    sortCulledByTile_ = std::move(sortCulledByTile.value());
    prepare_ = std::move(prepare.value());
    scan_ = std::move(scan.value());
    fill_ = std::move(fill.value());
    sort_ = std::move(sort.value());
    return {};
}

size_t ForwardBins::tileRects(const ForwardFrame& frame, const DecalVisibility& vis, int tileSize,
                              glm::ivec2 tiles) {
    rectsCpu_.clear();
    size_t items = 0;
    auto add = [&](const glm::vec4& r) {
        const int x0 = tileOf(r.x, frame.width, tileSize, tiles.x, -1.0);
        const int y0 = tileOf(r.y, frame.height, tileSize, tiles.y, -1.0);
        const int x1 = tileOf(r.z, frame.width, tileSize, tiles.x, 1.0);
        const int y1 = tileOf(r.w, frame.height, tileSize, tiles.y, 1.0);
        rectsCpu_.push_back(glm::uvec2(uint32_t(x0) | uint32_t(y0) << 16, uint32_t(x1) | uint32_t(y1) << 16));
        items += size_t(x1 - x0 + 1) * size_t(y1 - y0 + 1);
    };
    for (const glm::vec4& r : vis.rects)
        add(r);
    return items;
}

glm::ivec2 ForwardBins::grid(const ForwardFrame& frame, int tileSize, ForwardGridGpu& head) const {
    const glm::ivec2 tiles((frame.width + tileSize - 1) / tileSize, (frame.height + tileSize - 1) / tileSize);
    head.grid = glm::ivec4(frame.x, frame.y, tiles.x, tiles.y);
    head.info.x = tileSize;
    return tiles;
}

size_t ForwardBins::bin(const ForwardFrame& frame, const DecalVisibility& vis, int tileSize,
                        ForwardGridGpu head) {
    tileInfo_.reset();    // sized on the CPU, the tiles hold every decal: nothing is left out from here on
    zeroCounts_ = 0;      // the scan and the fill leave them counted
    everyDecalCount_ = 0; // the items are written from the start
    const glm::ivec2 tiles = grid(frame, tileSize, head);
    const uint32_t tileCount = uint32_t(tiles.x) * uint32_t(tiles.y);
    const size_t items = tileRects(frame, vis, tileSize, tiles);
    const uint32_t visible = uint32_t(rectsCpu_.size());

    const size_t tileBytes = sizeof(ForwardGridGpu) + tileCount * sizeof(glm::uvec2);
    reserveBuffer(tiles_, tilesCapacity_, tileBytes, 4096);
    reserveBuffer(counts_, countsCapacity_, tileCount * sizeof(uint32_t), 4096);
    reserveBuffer(decals_, decalsCapacity_, visible * sizeof(ForwardDecalGpu), 64 * sizeof(ForwardDecalGpu));
    reserveBuffer(items_, itemsCapacity_, items * sizeof(uint32_t), 4096);
    reserveBuffer(rects_, rectsCapacity_, visible * sizeof(glm::uvec2), 512);
    glNamedBufferSubData(tiles_.get(), 0, sizeof head, &head);
    glNamedBufferSubData(rects_.get(), 0, GLsizeiptr(visible * sizeof(glm::uvec2)), rectsCpu_.data());
    const uint32_t zero = 0;
    glClearNamedBufferSubData(counts_.get(), GL_R32UI, 0, GLsizeiptr(tileCount * sizeof(uint32_t)),
                              GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    if (visible == 0) { // no decal: every run empty
        glClearNamedBufferSubData(tiles_.get(), GL_R32UI, sizeof head,
                                  GLsizeiptr(tileCount * sizeof(glm::uvec2)), GL_RED_INTEGER, GL_UNSIGNED_INT,
                                  &zero);
        return sizeof head;
    }
    dispatch(visible, tileCount);
    return sizeof head + visible * sizeof(glm::uvec2);
}

size_t ForwardBins::binCulled(const ForwardFrame& frame, int tileSize, ForwardGridGpu head, GLuint draws,
                              size_t capacity, uint32_t tileCapacity, uint32_t mostPerTile, bool shownOnly) {
    const glm::ivec2 tiles = grid(frame, tileSize, head);
    const uint32_t tileCount = uint32_t(tiles.x) * uint32_t(tiles.y);
    reserveBuffer(tiles_, tilesCapacity_, sizeof(ForwardGridGpu) + tileCount * sizeof(glm::uvec2), 4096);
    if (reserveBuffer(counts_, countsCapacity_, tileCount * sizeof(uint32_t), 4096)) zeroCounts_ = 0;
    reserveBuffer(decals_, decalsCapacity_, capacity * sizeof(ForwardDecalGpu), 64 * sizeof(ForwardDecalGpu));
    const size_t runItems = size_t(tileCount) * tileCapacity;
    const size_t sent = sizeof head + reserveItems(runItems, capacity);
    glNamedBufferSubData(tiles_.get(), 0, sizeof head, &head);
    if (tileCount > zeroCounts_) { // the sort pass zeroes the counts it reads for the next binning
        const uint32_t zero = 0;
        glClearNamedBufferSubData(counts_.get(), GL_R32UI, 0, GLsizeiptr(tileCount * sizeof(uint32_t)),
                                  GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    }
    const ForwardBindings b;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, draws);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kForwardCountBuffer, counts_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b.decals, decals_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b.tiles, tiles_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b.items, items_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTileReadbackBinding, tileInfo_.target());
    glUseProgram(shownOnly ? prepareShown_.get() : prepareCulled_.get());
    glUniform1ui(0, uint32_t(capacity));
    glUniform1ui(1, tileCapacity);
    glDispatchCompute(groups(uint32_t(capacity)), 1, 1); // invocations past the visible count return at once
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    // Runs sized for a fullest tile of more than a few decals are sorted by a work group each.
    const bool byTile = !shortRuns(tileCapacity);
    glUseProgram(byTile ? sortCulledByTile_.get() : sortCulled_.get());
    if (!byTile) glUniform1ui(0, tileCount);
    glUniform1ui(1, tileCapacity);
    glUniform1ui(2, uint32_t(capacity));
    glUniform1ui(3, mostPerTile);
    glUniform1ui(4, uint32_t(runItems));
    if (byTile)
        glDispatchCompute(GLuint(tiles.x), GLuint(tiles.y), 1);
    else
        glDispatchCompute(groups(tileCount), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    zeroCounts_ = std::max(zeroCounts_, tileCount);
    return sent;
}

void ForwardBins::readBack() {
    tileInfo_.mark();
}

size_t ForwardBins::reserveItems(size_t runItems, size_t everyDecal) {
    const size_t bytes = (runItems + everyDecal) * sizeof(uint32_t);
    // Made anew where it is short or four times what is needed, with a quarter more for room: the
    // run over every decal follows the decals in view from frame to frame.
    const bool anew =
        !items_ || bytes > itemsCapacity_ || (itemsCapacity_ > 4096 && itemsCapacity_ >= 4 * bytes);
    if (anew) {
        itemsCapacity_ = std::max<size_t>(4096, bytes + bytes / 4);
        items_ = dynamicBuffer(itemsCapacity_);
    }
    if (!anew && everyDecalAt_ == runItems && everyDecalCount_ >= everyDecal) return 0;
    std::vector<uint32_t> every(everyDecal);
    std::iota(every.begin(), every.end(), 0u);
    glNamedBufferSubData(items_.get(), GLintptr(runItems * sizeof(uint32_t)),
                         GLsizeiptr(everyDecal * sizeof(uint32_t)), every.data());
    everyDecalAt_ = runItems;
    everyDecalCount_ = everyDecal;
    return everyDecal * sizeof(uint32_t);
}

bool ForwardBins::leftOut(bool wait) {
    if (wait) readBack();
    return tileInfo_.latest(wait)[0] != 0;
}

bool ForwardBins::tileOverflowed(bool wait) {
    if (wait) readBack();
    return tileInfo_.latest(wait)[0] == kTileOverflowed;
}

std::optional<uint32_t> ForwardBins::fullestTile(bool wait) {
    const uint32_t fullest = tileInfo_.latest(wait)[1];
    if (!tileInfo_.hasRead()) return std::nullopt;
    return fullest;
}

void ForwardBins::dispatch(uint32_t visible, uint32_t tileCount) const {
    const ForwardBindings b;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kForwardRectBuffer, rects_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kForwardCountBuffer, counts_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b.decals, decals_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b.tiles, tiles_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b.items, items_.get());
    glUseProgram(prepare_.get());
    glUniform1ui(0, visible);
    glDispatchCompute(groups(visible), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(scan_.get());
    glUniform1ui(0, tileCount);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(fill_.get());
    glUniform1ui(0, visible);
    glDispatchCompute(groups(visible), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(sort_.get());
    glUniform1ui(0, tileCount);
    glDispatchCompute(groups(tileCount), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void ForwardBins::bind(const ForwardBindings& b) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b.decals, decals_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b.tiles, tiles_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b.items, items_.get());
}

} // namespace spatter::render_detail
