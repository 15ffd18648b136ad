#include "ProjectorBuffers.hpp"

#include "NormalMatrix.hpp"
#include "ProjectorLayouts.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <utility>

namespace spatter::render_detail {

void ProjectorBuffers::create() {
    frame_ = createBuffer();
    glNamedBufferStorage(frame_.get(), sizeof(ProjectorFrameGpu), nullptr, GL_DYNAMIC_STORAGE_BIT);
}

void ProjectorBuffers::uploadFrame(const HostFrame& f, const glm::dmat4& view, const glm::dmat4& viewProj,
                                   float fadeStart, const std::vector<glm::dmat4>& transforms,
                                   const std::vector<uint8_t>& ids, const DecalBatch& batch) {
    ProjectorFrameGpu g{};
    g.viewProj = glm::mat4(viewProj);
    g.view = glm::mat4(view);
    g.invView = glm::mat4(glm::inverse(view));
    g.invProjection = glm::mat4(glm::inverse(f.projection));
    g.viewport = glm::vec4(float(f.x), float(f.y), 1.0f / float(f.width), 1.0f / float(f.height));
    g.params = glm::vec4(fadeStart, float(transforms.size()), 0.0f, 0.0f);
    glNamedBufferSubData(frame_.get(), 0, sizeof g, &g);

    std::vector<ProjectorObjectGpu> objects(std::max<size_t>(1, transforms.size()));
    const glm::dmat4 toEye = glm::translate(glm::dmat4(1.0), -f.eye);
    for (size_t i = 0; i < transforms.size(); ++i) {
        const glm::dmat4 rel = toEye * transforms[i];
        ProjectorObjectGpu& o = objects[i];
        o.model = glm::mat4(rel);
        o.normalMatrix = glm::mat4(glm::mat3(normalMatrix(glm::dmat3(transforms[i]))));
        o.worldToObject = glm::mat4(glm::inverse(rel)); // read only by decals, none on a singular one
        const double det = glm::determinant(glm::dmat3(transforms[i]));
        const bool collapsed = !(std::fabs(det) > 0.0) || !std::isfinite(det); // boxes collapse: not drawn
        o.info =
            glm::uvec4(ids[i], det < 0.0 ? 1u : 0u, collapsed ? 1u : 0u, batch.hostDrawnObject(i) ? 1u : 0u);
    }
    const size_t bytes = objects.size() * sizeof(ProjectorObjectGpu);
    reserveBuffer(objects_, objectCapacity_, bytes, 64 * sizeof(ProjectorObjectGpu));
    glNamedBufferSubData(objects_.get(), 0, GLsizeiptr(bytes), objects.data());
}

size_t ProjectorBuffers::uploadTypes(const DecalBatch& batch) {
    if (!std::exchange(typesChanged_, false) && types_) return 0;
    std::vector<DecalTypeGpu> records = batch.typeRecords();
    if (records.empty()) records.emplace_back(); // a buffer of one type that cannot be drawn
    typeBytes_ = records.size() * sizeof(DecalTypeGpu);
    types_ = createBuffer(); // sized exactly: the shaders take its length as the type count
    glNamedBufferStorage(types_.get(), GLsizeiptr(typeBytes_), records.data(), 0);
    return typeBytes_;
}

size_t ProjectorBuffers::uploadRecords(DecalBatch& batch, size_t& uploads, GroupBounds& groups) {
    size_t bytes = uploadTypes(batch), end = batch.size();
    if (bytes > 0) groups.markAll(); // which decals the projector draws may have changed
    groups.markDecals(batch.order(), batch.staged());
    for (const StagedRecords& run : batch.staged())
        end = std::max(end, run.begin + run.records.size());
    records_.reserve(std::max<size_t>(1, end), recordsOnGpu_);
    for (const StagedRecords& run : batch.staged()) {
        bytes += records_.upload(run.begin, run.records);
        ++uploads;
    }
    recordsOnGpu_ = std::max(batch.size(), end);
    batch.markUploaded();
    return bytes;
}

size_t ProjectorBuffers::uploadVisible(const std::vector<uint32_t>& list) {
    reserveBuffer(visible_, visibleCapacity_, list.size() * sizeof(uint32_t), 64 * sizeof(uint32_t));
    glNamedBufferSubData(visible_.get(), 0, GLsizeiptr(list.size() * sizeof(uint32_t)), list.data());
    visibleCount_ = list.size();
    return list.size() * sizeof(uint32_t);
}

size_t ProjectorBuffers::uploadDrawOrder(DecalBatch& batch, GpuCulling& culling) {
    const DrawOrder::Changes changes = batch.takeOrderChanges(!std::exchange(orderOnGpu_, true));
    const size_t sent = culling.updateDrawOrder(batch.order(), changes);
    batch.orderUploaded();
    return sent;
}

void ProjectorBuffers::bind() const {
    glBindBufferBase(GL_UNIFORM_BUFFER, kProjectorFrameBlock, frame_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kProjectorObjectBuffer, objects_.get());
    records_.bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kProjectorVisibleBuffer, visible_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDecalTypeBuffer, types_.get());
}

} // namespace spatter::render_detail
