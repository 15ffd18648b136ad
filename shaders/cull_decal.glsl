// A decal's object and bounding radius as the GPU culling's passes over the draw order read them from
// its 16-byte bounds (cull.comp, cull_bounds.comp); needs projector.glsl.

// The decal's object index: the low 16 bits in its bounds, the next 8 from its body's look only where
// there are more than 65,536 objects; with fewer, an index past 16 bits names no object (none known).
uint boundsObject(uint i, DecalBounds b) {
    if (u_params.y > 65536.0) return decalObject(b.objectRadius, decalBodies[i].look);
    return (b.objectRadius & 0x80000000u) != 0u ? 0xffffffffu : b.objectRadius & 0xffffu;
}

// The bounding radius in object space (0: a decal that cannot be drawn).
float boundsRadius(DecalBounds b) {
    return uintBitsToFloat(b.objectRadius & 0x7fff0000u);
}
