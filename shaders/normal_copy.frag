// The G-buffer blend's copy of the host's normals under the decal boxes (DecalProjector): the same
// boxes as the decal pass, each fragment copying the host's normal at its pixel, so that the decals
// then read the surface as it was before any of them, at the cost of the pixels they cover.
layout(binding = 1) uniform sampler2D s_normal;
layout(location = 0) out vec4 o_normal;

void main() {
    o_normal = texelFetch(s_normal, ivec2(gl_FragCoord.xy), 0);
}
