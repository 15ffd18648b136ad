#include "DecalBatch.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace spatter::render_detail {

namespace {

void addDirty(std::vector<std::pair<size_t, size_t>>& dirty, size_t begin, size_t end) {
    // Ranges arrive in increasing order; join those closer than a few instances.
    if (!dirty.empty() && begin <= dirty.back().second + 4) {
        dirty.back().second = std::max(dirty.back().second, end);
        return;
    }
    dirty.emplace_back(begin, end);
}

} // namespace

void DecalBatch::configure(float wrapMaxAngleDeg, int layerCount) {
    if (wrapMaxAngleDeg == wrapMaxAngleDeg_ && layerCount == layerCount_) return;
    wrapMaxAngleDeg_ = wrapMaxAngleDeg;
    layerCount_ = layerCount;
    rebuild();
}

void DecalBatch::setTypes(std::vector<DecalType> types) {
    types_ = std::move(types);
    rebuild();
}

void DecalBatch::setDecals(const std::vector<Decal>& decals, size_t objectCount) {
    decals_ = decals;
    objectCount_ = objectCount;
    rebuild();
}

void DecalBatch::setObjectCount(size_t objectCount) {
    if (objectCount == objectCount_) return;
    objectCount_ = objectCount;
    rebuild();
}

bool DecalBatch::build(const Decal& d, DecalRecordGpu& out) const {
    const bool sound = buildDecalRecord(d, out);
    return sound && d.object < objectCount_ && d.type < typeRecords_.size() &&
           typeRecords_[d.type].info.z != 0;
}

void DecalBatch::rebuild() {
    typeRecords_.clear();
    for (const DecalType& t : types_)
        typeRecords_.push_back(buildDecalType(t, wrapMaxAngleDeg_, layerCount_));
    std::vector<DecalRecordGpu> next(decals_.size());
    valid_.assign(decals_.size(), 0);
    invalid_ = 0;
    flagsUnion_ = 0;
    for (size_t i = 0; i < decals_.size(); ++i) {
        valid_[i] = build(decals_[i], next[i]) ? 1 : 0;
        invalid_ += valid_[i] ? 0 : 1;
        if (valid_[i]) flagsUnion_ |= flags(next[i]);
    }
    // Only instances whose bytes changed (or are new) need uploading.
    const size_t common = std::min(next.size(), gpu_.size());
    size_t i = 0;
    while (i < next.size()) {
        if (i < common && std::memcmp(&next[i], &gpu_[i], sizeof(DecalRecordGpu)) == 0) {
            ++i;
            continue;
        }
        size_t j = i + 1;
        while (j < next.size() &&
               !(j < common && std::memcmp(&next[j], &gpu_[j], sizeof(DecalRecordGpu)) == 0))
            ++j;
        addDirty(dirty_, i, j);
        i = j;
    }
    gpu_ = std::move(next);
    sortDrawOrder();
    // Ranges recorded earlier may point past a shrunk array.
    for (auto& r : dirty_)
        r.second = std::min(r.second, gpu_.size());
    dirty_.erase(
        std::remove_if(dirty_.begin(), dirty_.end(), [](const auto& r) { return r.first >= r.second; }),
        dirty_.end());
    std::sort(dirty_.begin(), dirty_.end());
}

void DecalBatch::sortDrawOrder() {
    auto priority = [this](uint32_t i) {
        const uint16_t t = decals_[i].type;
        return t < types_.size() ? types_[t].priority : 0;
    };
    auto time = [this](uint32_t i) { // a spawn time that is not a number sorts as 0, keeping the order strict
        const double t = decals_[i].spawnTime;
        return std::isfinite(t) ? t : 0.0;
    };
    auto before = [&](uint32_t a, uint32_t b) {
        const int pa = priority(a), pb = priority(b);
        if (pa != pb) return pa < pb;
        const double ta = time(a), tb = time(b);
        if (ta != tb) return ta < tb;
        return a < b;
    };
    // The order the GPU holds: empty when it is the index order.
    const std::vector<uint32_t> previous = indexOrder_ ? std::vector<uint32_t>{} : order_;
    order_.resize(decals_.size());
    for (size_t i = 0; i < order_.size(); ++i)
        order_[i] = uint32_t(i);
    indexOrder_ = std::is_sorted(order_.begin(), order_.end(), before);
    if (!indexOrder_) std::sort(order_.begin(), order_.end(), before);
    orderChanged_ = orderChanged_ || (indexOrder_ ? !previous.empty() : previous != order_);
}

DecalVisibility DecalBatch::cull(const std::vector<glm::dmat4>& objectTransforms,
                                 const CullView& view) const {
    DecalVisibility vis;
    const double radius = view.nearRadius * 1.01;
    // On an object with a singular transform (a scale of 0) the boxes collapse: nothing to draw.
    std::vector<uint8_t> collapsed(objectTransforms.size());
    for (size_t o = 0; o < objectTransforms.size(); ++o) {
        const double det = glm::determinant(glm::dmat3(objectTransforms[o]));
        collapsed[o] = !(std::fabs(det) > 0.0) || !std::isfinite(det) ? 1 : 0;
    }
    for (const uint32_t i : order_) {
        if (!valid_[i]) continue;
        const uint32_t object = gpu_[i].info.x;
        if (object >= objectTransforms.size() || collapsed[object]) continue;
        const glm::dmat4 boxToWorld = objectTransforms[object] * recordBoxToObject(gpu_[i]);

        // Frustum: the box is outside when all eight corners lie beyond one clip plane.
        int outside[6] = {0, 0, 0, 0, 0, 0};
        glm::dvec4 rect(1.0, 1.0, -1.0, -1.0);
        bool behind = false;
        for (int c = 0; c < 8; ++c) {
            const glm::dvec4 corner((c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0, 1.0);
            const glm::dvec3 rel = glm::dvec3(boxToWorld * corner) - view.eye;
            const glm::dvec4 clip = view.viewProj * glm::dvec4(rel, 1.0);
            const double low = view.clipMinusOne ? -clip.w : 0.0; // the low end of clip depth
            outside[0] += clip.x < -clip.w;
            outside[1] += clip.x > clip.w;
            outside[2] += clip.y < -clip.w;
            outside[3] += clip.y > clip.w;
            outside[4] += view.reversedZ ? clip.z > clip.w : clip.z < low; // in front of the near plane
            outside[5] += view.reversedZ ? clip.z < low : clip.z > clip.w; // beyond the far plane
            behind = behind || !(clip.w > 0.0);
            rect = glm::dvec4(glm::min(glm::dvec2(rect), glm::dvec2(clip) / clip.w),
                              glm::max(glm::dvec2(rect.z, rect.w), glm::dvec2(clip) / clip.w));
        }
        if (std::any_of(outside, outside + 6, [](int n) { return n == 8; })) {
            ++vis.culled;
            continue;
        }

        // Camera inside, conservatively: the eye's near-plane sphere against the box slabs. Row r of
        // the inverse maps world offsets to box coordinate r, so the sphere reaches |u_r| <= 1 only
        // if |u_r| <= 1 + radius * |row r|.
        const glm::dmat4 worldToBox = glm::inverse(boxToWorld);
        const glm::dvec3 u = glm::dvec3(worldToBox * glm::dvec4(view.eye, 1.0));
        if (!std::isfinite(u.x + u.y + u.z)) continue; // the box collapsed in double after all
        bool inside = true;
        for (int r = 0; r < 3 && inside; ++r) {
            const double rowLength =
                glm::length(glm::dvec3(worldToBox[0][r], worldToBox[1][r], worldToBox[2][r]));
            inside = std::fabs(u[r]) <= 1.0 + radius * rowLength;
        }
        vis.visible.push_back(i);
        vis.inside += inside ? 1 : 0;
        vis.flags |= flags(gpu_[i]);
        if (view.rects)
            vis.rects.push_back(behind || inside ? glm::vec4(-1.0f, -1.0f, 1.0f, 1.0f)
                                                 : glm::vec4(glm::clamp(rect, -1.0, 1.0)));
    }
    return vis;
}

} // namespace spatter::render_detail
