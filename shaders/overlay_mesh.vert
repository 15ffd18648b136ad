// Overlay: the per-object wireframes (collision proxies), all objects in one indexed GL_LINES draw.
// Each vertex carries its object's index, so the object's current transform places it. The
// camera-relative position is scaled towards the eye by u_depthScale (1 - depth bias), which leaves
// its place on screen unchanged and brings it slightly in front of a surface it lies on.
#include "common.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in uint a_object;

layout(location = 0) uniform float u_depthScale;

flat out vec3 v_color;

void main() {
    ObjectData o = objects[a_object];
    vec3 rel = (o.model * vec4(a_position, 1.0)).xyz;
    gl_Position = u_viewProj * vec4(rel * u_depthScale, 1.0);
    uint id = o.info.x;
    v_color = id == 0u ? vec3(0.15, 0.95, 0.35) : idColor(id);
}
