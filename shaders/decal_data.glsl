// Decal instances as the projector stores them (DecalProjector::resources()), shared by the projector's
// shaders and any host's debug drawing: the decals (bounds at binding 9 and bodies at binding 3, 44
// bytes in all), the decal types (binding 8), the visible list of the last draw (binding 4), the
// SPATTER_DECAL_* flags, and the octahedral normal encoding. Mirrored on the C++ side by
// render/src/GpuLayouts.hpp (DecalBoundsGpu, DecalBodyGpu, DecalTypeGpu).

#include "decal_flags.glsl"

// One decal is kept in two parts: its bounds (binding 9, 16 bytes), all the culling's pass over every
// decal reads, and its body (binding 3, 28 bytes), the rest of its box and what is its own; the rest
// of its look comes from its type, and the decal ID it clips to from its object.
struct DecalBounds {
    vec3 center;       // the box's centre in object space
    uint objectRadius; // bits 16-30: the box's bounding radius in object space, the high half of a
                       // positive float rounded up, without its sign (0: a decal that cannot be
                       // drawn); bit 31: the object index has bits past the low 16; bits 0-15: the
                       // object index's low 16 bits
};

// Scalars only: an array of them has a stride of 28 bytes.
struct DecalBody {
    uint frameLow, frameHigh; // the packed frame (spatter/core/PackedFrame.hpp), its low and high 32 bits
    float halfWidth, halfHeight;
    float halfDepth; // 0 for a decal that cannot be drawn
    uint look;       // type index (bits 0-15), the object index's bits 16-23 (16-23), opacity in
                     // 1/255 (24-31)
    uint slant;      // the projection axis's slopes along the tangent and bitangent as two halves
                     // (spatter/core/DecalProjection.hpp). A left-handed frame: bit 62 of the frame
};

layout(std430, binding = 9) readonly buffer DecalBoundsBuffer {
    DecalBounds decalBounds[];
};

layout(std430, binding = 3) readonly buffer DecalBuffer {
    DecalBody decalBodies[];
};

// The object index of a decal from the low bits in its bounds and its body's look.
uint decalObject(uint boundsObjectRadius, uint look) {
    return (boundsObjectRadius & 0xffffu) | (look & 0x00ff0000u);
}

// One decal's two parts together.
struct DecalRecord {
    vec4 centerDepth; // xyz: the box's centre in object space; w: its half depth
    uvec2 frame;
    vec2 halfSize;
    uvec3 info; // x: object index; y: type, opacity (DecalBody::look); z: slant
};

DecalRecord decalRecord(uint index) {
    DecalBody b = decalBodies[index];
    DecalBounds bounds = decalBounds[index];
    DecalRecord r;
    r.centerDepth = vec4(bounds.center, b.halfDepth);
    r.frame = uvec2(b.frameLow, b.frameHigh);
    r.halfSize = vec2(b.halfWidth, b.halfHeight);
    r.info = uvec3(decalObject(bounds.objectRadius, b.look), b.look, b.slant);
    return r;
}

// A decal type as the shaders use it.
struct DecalTypeRecord {
    vec4 tint;   // rgb; a: alpha
    uvec4 info;  // x: texture layer; y: SPATTER_DECAL_* flags; z: 1 when decals of the type can be drawn,
                 // 2 when the host draws them itself (DecalProjector::setHostDrawn), 0 otherwise;
                 // w: the layer's cutout (spatterInCutout)
    vec4 params; // x: cosine of the largest accepted angle; y: roughness written
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
    uvec4 info;          // x: object index, y: texture layer, z: SPATTER_DECAL_* flags, w: cutout
    vec4 params;         // x: cosine of the largest accepted angle; y: roughness written
};

// The rotation of a packed frame (PackedFrame.hpp): columns tangent, bitangent (not yet mirrored),
// normal. The three smallest components of the unit quaternion are 20 bits each, offset by 2^19,
// in the order w, x, y, z without the largest, which bits 60-61 name.
mat3 unpackFrame(uvec2 bits) {
    const float scale = 0.70710678 / 524287.0;
    // No arrays and no component picked by a variable: either makes the compiler keep the values in
    // memory, for which a GPU driver reserves room for every invocation it can hold.
    vec3 small = (vec3(float(bitfieldExtract(bits.y, 8, 20)),
                       float((bitfieldExtract(bits.y, 0, 8) << 12) | (bits.x >> 20)),
                       float(bitfieldExtract(bits.x, 0, 20))) -
                  524288.0) *
                 scale;
    float sum = small.x * small.x;
    sum += small.y * small.y;
    sum += small.z * small.z;
    float big = sqrt(max(0.0, 1.0 - sum));
    uint largest = bitfieldExtract(bits.y, 28, 2);
    vec4 q = vec4(largest == 0u ? big : small.x, // w, x, y, z
                  largest == 0u ? small.x : largest == 1u ? big : small.y,
                  largest == 3u ? small.z : largest == 2u ? big : small.y,
                  largest == 3u ? big : small.z);
    q = normalize(q);
    float w = q.x, x = q.y, y = q.z, z = q.w;
    return mat3(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y),
                2.0 * (x * y - w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z + w * x),
                2.0 * (x * z + w * y), 2.0 * (y * z - w * x), 1.0 - 2.0 * (x * x + y * y));
}

uint decalTypeIndex(DecalRecord r) {
    return r.info.y & 0xffffu;
}

DecalData unpackDecal(DecalRecord r) {
    DecalTypeRecord t = decalTypes[decalTypeIndex(r)];
    DecalData d;
    mat3 frame = unpackFrame(r.frame); // orthonormal: its inverse is its transpose
    bool mirrored = (r.frame.y & (1u << 30)) != 0u; // bit 62 of the packed frame
    if (mirrored) frame[1] = -frame[1];
    vec3 center = r.centerDepth.xyz;
    vec3 h = vec3(r.halfSize, r.centerDepth.w);
    // The box's depth axis runs along the projection axis, normal + slant.x * tangent + slant.y *
    // bitangent: a parallelepiped whose rows of the inverse subtract the slant's share of the depth.
    vec2 slant = unpackHalf2x16(r.info.z);
    vec3 depthAxis = frame[2] + slant.x * frame[0] + slant.y * frame[1];
    vec3 rows[3] = vec3[3]((frame[0] - slant.x * frame[2]) / h.x, (frame[1] - slant.y * frame[2]) / h.y,
                           frame[2] / h.z);
    for (int k = 0; k < 3; ++k) {
        d.objectToBox[k] = vec4(rows[k], -dot(rows[k], center));
        d.boxToObject[k] = vec4(frame[0][k] * h.x, frame[1][k] * h.y, depthAxis[k] * h.z, center[k]);
    }
    d.tangent = vec4(frame[0], h.x);
    d.bitangent = vec4(frame[1], h.y);
    d.normal = vec4(frame[2], h.z);
    d.tint = vec4(t.tint.rgb, t.tint.a * float(r.info.y >> 24) / 255.0);
    d.info = uvec4(r.info.x, t.info.x,
                   t.info.y | (mirrored ? SPATTER_DECAL_MIRRORED : 0u) | (r.info.z != 0u ? SPATTER_DECAL_SLANTED : 0u),
                   t.info.w);
    d.params = t.params;
    return d;
}

DecalData decalData(uint index) {
    return unpackDecal(decalRecord(index));
}

// Corner `c` (of the unit box [-1, 1]^3) of the part of decal `d`'s box that can show: the box over
// its texture's cutout, or the whole box for a wrap-around decal, whose texture coordinates are pushed
// off the box's.
vec3 shownCorner(DecalData d, vec3 c) {
    if ((d.info.z & SPATTER_DECAL_WRAP) != 0u) return c;
    vec4 cut = spatterCutout(d.info.w) * 2.0 - 1.0;
    return vec3(mix(cut.xy, cut.zw, c.xy * 0.5 + 0.5), c.z);
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

