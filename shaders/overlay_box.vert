// Overlay: the 12 edges of every visible decal's box, one instanced GL_LINES draw of 24 vertices
// per decal (instance i is visibleDecals[i]). Depth bias as in overlay_mesh.vert.
#include "common.glsl"

layout(location = 0) uniform float u_depthScale;

flat out vec3 v_color;

// Corner i of the unit cube: x from bit 0, y from bit 1, z from bit 2; edges along x, y, then z.
const int kEdgeCorners[24] = int[24](0, 1, 2, 3, 4, 5, 6, 7,  0, 2, 1, 3, 4, 6, 5, 7,  0, 4, 1, 5, 2, 6, 3, 7);

void main() {
    // With culling on the GPU the count drawn may be an earlier frame's: an entry past this frame's
    // list may name a decal that is gone.
    uint index = visibleDecals[uint(gl_InstanceID)];
    if (index >= uint(decalBodies.length())) {
        gl_Position = vec4(0.0, 0.0, 2.0, 1.0); // outside the clip volume: nothing drawn
        v_color = vec3(0.0);
        return;
    }
    DecalData d = decalData(index);
    ObjectData o = objects[d.info.x];
    int corner = kEdgeCorners[gl_VertexID];
    vec4 local = vec4((corner & 1) != 0 ? 1.0 : -1.0, (corner & 2) != 0 ? 1.0 : -1.0,
                      (corner & 4) != 0 ? 1.0 : -1.0, 1.0);
    vec3 objectPos = vec3(dot(d.boxToObject[0], local), dot(d.boxToObject[1], local), dot(d.boxToObject[2], local));
    vec3 rel = (o.model * vec4(objectPos, 1.0)).xyz;
    gl_Position = u_viewProj * vec4(rel * u_depthScale, 1.0);
    uint id = o.info.x; // the object decal ID the decal clips to
    v_color = id == 0u ? vec3(1.0, 0.72, 0.1) : idColor(id);
}
