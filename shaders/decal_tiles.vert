// Tiled decal resolve: a quad over each screen tile that has decals (an instance per tile); the
// quads of empty tiles collapse to a point and draw nothing, so pixels without decals cost nothing.
#include "projector.glsl"
#include "forward_data.glsl"

// The corners of a quad as two counter-clockwise triangles.
const vec2 kCorners[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));

void main() {
    int tile = gl_InstanceID;
    if (spatterTiles[tile].y == 0u) {
        gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    ivec2 t = ivec2(tile % spatterTileGrid.z, tile / spatterTileGrid.z);
    vec2 viewport = 1.0 / u_viewport.zw;
    vec2 corner = min((vec2(t) + kCorners[gl_VertexID]) * float(spatterTileInfo.x), viewport);
    gl_Position = vec4(corner / viewport * 2.0 - 1.0, 0.0, 1.0);
}
