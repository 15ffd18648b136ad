// Texture-space decals: a mesh drawn into its own UV layout. Each vertex goes to its UV (the whole
// unit square is the viewport, v = 0 at the bottom row, as the geometry pass samples it) and carries
// its rest-pose object-space position, normal and tangent. Instance i splats the decal
// visibleDecals[u_first + i]; MASK draws the UV coverage mask instead.
#include "common.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_tangent;

layout(location = 0) uniform uint u_first;

out vec3 v_position;
out vec3 v_normal;
out vec4 v_tangent;
flat out uint v_decal;

void main() {
    gl_Position = vec4(a_uv * 2.0 - 1.0, 0.0, 1.0);
    v_position = a_position;
    v_normal = a_normal;
    v_tangent = a_tangent;
#ifdef MASK
    v_decal = 0u;
#else
    v_decal = visibleDecals[u_first + uint(gl_InstanceID)];
#endif
}
