// The bounds of the draw order's groups of 256 places (GroupBounds; cull_bounds.comp writes them,
// cull_groups.comp reads them): an axis-aligned box in one object's space holding the bounding
// spheres of every decal of the group, so that a group whose box lies outside the view needs none of
// its decals read.

const uint kGroupEmpty = 0u;  // no decal: nothing to draw or count
const uint kGroupPlain = 1u;  // every decal drawable by the projector, on one object: `center`, `extent`
const uint kGroupByPlace = 2u; // decals on several objects, or some the culling counts: tested one by one

struct GroupBound {
    vec3 center; // of the box, in the object's space
    uint object;
    vec3 extent; // half extents of the box
    uint state; // kGroup*
};

layout(std430, binding = 10) buffer GroupBoundsBuffer {
    GroupBound groupBounds[];
};
