// The projector's declarations: its per-draw block (binding 0), its object buffer (binding 1), the
// decal data (decal_data.glsl) and the host's conventions, picked by defines:
//   depth    DEPTH_LINEAR (view distance) or window depth, CLIP_MINUS_ONE (GL's default clip depth;
//            otherwise zero to one), STANDARD_Z (far is 1; otherwise reversed: far is 0)
//   normals  NO_NORMALS, NORMAL_WORLD_SIGNED, NORMAL_WORLD_UNORM, NORMAL_VIEW_UNORM, otherwise
//            octahedral world normals in RG
//   target   DBUFFER: the decal buffers (normals written world space, signed), else the host's
// Mirrored on the C++ side by render/src/ProjectorLayouts.hpp (keep both in step).
#include "decal_data.glsl"

layout(std140, binding = 0) uniform ProjectorFrame {
    mat4 u_viewProj;      // camera-relative world -> clip
    mat4 u_view;          // camera-relative world -> view
    mat4 u_invView;       // view -> camera-relative world
    mat4 u_invProjection; // clip -> view
    vec4 u_viewport;      // x, y of the host's viewport, 1 / width, 1 / height
    vec4 u_params;        // x: fade start (fraction of the half-depth); y: object count
};

struct ProjectorObject {
    mat4 model;         // object -> camera-relative world
    mat4 normalMatrix;  // upper left 3x3: inverse transpose of model
    mat4 worldToObject; // camera-relative world -> object
    uvec4 info;         // x: object decal ID, y: 1 when model mirrors, z: 1 when it is singular (its
                        // decals collapse), w: 1 when the host draws its decals itself
};

layout(std430, binding = 1) readonly buffer ProjectorObjects {
    ProjectorObject objects[];
};

// The view-space point of the host's projection behind window position `fragCoord` at normalised
// device depth `ndcZ`.
vec3 unproject(vec2 fragCoord, float ndcZ) {
    vec2 ndc = (fragCoord - u_viewport.xy) * u_viewport.zw * 2.0 - 1.0;
    vec4 v = u_invProjection * vec4(ndc, ndcZ, 1.0);
    return v.xyz / v.w;
}

// Whether the host's depth sample is background (no surface).
bool isBackground(float depth) {
#if defined(DEPTH_LINEAR)
    return !(depth > 0.0);
#elif defined(STANDARD_Z)
    return !(depth < 1.0);
#else
    return !(depth > 0.0);
#endif
}

// The camera-relative world position of the host's surface behind `fragCoord` (not background).
vec3 hostPosition(vec2 fragCoord, float depth) {
#ifdef DEPTH_LINEAR
    // Any two points on the pixel's ray; the one at view distance `depth` along -Z.
    vec3 a = unproject(fragCoord, 0.25), b = unproject(fragCoord, 0.75);
    vec3 viewPos = mix(a, b, (-depth - a.z) / (b.z - a.z));
#elif defined(CLIP_MINUS_ONE)
    vec3 viewPos = unproject(fragCoord, depth * 2.0 - 1.0);
#else
    vec3 viewPos = unproject(fragCoord, depth);
#endif
    return (u_invView * vec4(viewPos, 1.0)).xyz;
}

// The host's normal sample as a world-space unit vector (not with NO_NORMALS).
vec3 decodeHostNormal(vec4 s) {
#if defined(NORMAL_WORLD_SIGNED)
    return normalize(s.xyz);
#elif defined(NORMAL_WORLD_UNORM)
    return normalize(s.xyz * 2.0 - 1.0);
#elif defined(NORMAL_VIEW_UNORM)
    return normalize(mat3(u_invView) * (s.xyz * 2.0 - 1.0));
#else
    return decodeNormal(s.xy);
#endif
}

// A world-space unit normal in the host's encoding, as the normal target takes it (DBUFFER: the
// decal buffer's, world space and signed).
vec4 encodeHostNormal(vec3 n) {
#if defined(NORMAL_WORLD_SIGNED) || defined(DBUFFER)
    return vec4(n, 0.0);
#elif defined(NORMAL_WORLD_UNORM)
    return vec4(n * 0.5 + 0.5, 0.0);
#elif defined(NORMAL_VIEW_UNORM)
    return vec4(mat3(u_view) * n * 0.5 + 0.5, 0.0);
#else
    return vec4(encodeNormal(n), 0.0, 0.0);
#endif
}

// A decal in camera-relative world space, as its box is drawn (decal.vert) or binned (forward):
// rows of world -> unit box, and the unit tangent, bitangent and normal with the half width, height and
// depth in w.
struct WorldDecal {
    vec4 worldToBox[3];
    vec4 tangent;
    vec4 bitangent;
    vec4 normal;
};

WorldDecal worldDecal(DecalData d, ProjectorObject o) {
    WorldDecal w;
    for (int r = 0; r < 3; ++r) w.worldToBox[r] = d.objectToBox[r] * o.worldToObject;
    vec3 t = mat3(o.model) * d.tangent.xyz;
    vec3 b = mat3(o.model) * d.bitangent.xyz;
    float depthScale = length(mat3(o.model) * d.normal.xyz);
    w.tangent = vec4(normalize(t), length(t) * d.tangent.w);
    w.bitangent = vec4(normalize(b), length(b) * d.bitangent.w);
    w.normal = vec4(normalize(mat3(o.normalMatrix) * d.normal.xyz), depthScale * d.normal.w);
    return w;
}
