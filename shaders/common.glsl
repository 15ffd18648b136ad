// Shared declarations of spatter's renderer: the per-frame block, the object and material buffers,
// the decal data (decal_data.glsl, shared with the projector) and the helpers every pass uses.
// Mirrored on the C++ side by render/src/GpuLayouts.hpp (keep both in step).

layout(std140, binding = 0) uniform FrameBlock {
    mat4 u_viewProj;       // camera-relative world -> clip (reversed-Z)
    mat4 u_view;           // camera-relative world -> view (a rotation)
    mat4 u_invView;        // view -> camera-relative world
    vec4 u_projection;     // x = P[0][0], y = P[1][1], z = A, w = B: depth = (A z + B) / -z
    vec4 u_viewport;       // width, height, 1 / width, 1 / height
    vec4 u_lightDirection; // xyz: unit, towards the light; w: intensity
    vec4 u_lightColor;     // rgb; w: exposure
    vec4 u_skyAmbient;
    vec4 u_groundAmbient;
    vec4 u_depthRange;     // x: nearest, y: farthest scene distance; z: decal fade start
};

struct ObjectData {
    mat4 model;         // object -> camera-relative world
    mat4 normalMatrix;  // upper left 3x3: inverse transpose of model
    uvec4 info;         // x: object decal ID, y: 1 when model mirrors, z: 1 with a decal layer
    vec4 deformA;       // xyz: displacement direction * amplitude (0: none); w: frequency
    vec4 deformB;       // xyz: unit wave direction; w: phase at this frame's time
};

// The object's vertex animation (spatter/render/Deformation.hpp) applied to the object-space point
// p: returns the moved point and carries the normal n and tangent t with the map's Jacobian
// J = I + a g^T (a: displacement, g: gradient of the wave), n by J^-T (Sherman-Morrison).
vec3 deformPoint(ObjectData o, vec3 p, inout vec3 n, inout vec3 t) {
    vec3 a = o.deformA.xyz;
    if (dot(a, a) == 0.0) return p;
    float theta = o.deformA.w * dot(o.deformB.xyz, p) + o.deformB.w;
    vec3 g = o.deformA.w * cos(theta) * o.deformB.xyz;
    t += a * dot(g, t);
    n -= g * (dot(a, n) / max(1.0 + dot(a, g), 1e-3));
    return p + a * sin(theta);
}

layout(std430, binding = 1) readonly buffer ObjectBuffer {
    ObjectData objects[];
};

struct MaterialData {
    vec4 baseColor;
    vec4 params;  // x: roughness, y: metallic, z: normal scale
    uvec4 flags;  // x: has base colour texture, y: has normal texture
};

layout(std430, binding = 2) readonly buffer MaterialBuffer {
    MaterialData materials[];
};

#include "decal_data.glsl"

// View-space position of the scene point behind window position `fragCoord` with reversed-Z
// depth `depth` (> 0).
vec3 viewPositionFromDepth(vec2 fragCoord, float depth) {
    vec2 ndc = fragCoord * u_viewport.zw * 2.0 - 1.0;
    float z = -u_projection.w / (depth + u_projection.z);
    return vec3(ndc.x * -z / u_projection.x, ndc.y * -z / u_projection.y, z);
}

// Camera-relative world position of the same point.
vec3 worldPositionFromDepth(vec2 fragCoord, float depth) {
    return mat3(u_invView) * viewPositionFromDepth(fragCoord, depth);
}

// Colour of an 8-bit object decal ID (sRGB-encoded): ID 0, static geometry, dark grey; every other
// ID a bright hashed colour. The ids view and the overlays use it.
vec3 idColor(uint id) {
    if (id == 0u) return vec3(0.25);
    uint h = id * 2654435761u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return 0.35 + 0.65 * vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) / 255.0;
}

// Linear to sRGB-encoded colour, for the output image (an RGBA8 target, encoded in the shader so
// that readback gives exactly these bytes).
vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
