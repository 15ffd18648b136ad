#include "GltfAccessor.hpp"

namespace spatter::gltf {

Result<AccessorView> viewAccessor(const tinygltf::Model& model, int index, const char* role, int type,
                                  unsigned allowedComponentTypes) {
    if (!validIndex(index, model.accessors.size()))
        return fail(std::string(role) + " refers to accessor " + std::to_string(index) +
                    ", which does not exist");
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    const std::string what = "accessor " + std::to_string(index) + " (" + role + ")";
    if (a.sparse.isSparse) return fail(what + " is sparse, which is not supported");
    if (a.type != type) return fail(what + " is " + typeName(a.type) + ", expected " + typeName(type));
    const size_t size = componentSize(a.componentType);
    if (size == 0 || (componentBit(a.componentType) & allowedComponentTypes) == 0)
        return fail(what + " has component type " + std::to_string(a.componentType) + ", which " + role +
                    " cannot use");
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

    AccessorView v;
    v.present = true;
    v.count = a.count;
    v.stride = stride;
    v.componentType = a.componentType;
    v.normalized = a.normalized;
    if (a.count == 0) return v;
    size_t span = 0;
    if (!mulAdd(a.count - 1, stride, elementSize, span) || !rangeInside(a.byteOffset, span, view.byteLength))
        return fail(what + " reads past the end of buffer view " + std::to_string(a.bufferView) + " (" +
                    num(a.count) + " elements from byte " + num(a.byteOffset) + ", the view has " +
                    num(view.byteLength) + " bytes)");
    v.data = model.buffers[size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
    return v;
}

} // namespace spatter::gltf
