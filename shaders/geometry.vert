// Geometry pass: one object's render mesh, positions relative to the eye.
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
    gl_Position = u_viewProj * (o.model * vec4(a_position, 1.0));
    v_normal = mat3(o.normalMatrix) * a_normal;
    v_tangent = vec4(mat3(o.model) * a_tangent.xyz, a_tangent.w);
    v_uv = a_uv;
}
