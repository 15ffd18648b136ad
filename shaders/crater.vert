// Volumetric decals (render/src/VolumetricDecals.hpp): the crater or its footprint, from crater
// space (unit radius, rim at z = 0, depth along -z) to the camera-relative world, cut by the crater's
// clip planes (where the solid it is carved into ends: Decal::clips).
#include "common.glsl"
#include "crater.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

layout(location = 0) uniform uint u_base; // the draw's first record

out gl_PerVertex {
    vec4 gl_Position;
    float gl_ClipDistance[2];
};

out vec3 v_world;
out vec3 v_normal;
out float v_depth;      // crater-space depth below the rim, >= 0
flat out uint v_crater; // index of the record

void main() {
    v_crater = u_base + uint(gl_InstanceID);
    Crater c = craters[v_crater];
    vec4 world = c.model * vec4(a_position, 1.0);
    v_world = world.xyz;
    v_normal = mat3(c.normalMatrix) * a_normal;
    v_depth = -a_position.z;
    gl_ClipDistance[0] = c.clips[0].w - dot(c.clips[0].xyz, a_position);
    gl_ClipDistance[1] = c.clips[1].w - dot(c.clips[1].xyz, a_position);
    gl_Position = u_viewProj * world;
}
