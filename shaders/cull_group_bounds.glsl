// The bounds of the draw order's groups of 256 places (GroupBounds; cull_bounds.comp writes them,
// cull_groups.comp reads them): up to kGroupBoxes axis-aligned boxes a group, each in the space of
// one object the group's decals lie on, holding the bounding spheres of its decals there, so that a
// group whose boxes all lie outside the view needs none of its decals read, however its objects move.

const uint kGroupBoxes = 4u; // boxes a group: decals on more objects are tested by place

const uint kBoxUnused = 0u;  // no decal on a further object
const uint kBoxUsed = 1u;    // `center`, `extent` around the decals on `object`
const uint kBoxByPlace = 2u; // (first box) decals on more objects, or some the culling counts (the
                             // host's, or ones that cannot be drawn): tested one by one

struct GroupBox {
    vec3 center; // in the object's space
    uint object;
    vec3 extent; // half extents
    uint state;  // kBox*
};

layout(std430, binding = 10) buffer GroupBoundsBuffer {
    GroupBox groupBoxes[]; // kGroupBoxes a group
};
