// Decal pass: one instanced unit cube per visible decal. The instance's decal index comes from the
// visible list (gl_InstanceID: the list is in draw order); its object-space box is carried to camera-relative
// world space by its object's transform, and the inverse, world -> unit box, goes to the fragment
// shader together with the decal frame in world space.
#include "projector.glsl"
#include "depth_axis.glsl"

flat out vec4 v_worldToBox[3]; // rows: camera-relative world -> unit box [-1, 1]^3
flat out vec4 v_tangent;       // xyz: world unit tangent; w: half width (world units)
flat out vec4 v_bitangent;     // w: half height
flat out vec4 v_normal;        // xyz: world unit decal normal; w: half depth
flat out vec3 v_axis;          // world unit axis the box is projected along (depth_axis.glsl)
flat out vec4 v_tint;
flat out uvec4 v_info;         // x: object decal ID, y: texture layer, z: SPATTER_DECAL_* flags, w: cutout
flat out vec2 v_params;        // x: cosine of the largest accepted angle, y: roughness

void main() {
    DecalData d = decalData(visibleDecals[uint(gl_InstanceID)]);
    ProjectorObject o = objects[d.info.x];

    int corner = gl_VertexID; // of the cube's eight: x from bit 0, y from bit 1, z from bit 2 (indexed draw)
    vec3 c = vec3((corner & 1) != 0 ? 1.0 : -1.0, (corner & 2) != 0 ? 1.0 : -1.0, (corner & 4) != 0 ? 1.0 : -1.0);
    // A mirroring box-to-world transform turns the winding inside out; mirroring the cube in its
    // own space (it maps onto itself) turns it back.
    bool mirrored = ((d.info.z & SPATTER_DECAL_MIRRORED) != 0u) != (o.info.y != 0u);
    if (mirrored) c.x = -c.x;
#ifndef COVERAGE
    c = shownCorner(d, c); // coverage is the whole box's
#endif

    vec4 local = vec4(c, 1.0);
    vec3 objectPos = vec3(dot(d.boxToObject[0], local), dot(d.boxToObject[1], local), dot(d.boxToObject[2], local));
    gl_Position = u_viewProj * (o.model * vec4(objectPos, 1.0));

    WorldDecal w = worldDecal(d, o);
    v_worldToBox = w.worldToBox;
    v_tangent = w.tangent;
    v_bitangent = w.bitangent;
    v_normal = w.normal;
    v_axis = spatterDepthAxis(w.worldToBox[0].xyz, w.worldToBox[1].xyz, w.normal.xyz);
    v_tint = d.tint;
    v_info = uvec4(o.info.x, d.info.y, d.info.z, d.info.w);
    v_params = d.params.xy;
}
