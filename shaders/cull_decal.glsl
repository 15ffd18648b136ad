// A decal's object and bounding radius as the GPU culling's passes over the draw order read them from
// its 16-byte bounds (cull.comp, cull_bounds.comp); needs projector.glsl.

// The decal's object index: the low 16 bits in its bounds, the next 8 from its body's look only where
// there are more than 65,536 objects.
uint boundsObject(uint i, DecalBounds b) {
    return u_params.y > 65536.0 ? decalObject(b.objectRadius, decalBodies[i].look) : b.objectRadius & 0xffffu;
}

// The bounding radius in object space (0: a decal that cannot be drawn).
float boundsRadius(DecalBounds b) {
    return uintBitsToFloat(b.objectRadius & 0xffff0000u);
}
