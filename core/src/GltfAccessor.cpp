#include "GltfAccessor.hpp"

namespace spatter::gltf {

namespace {

std::string accessorName(int index, const char* role) {
    return "accessor " + std::to_string(index) + " (" + role + ")";
}

// Checks that accessor `index` exists and has `type` and an allowed component type.
Result<const tinygltf::Accessor*> checkedAccessor(const tinygltf::Model& model, int index, const char* role,
                                                  int type, unsigned allowedComponentTypes) {
    if (!validIndex(index, model.accessors.size()))
        return fail(std::string(role) + " refers to accessor " + std::to_string(index) +
                    ", which does not exist");
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    const std::string what = accessorName(index, role);
    if (a.type != type) return fail(what + " is " + typeName(a.type) + ", expected " + typeName(type));
    const size_t size = componentSize(a.componentType);
    if (size == 0 || (componentBit(a.componentType) & allowedComponentTypes) == 0)
        return fail(what + " has component type " + std::to_string(a.componentType) + ", which " + role +
                    " cannot use");
    return &a;
}

// A view of `a`'s elements `stride` bytes apart, its data still to be set.
AccessorView viewOf(const tinygltf::Accessor& a, size_t stride) {
    AccessorView v;
    v.present = true;
    v.count = a.count;
    v.stride = stride;
    v.componentType = a.componentType;
    v.normalized = a.normalized;
    return v;
}

// The view of an accessor that has a buffer view, its sparse part left aside.
Result<AccessorView> viewDense(const tinygltf::Model& model, int index, const char* role, int type,
                               unsigned allowedComponentTypes) {
    Result<const tinygltf::Accessor*> checked =
        checkedAccessor(model, index, role, type, allowedComponentTypes);
    if (!checked) return fail(checked.error());
    const tinygltf::Accessor& a = *checked.value();
    const std::string what = accessorName(index, role);
    const size_t size = componentSize(a.componentType);
    if (a.bufferView < 0)
        return fail(what + " has no buffer view (zero-filled or extension-provided data is not supported)");
    if (!validIndex(a.bufferView, model.bufferViews.size()))
        return fail(what + " refers to buffer view " + std::to_string(a.bufferView) +
                    ", which does not exist");
    const tinygltf::BufferView& view = model.bufferViews[size_t(a.bufferView)];
    const size_t elementSize = size * size_t(componentCount(type));
    const size_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
    if (stride < elementSize)
        return fail(what + ": byte stride " + num(stride) + " of buffer view " +
                    std::to_string(a.bufferView) + " is smaller than one element (" + num(elementSize) +
                    " bytes)");

    AccessorView v = viewOf(a, stride);
    if (a.count == 0) return v;
    size_t span = 0;
    if (!mulAdd(a.count - 1, stride, elementSize, span) || !rangeInside(a.byteOffset, span, view.byteLength))
        return fail(what + " reads past the end of buffer view " + std::to_string(a.bufferView) + " (" +
                    num(a.count) + " elements from byte " + num(a.byteOffset) + ", the view has " +
                    num(view.byteLength) + " bytes)");
    v.data = model.buffers[size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
    return v;
}

// `count` tightly packed elements of `elementSize` bytes at `offset` in buffer view `view`, or an
// error saying what they are (`what`).
Result<const unsigned char*> sparseRange(const tinygltf::Model& model, int view, int offset, size_t count,
                                         size_t elementSize, const std::string& what) {
    if (!validIndex(view, model.bufferViews.size()))
        return fail(what + " refer to buffer view " + std::to_string(view) + ", which does not exist");
    const tinygltf::BufferView& v = model.bufferViews[size_t(view)];
    size_t span = 0;
    if (offset < 0 || !mulAdd(count, elementSize, 0, span) ||
        !rangeInside(size_t(offset), span, v.byteLength))
        return fail(what + " read past the end of buffer view " + std::to_string(view));
    return model.buffers[size_t(v.buffer)].data.data() + v.byteOffset + size_t(offset);
}

// Copies the sparse values of accessor `a` (elements of `elementSize` bytes) over the elements of
// `out` (tightly packed, one per accessor element) that its indices name.
Status applySparse(const tinygltf::Model& model, const tinygltf::Accessor& a, const std::string& what,
                   size_t elementSize, unsigned char* out) {
    const auto& sparse = a.sparse;
    if (sparse.count < 1 || size_t(sparse.count) > a.count)
        return fail(what + " has a sparse count of " + std::to_string(sparse.count) + " for " + num(a.count) +
                    " elements");
    const size_t n = size_t(sparse.count);
    const int indexType = sparse.indices.componentType;
    if (componentSize(indexType) == 0 || (componentBit(indexType) & kIndexTypes) == 0)
        return fail(what + " has sparse indices of component type " + std::to_string(indexType));
    Result<const unsigned char*> indices =
        sparseRange(model, sparse.indices.bufferView, sparse.indices.byteOffset, n, componentSize(indexType),
                    what + ": its sparse indices");
    if (!indices) return fail(indices.error());
    Result<const unsigned char*> values =
        sparseRange(model, sparse.values.bufferView, sparse.values.byteOffset, n, elementSize,
                    what + ": its sparse values");
    if (!values) return fail(values.error());
    AccessorView iv;
    iv.data = indices.value();
    iv.count = n;
    iv.stride = componentSize(indexType);
    iv.componentType = indexType;
    for (size_t i = 0; i < n; ++i) {
        const uint32_t target = iv.index(i);
        if (target >= a.count || (i > 0 && target <= iv.index(i - 1)))
            return fail(what + " has sparse index " + num(target) + " (entry " + num(i) +
                        ") that is past the elements or does not increase");
        std::memcpy(out + size_t(target) * elementSize, values.value() + i * elementSize, elementSize);
    }
    return {};
}

// The view of an accessor without a buffer view (zeros) or with a sparse part, copied and packed.
Result<AccessorView> viewCopied(const tinygltf::Model& model, int index, const char* role, int type,
                                unsigned allowedComponentTypes) {
    Result<const tinygltf::Accessor*> checked =
        checkedAccessor(model, index, role, type, allowedComponentTypes);
    if (!checked) return fail(checked.error());
    const tinygltf::Accessor& a = *checked.value();
    const std::string what = accessorName(index, role);
    const size_t elementSize = componentSize(a.componentType) * size_t(componentCount(type));
    if (a.bufferView < 0 && a.count > kMaxBufferlessElements)
        return fail(what + " has " + num(a.count) +
                    " elements without a buffer view, more than the limit of " + num(kMaxBufferlessElements));
    auto bytes = std::make_shared<std::vector<unsigned char>>();
    if (a.bufferView >= 0) {
        Result<AccessorView> dense = viewDense(model, index, role, type, allowedComponentTypes);
        if (!dense) return fail(dense.error());
        bytes->resize(a.count * elementSize); // the dense range was checked: no overflow
        for (size_t i = 0; i < a.count; ++i)
            std::memcpy(bytes->data() + i * elementSize, dense->data + i * dense->stride, elementSize);
    } else {
        bytes->assign(a.count * elementSize, 0);
    }
    if (a.sparse.isSparse)
        if (Status s = applySparse(model, a, what, elementSize, bytes->data()); !s) return fail(s.error());
    AccessorView v = viewOf(a, elementSize);
    v.data = bytes->data();
    v.owned = std::move(bytes);
    return v;
}

} // namespace

Result<AccessorView> viewAccessor(const tinygltf::Model& model, int index, const char* role, int type,
                                  unsigned allowedComponentTypes) {
    if (validIndex(index, model.accessors.size())) {
        const tinygltf::Accessor& a = model.accessors[size_t(index)];
        if (a.sparse.isSparse || a.bufferView < 0)
            return viewCopied(model, index, role, type, allowedComponentTypes);
    }
    return viewDense(model, index, role, type, allowedComponentTypes);
}

Result<std::vector<glm::vec3>> readVec3(const tinygltf::Model& model, int index, const char* role,
                                        unsigned allowedComponentTypes, size_t count) {
    Result<const tinygltf::Accessor*> checked =
        checkedAccessor(model, index, role, TINYGLTF_TYPE_VEC3, allowedComponentTypes);
    if (!checked) return fail(checked.error());
    const std::string what = accessorName(index, role);
    if (checked.value()->count != count)
        return fail(what + " has " + num(checked.value()->count) + " elements, the primitive has " +
                    num(count) + " vertices");
    Result<AccessorView> view = viewAccessor(model, index, role, TINYGLTF_TYPE_VEC3, allowedComponentTypes);
    if (!view) return fail(view.error());
    std::vector<glm::vec3> out(count);
    for (size_t i = 0; i < count; ++i) {
        out[i] = view->vec<3>(i);
        if (!finite(out[i])) return fail(what + " element " + num(i) + " is not finite (NaN or Inf)");
    }
    return out;
}

} // namespace spatter::gltf
