// Volumetric decals (render/src/VolumetricDecals.hpp): one record per crater drawn, in draw order;
// a draw covers the records from u_base on, one instance each.
struct Crater {
    mat4 model;        // crater space (unit radius, rim at z = 0, depth along -z) -> camera-relative world
    mat4 normalMatrix; // inverse transpose of the model's 3x3 part
    vec4 plane;        // xyz: unit decal axis (world); w: its dot with the rim centre (camera-relative)
    vec4 clips[2];     // crater space: kept where dot(xyz, p) <= w (an unused one keeps everything)
    float tolerance;   // largest view-depth difference between the footprint and the surface
    float cosAngle;    // cosine of the largest angle between the surface normal and the decal axis
    float depth;       // depth of the crater's deepest point, crater units
    uint id;           // object decal ID
};

layout(std430, binding = 5) readonly buffer CraterBuffer {
    Crater craters[];
};
