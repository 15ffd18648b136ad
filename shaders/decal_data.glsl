// Decal instances as the projector stores them (DecalProjector::resources()), shared by the projector's
// shaders and any host's debug drawing: the DecalData buffer (binding 3), the visible list of the last
// draw (binding 4), the SPATTER_DECAL_* flags, and the octahedral normal encoding. Mirrored on the C++ side
// by render/src/GpuLayouts.hpp (DecalGpu).

#include "decal_flags.glsl"

struct DecalData {
    vec4 objectToBox[3]; // rows: object -> unit box
    vec4 boxToObject[3]; // rows: unit box -> object
    vec4 tangent;        // xyz: object-space unit tangent; w: half width
    vec4 bitangent;      // w: half height
    vec4 normal;         // w: half depth
    vec4 tint;           // rgb tint; a: tint alpha * opacity
    uvec4 info;          // x: object index, y: object decal ID, z: texture layer, w: SPATTER_DECAL_* flags
    vec4 params;         // x: cosine of the largest accepted angle; y: roughness written
};

layout(std430, binding = 3) readonly buffer DecalBuffer {
    DecalData decals[];
};

layout(std430, binding = 4) readonly buffer VisibleBuffer {
    uint visibleDecals[];
};

// Octahedral normal encoding (Cigolle et al. 2014): unit vector <-> [-1, 1]^2.
vec2 signNotZero(vec2 v) {
    return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0);
}

vec2 encodeNormal(vec3 n) {
    vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    return n.z <= 0.0 ? (1.0 - abs(p.yx)) * signNotZero(p) : p;
}

vec3 decodeNormal(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * signNotZero(n.xy);
    return normalize(n);
}

