// Skinning and morph targets in the geometry pass. Joint influences and morph deltas are uploaded
// with the scene; joint matrices (camera-relative: they take a skinned vertex from bind space to
// camera-relative world space) and morph weights every frame. Mirrored on the C++ side by
// render/src/GpuLayouts.hpp (PoseObjectGpu, InfluenceGpu, PoseBinding).

struct PoseObject {
    uvec4 skin;  // x: first influence; y: influences per vertex (0: not skinned); z: first joint
    uvec4 morph; // x: first delta (three per target and vertex); y: targets; z: first weight; w: vertices
};

struct Influence {
    uint joint;
    float weight;
};

layout(std430, binding = 10) readonly buffer PoseObjectBuffer {
    PoseObject poseObjects[];
};
layout(std430, binding = 11) readonly buffer InfluenceBuffer {
    Influence influences[];
};
layout(std430, binding = 12) readonly buffer MorphDeltaBuffer {
    vec4 morphDeltas[];
};
layout(std430, binding = 13) readonly buffer JointBuffer {
    mat4 joints[];
};
layout(std430, binding = 14) readonly buffer MorphWeightBuffer {
    float morphWeights[];
};

// Unit `v`, or `v` itself when it is zero.
vec3 safeNormalize(vec3 v) {
    float l = length(v);
    return l > 0.0 ? v / l : v;
}

// Adds the object's weighted morph target deltas of `vertex` to its position, normal and tangent;
// the normal comes out of unit length again (it is interpolated like an unmorphed one).
void morphVertex(PoseObject po, uint vertex, inout vec3 p, inout vec3 n, inout vec3 t) {
    if (po.morph.y == 0u) return;
    for (uint k = 0u; k < po.morph.y; ++k) {
        float w = morphWeights[po.morph.z + k];
        if (w == 0.0) continue;
        uint d = po.morph.x + 3u * (k * po.morph.w + vertex);
        p += w * morphDeltas[d].xyz;
        n += w * morphDeltas[d + 1u].xyz;
        t += w * morphDeltas[d + 2u].xyz;
    }
    n = safeNormalize(n);
}

// The weighted sum of the joint matrices that influence `vertex`: bind space to camera-relative world.
mat4 skinMatrix(PoseObject po, uint vertex) {
    mat4 m = mat4(0.0);
    uint first = po.skin.x + vertex * po.skin.y;
    for (uint k = 0u; k < po.skin.y; ++k) {
        Influence i = influences[first + k];
        if (i.weight > 0.0) m += i.weight * joints[po.skin.z + i.joint];
    }
    return m;
}

// Inverse transpose of `a` up to a positive factor (its cofactor matrix, sign-corrected), for normals.
mat3 normalTransform(mat3 a) {
    mat3 c = mat3(cross(a[1], a[2]), cross(a[2], a[0]), cross(a[0], a[1]));
    return determinant(a) < 0.0 ? -c : c;
}
