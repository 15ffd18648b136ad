// Geometry pass: one object's render mesh, positions relative to the eye, after its morph targets
// and vertex animation (deformPoint) when it has them, then skinned when it has a skin (pose.glsl;
// only once a pose is set, u_posed).
#include "common.glsl"
#include "pose.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_tangent;

layout(location = 0) uniform uint u_object;
layout(location = 2) uniform uint u_posed; // 1: skin and morph with the pose buffers

out vec3 v_normal;
out vec2 v_uv;
out vec4 v_tangent;
out vec3 v_position; // relative to the eye

void main() {
    ObjectData o = objects[u_object];
    vec3 p = a_position;
    vec3 n = a_normal;
    vec3 t = a_tangent.xyz;
    PoseObject po = poseObjects[u_object];
    uint vertex = uint(gl_VertexID);
    if (u_posed != 0u) morphVertex(po, vertex, p, n, t);
    p = deformPoint(o, p, n, t);
    v_uv = a_uv;
    if (u_posed != 0u && po.skin.y != 0u) {
        mat4 skin = skinMatrix(po, vertex);
        v_position = (skin * vec4(p, 1.0)).xyz;
        gl_Position = u_viewProj * vec4(v_position, 1.0);
        v_normal = safeNormalize(normalTransform(mat3(skin)) * n); // joints may scale unevenly
        v_tangent = vec4(mat3(skin) * t, a_tangent.w);
        return;
    }
    v_position = (o.model * vec4(p, 1.0)).xyz;
    gl_Position = u_viewProj * vec4(v_position, 1.0);
    v_normal = mat3(o.normalMatrix) * n;
    v_tangent = vec4(mat3(o.model) * t, a_tangent.w);
}
