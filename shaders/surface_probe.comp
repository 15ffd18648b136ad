// The drawn surface along lines (SurfaceProbe, DecalProjector::findSurface): for each line, the first
// point from its start where it passes from in front of the surface the host's depth holds to behind
// it, where the camera sees it, and the normal the depth of the pixels around that point gives. Lines
// and results are in view space: the frame block's view is the identity here, so the projector's
// "camera-relative world" is view space.
#include "projector.glsl"

layout(local_size_x = 64) in;

layout(binding = 0) uniform sampler2D s_depth;
layout(binding = 2) uniform usampler2D s_ids;
#if defined(FACE_NORMALS)
layout(binding = 3) uniform sampler2D s_faceNormals; // each pixel's triangle face normal, the host's encoding
layout(location = 4) uniform mat3 u_faceToView;      // decoded face normals to view space
#endif
layout(location = 0) uniform uint u_lines;
layout(location = 1) uniform ivec4 u_rect;   // the host's viewport: x, y, width, height
layout(location = 2) uniform int u_checkIds; // 1: the surface a line meets must carry its object ID
layout(location = 3) uniform vec2 u_pixel;   // a pixel's height at view z: u_pixel.x * z + u_pixel.y

layout(std430, binding = 5) readonly buffer SurfaceLines {
    vec4 lines[]; // two a line: from (w: its object's decal ID, or kAnyObject), to
};
layout(std430, binding = 6) writeonly buffer SurfacePoints {
    vec4 points[]; // two a line: the point (w: 1 when found), the unit normal facing the camera (w: the
                   // object decal ID there, 0 without an ID texture)
};

const int kMaxSteps = 1024; // samples along a line, about one a pixel
const int kRefine = 16;     // halvings of the step in which the line passes behind the surface
// A line passes behind the surface there when the depth jumps by at most this many pixels' size, plus
// kJumpOfLength of the line's length, across the crossing; more is an edge of something in front.
const float kJumpPixels = 8.0, kJumpOfLength = 0.05;

const float kFar = 3.0e38, kMissing = 1.0e30;
const uint kAnyObject = 256u; // a line's ID that the surface of any object matches
const int kUnknown = 0, kFront = 1, kBehind = 2;

// Where view-space point `p` falls on the host's window, in pixels; false behind the camera.
bool windowOf(vec3 p, out vec2 w) {
    vec4 c = u_viewProj * vec4(p, 1.0);
    if (!(c.w > 0.0)) return false;
    w = (c.xy / c.w * 0.5 + 0.5) / u_viewport.zw + u_viewport.xy;
    return true;
}

bool onViewport(ivec2 pixel) {
    return all(greaterThanEqual(pixel, u_rect.xy)) && all(lessThan(pixel, u_rect.xy + u_rect.zw));
}

// The host's surface at `pixel` (view space); false for the background and off the viewport.
bool surfaceAt(ivec2 pixel, out vec3 s) {
    if (!onViewport(pixel)) return false;
    float depth = texelFetch(s_depth, pixel, 0).r;
    if (isBackground(depth)) return false;
    s = hostPosition(vec2(pixel) + 0.5, depth);
    return true;
}

// Whether `p` lies in front of the surface the camera sees through it (or before the background),
// behind it, or neither can be told (behind the camera, off the viewport). `gap`: how far in front of
// or behind that surface it lies, along the view direction (infinite before the background).
int sideOf(vec3 p, out ivec2 pixel, out float gap) {
    vec2 w;
    gap = 0.0;
    if (!windowOf(p, w)) return kUnknown;
    pixel = ivec2(floor(w));
    if (!onViewport(pixel)) return kUnknown;
    vec3 s;
    if (!surfaceAt(pixel, s)) {
        gap = kFar;
        return kFront;
    }
    gap = abs(p.z - s.z);
    return p.z > s.z ? kFront : kBehind;
}

// The unit normal of the surface at `pixel` from the depth around it, facing the camera: of the four
// quadrants around the pixel, the one whose pixels lie flattest on the plane of its two steps (a
// triangle's pixels are coplanar; a crease or an edge beside the pixel bends the others).
bool depthNormalAt(ivec2 pixel, out vec3 n) {
    vec3 s;
    if (!surfaceAt(pixel, s)) return false;
    float best = kFar;
    for (int q = 0; q < 4; ++q) {
        ivec2 dx = ivec2((q & 1) == 0 ? 1 : -1, 0), dy = ivec2(0, (q & 2) == 0 ? 1 : -1);
        vec3 x1, y1, d, x2, y2;
        if (!surfaceAt(pixel + dx, x1) || !surfaceAt(pixel + dy, y1)) continue;
        vec3 c = cross(x1 - s, y1 - s);
        if (!(dot(c, c) > 0.0)) continue;
        c = normalize(c);
        float bend = 0.0; // a pixel with no surface counts as bent far out, but less than no quadrant
        bend += surfaceAt(pixel + dx + dy, d) ? abs(dot(c, d - s)) : kMissing;
        bend += surfaceAt(pixel + 2 * dx, x2) ? abs(dot(c, x2 - s)) : kMissing;
        bend += surfaceAt(pixel + 2 * dy, y2) ? abs(dot(c, y2 - s)) : kMissing;
        if (bend < best) {
            best = bend;
            n = c;
        }
    }
    if (best == kFar) return false;
    if (dot(n, s) > 0.0) n = -n;
    return true;
}

#if defined(FACE_NORMALS)
const float kCosCrease = 0.8660; // cos 30 degrees: neighbouring faces farther apart meet at a crease

// The host's face normal at `pixel` (unit, facing the camera); false where it holds none.
bool faceNormalAt(ivec2 pixel, out vec3 n) {
    vec3 s;
    if (!surfaceAt(pixel, s)) return false;
    vec4 texel = texelFetch(s_faceNormals, pixel, 0);
    if (all(equal(texel.xyz, vec3(0.0)))) return false;
    n = u_faceToView * decodeHostNormal(texel);
    if (!(dot(n, n) > 0.0)) return false;
    n = normalize(n);
    if (dot(n, s) > 0.0) n = -n;
    return true;
}

// Whether the face at `pixel` turns from `n` by more than a crease's angle.
bool creased(ivec2 pixel, vec3 n) {
    vec3 m;
    return faceNormalAt(pixel, m) && dot(m, n) < kCosCrease;
}

// Whether a face beside `pixel` turns from `n` by more than a crease's angle: the meet may lie on
// that face within the pixel, whose centre shows the other. (No array of steps: an indexed local
// array can cost a driver local memory for every invocation.)
bool besideACrease(ivec2 pixel, vec3 n) {
    return creased(pixel + ivec2(1, 0), n) || creased(pixel - ivec2(1, 0), n) ||
           creased(pixel + ivec2(0, 1), n) || creased(pixel - ivec2(0, 1), n);
}
#endif

// The unit normal of the surface at `pixel`, facing the camera, and whether it is the host's face
// normal: that where it gives one away from creases, else the depth's (whose flattest quadrant keeps
// to the meet's side of a crease).
bool normalAt(ivec2 pixel, out vec3 n, out bool face) {
    face = false;
#if defined(FACE_NORMALS)
    if (faceNormalAt(pixel, n) && !besideACrease(pixel, n)) {
        face = true;
        return true;
    }
#endif
    return depthNormalAt(pixel, n);
}

#if defined(FACE_NORMALS)
// Where the line from `a` to `b` meets the plane of the triangle seen at `pixel` (through its surface
// point there, normal `n`, which is then that of the pixel the meet falls in): the meet within the
// triangle rather than within the pixel's depth, where it lies within two pixels of `p`, the meet the
// depth gave; else `p`.
vec3 onFacePlane(vec3 a, vec3 b, vec3 p, inout ivec2 pixel, inout vec3 n) {
    vec3 s, d = b - a, m;
    if (!surfaceAt(pixel, s) || abs(dot(n, d)) < 1e-6 * length(d)) return p;
    vec3 q = a + d * (dot(n, s - a) / dot(n, d));
    float reach = 2.0 * abs(u_pixel.x * p.z + u_pixel.y);
    if (!(length(q - p) <= reach)) return p;
    vec2 w;
    if (windowOf(q, w) && ivec2(floor(w)) != pixel && faceNormalAt(ivec2(floor(w)), m)) {
        pixel = ivec2(floor(w));
        n = m;
    }
    return q;
}
#endif

// Narrows the step [lo, hi] of the line from `a` to `b` in which it passes from in front of the surface
// to behind it, and whether the depth is continuous across the crossing found (not an edge).
bool refine(vec3 a, vec3 b, inout float lo, inout float hi, out ivec2 pixel) {
    float gapLo = 0.0, gapHi = 0.0;
    ivec2 p;
    sideOf(mix(a, b, lo), p, gapLo);
    sideOf(mix(a, b, hi), pixel, gapHi);
    for (int i = 0; i < kRefine; ++i) {
        float mid = 0.5 * (lo + hi), gap;
        int side = sideOf(mix(a, b, mid), p, gap);
        if (side == kUnknown) return false;
        if (side == kFront) {
            lo = mid;
            gapLo = gap;
        } else {
            hi = mid;
            gapHi = gap;
            pixel = p;
        }
    }
    vec3 at = mix(a, b, hi);
    float jump = kJumpPixels * abs(u_pixel.x * at.z + u_pixel.y) + kJumpOfLength * length(b - a);
    return gapLo <= jump && gapHi <= jump;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_lines) return;
    vec3 a = lines[2u * i].xyz, b = lines[2u * i + 1u].xyz;
    uint id = uint(lines[2u * i].w);
    points[2u * i] = vec4(0.0);
    points[2u * i + 1u] = vec4(0.0);
    vec2 wa, wb;
    int steps = kMaxSteps;
    if (windowOf(a, wa) && windowOf(b, wb)) steps = clamp(int(ceil(length(wb - wa))) + 1, 2, kMaxSteps);
    ivec2 pixel;
    float gap;
    int before = sideOf(a, pixel, gap);
    for (int k = 1; k <= steps; ++k) {
        float t = float(k) / float(steps);
        int side = sideOf(mix(a, b, t), pixel, gap);
        if (before == kFront && side == kBehind) {
            float lo = float(k - 1) / float(steps), hi = t;
            vec3 n;
            bool face;
            if (refine(a, b, lo, hi, pixel)) {
                uint seen = u_checkIds != 0 ? texelFetch(s_ids, pixel, 0).r : 0u;
                if ((u_checkIds == 0 || id == kAnyObject || seen == id) && normalAt(pixel, n, face)) {
                    vec3 p = mix(a, b, 0.5 * (lo + hi));
#if defined(FACE_NORMALS)
                    if (face) p = onFacePlane(a, b, p, pixel, n);
#endif
                    points[2u * i] = vec4(p, 1.0);
                    points[2u * i + 1u] = vec4(n, float(seen));
                    return;
                }
            }
        }
        before = side;
    }
}
