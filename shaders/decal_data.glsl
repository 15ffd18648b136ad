// Decal instances as the projector stores them (DecalProjector::resources()), shared by the projector's
// shaders and any host's debug drawing: the decal records (binding 3, 64 bytes each), the decal types
// (binding 8), the visible list of the last draw (binding 4), the SPATTER_DECAL_* flags, and the
// octahedral normal encoding. Mirrored on the C++ side by render/src/GpuLayouts.hpp (DecalRecordGpu,
// DecalTypeGpu).

#include "decal_flags.glsl"

// One decal: its box and what is its own; the rest comes from its type.
struct DecalRecord {
    vec4 objectToBox[3]; // rows: object space -> unit box [-1, 1]^3 (the inverse of the box's
                         // axes and centre); all zero for a decal that cannot be drawn
    uvec4 info;          // x: object index; y: type index (bits 0-15), object decal ID (16-23), SPATTER_DECAL_MIRRORED
                         // when the frame is left-handed (24-31); z: opacity (float bits); w: 32-bit decal ID
};

// A decal type as the shaders use it.
struct DecalTypeRecord {
    vec4 tint;   // rgb; a: alpha
    uvec4 info;  // x: texture layer; y: SPATTER_DECAL_* flags; z: 1 when decals of the type can be drawn
    vec4 params; // x: cosine of the largest accepted angle; y: roughness written
};

layout(std430, binding = 3) readonly buffer DecalBuffer {
    DecalRecord decalRecords[];
};

layout(std430, binding = 8) readonly buffer DecalTypeBuffer {
    DecalTypeRecord decalTypes[];
};

layout(std430, binding = 4) readonly buffer VisibleBuffer {
    uint visibleDecals[];
};

// A decal unpacked from its record and its type.
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

// Whether record `r` can be drawn at all (its box is not degenerate; its type and object are checked apart).
bool decalRecordValid(DecalRecord r) {
    return r.objectToBox[0].xyz != vec3(0.0) && r.objectToBox[1].xyz != vec3(0.0) &&
           r.objectToBox[2].xyz != vec3(0.0);
}

uint decalTypeIndex(DecalRecord r) {
    return r.info.y & 0xffffu;
}

DecalData unpackDecal(DecalRecord r) {
    DecalTypeRecord t = decalTypes[decalTypeIndex(r)];
    DecalData d;
    mat3 toBox = transpose(mat3(r.objectToBox[0].xyz, r.objectToBox[1].xyz, r.objectToBox[2].xyz));
    mat3 axes = inverse(toBox); // columns: the box's half axes in object space
    vec3 center = -(axes * vec3(r.objectToBox[0].w, r.objectToBox[1].w, r.objectToBox[2].w));
    for (int k = 0; k < 3; ++k) {
        d.objectToBox[k] = r.objectToBox[k];
        d.boxToObject[k] = vec4(axes[0][k], axes[1][k], axes[2][k], center[k]);
    }
    vec3 h = vec3(length(axes[0]), length(axes[1]), length(axes[2]));
    d.tangent = vec4(axes[0] / h.x, h.x);
    d.bitangent = vec4(axes[1] / h.y, h.y);
    d.normal = vec4(axes[2] / h.z, h.z);
    d.tint = vec4(t.tint.rgb, t.tint.a * uintBitsToFloat(r.info.z));
    d.info = uvec4(r.info.x, (r.info.y >> 16) & 0xffu, t.info.x, t.info.y | (r.info.y >> 24));
    d.params = t.params;
    return d;
}

DecalData decalData(uint index) {
    return unpackDecal(decalRecords[index]);
}

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

