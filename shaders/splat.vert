// Texture-space decals: a mesh drawn into its own UV layout. Each vertex goes to its UV (the whole
// unit square is the viewport, v = 0 at the bottom row, as the geometry pass samples it) and carries
// its object-space position, normal and tangent in the pose that is drawn (u_posed: morphed, and
// skinned then taken from camera-relative world to object space by u_worldToObject), which is the
// pose its decals were placed against; without a pose, or under a vertex animation, its rest pose.
// Instance i splats the decal visibleDecals[u_first + i]; MASK draws the UV coverage mask instead.
#include "common.glsl"
#include "pose.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_tangent;

layout(location = 0) uniform uint u_first;
layout(location = 2) uniform uint u_object;
layout(location = 3) uniform uint u_posed;
layout(location = 4) uniform mat4 u_worldToObject;

out vec3 v_position;
out vec3 v_normal;
out vec4 v_tangent;
flat out uint v_decal;

void main() {
    gl_Position = vec4(a_uv * 2.0 - 1.0, 0.0, 1.0);
    vec3 p = a_position;
    vec3 n = a_normal;
    vec3 t = a_tangent.xyz;
#ifdef MASK
    v_decal = 0u;
#else
    v_decal = visibleDecals[u_first + uint(gl_InstanceID)];
    PoseObject po = poseObjects[u_object];
    uint vertex = uint(gl_VertexID);
    if (u_posed != 0u) morphVertex(po, vertex, p, n, t);
    if (u_posed != 0u && po.skin.y != 0u) {
        mat4 m = u_worldToObject * skinMatrix(po, vertex);
        p = (m * vec4(p, 1.0)).xyz;
        n = safeNormalize(normalTransform(mat3(m)) * n);
        t = mat3(m) * t;
    }
#endif
    v_position = p;
    v_normal = n;
    v_tangent = vec4(t, a_tangent.w);
}
