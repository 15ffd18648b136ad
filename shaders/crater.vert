// Volumetric decals (render/src/VolumetricDecals.hpp): the crater or its footprint, from crater
// space (unit radius, rim at z = 0, depth along -z) to the camera-relative world.
#include "common.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

layout(location = 0) uniform mat4 u_model;
layout(location = 1) uniform mat4 u_normalMatrix;

out vec3 v_world;
out vec3 v_normal;
out float v_depth; // crater-space depth below the rim, >= 0

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world = world.xyz;
    v_normal = mat3(u_normalMatrix) * a_normal;
    v_depth = -a_position.z;
    gl_Position = u_viewProj * world;
}
