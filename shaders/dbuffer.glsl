// spatter's DBuffer, applied in a host's material or lighting shader. DecalProjector::draw with
// ProjectorPath::DBuffer renders the decals into three textures of the projector's
// (ProjectorResources::dbufferAlbedo, dbufferNormal, dbufferMaterial), the size of the host's depth
// texture and addressed by the same pixels. Each holds the decals' contribution premultiplied by
// their alpha in RGB and, in A, the fraction of the surface's own value that shows through (1 where
// no decal lies). Applying them gives what blending the decals into the G-buffer in turn would give:
//   value = surface * A + RGB
// The host binds the three textures to samplers of its choosing and calls these functions with the
// pixel (ivec2(gl_FragCoord.xy) in a full-screen pass over the same viewport). Nothing here needs the
// projector's other resources.

// Albedo in linear RGB (the buffer is SRGB8_ALPHA8, read back linear).
vec3 spatterDBufferAlbedo(sampler2D dbufferAlbedo, ivec2 pixel, vec3 albedo) {
    vec4 d = texelFetch(dbufferAlbedo, pixel, 0);
    return albedo * d.a + d.rgb;
}

// A world-space unit normal (RGBA16F, world space, signed). Decals change it only where their type
// has a normal map and the host gave the projector its normals.
vec3 spatterDBufferNormal(sampler2D dbufferNormal, ivec2 pixel, vec3 worldNormal) {
    vec4 d = texelFetch(dbufferNormal, pixel, 0);
    vec3 n = worldNormal * d.a + d.rgb;
    return dot(n, n) > 1e-12 ? normalize(n) : worldNormal;
}

// Roughness in [0, 1] (RGBA8, roughness in R), changed where a decal's type sets one.
float spatterDBufferRoughness(sampler2D dbufferMaterial, ivec2 pixel, float roughness) {
    vec4 d = texelFetch(dbufferMaterial, pixel, 0);
    return roughness * d.a + d.r;
}
