// Geometry pass: one object's render mesh, positions relative to the eye, after the object's
// vertex animation (deformPoint) when it has one.
#include "common.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_tangent;

layout(location = 0) uniform uint u_object;

out vec3 v_normal;
out vec2 v_uv;
out vec4 v_tangent;

void main() {
    ObjectData o = objects[u_object];
    vec3 n = a_normal;
    vec3 t = a_tangent.xyz;
    vec3 p = deformPoint(o, a_position, n, t);
    gl_Position = u_viewProj * (o.model * vec4(p, 1.0));
    v_normal = mat3(o.normalMatrix) * n;
    v_tangent = vec4(mat3(o.model) * t, a_tangent.w);
    v_uv = a_uv;
}
