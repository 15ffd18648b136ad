#include "spatter/placement/DecalLooks.hpp"

namespace spatter {

namespace {

// The looks' names, in DecalTexture order.
const char* const kLookNames[] = {"bullet_hole", "blood", "paint", "scorch"};
static_assert(sizeof(kLookNames) / sizeof(kLookNames[0]) == size_t(DecalTexture::Count),
              "one name per built-in decal texture");

} // namespace

Result<int> parseDecalLook(const std::string& name) {
    for (int k = 0; k < int(DecalTexture::Count); ++k)
        if (name == kLookNames[k]) return k;
    if (name == "mixed") return kMixedLooks;
    return fail("unknown decal look '" + name + "' (bullet_hole, blood, paint, scorch or mixed)");
}

DecalType withLook(DecalType base, int texture) {
    base.texture = texture;
    base.tint = glm::vec4(1.0f);
    base.roughness = -1.0f;
    if (texture == int(DecalTexture::Blood)) base.roughness = 0.25f;
    if (texture == int(DecalTexture::Paint)) base.tint = glm::vec4(0.9f, 0.75f, 0.1f, 1.0f);
    if (texture == int(DecalTexture::Scorch)) base.roughness = 0.95f;
    return base;
}

int lookOf(int look, size_t k) {
    return look >= 0 ? look : int(k % size_t(DecalTexture::Count));
}

} // namespace spatter
