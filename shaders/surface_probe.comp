// The drawn surface along lines (SurfaceProbe, DecalProjector::findSurface): for each line, the first
// point from its start where it passes from in front of the surface the host's depth holds to behind
// it (or, for a line that starts behind it, from behind to in front), where the camera sees it, and
// the normal there: the host's face normal where the frame has them, else the one the depth of the
// pixels around that point gives. Lines
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
// A line passes behind the surface there when the depth jumps by at most this many pixels' size across
// the crossing (a surface seen up to about 83 degrees from its normal); more is an edge of something
// in front. Not scaled by the line's length: a shot searched from its origin passes many edges.
const float kJumpPixels = 8.0;

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
const float kCosSameFace = 0.99996; // cos 0.5 degrees: faces nearer are one, blurred by the encoding

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
#endif

// The unit normal of the surface at `pixel`, facing the camera, and whether it is the host's face
// normal: that where it gives one, else the depth's.
bool normalAt(ivec2 pixel, out vec3 n, out bool face) {
    face = false;
#if defined(FACE_NORMALS)
    if (faceNormalAt(pixel, n)) {
        face = true;
        return true;
    }
#endif
    return depthNormalAt(pixel, n);
}

#if defined(FACE_NORMALS)
// Where the line from `a` along `d` crosses the plane through `s` with normal `n`, as a multiple of `d`;
// false where it runs along the plane.
bool crossing(vec3 a, vec3 d, vec3 n, vec3 s, out float t) {
    float along = dot(n, d);
    if (abs(along) < 1e-6 * length(d)) return false;
    t = dot(n, s - a) / along;
    return true;
}

// Whether `q` falls on the window within the 3 x 3 pixels around `pixel`.
bool around(vec3 q, ivec2 pixel) {
    vec2 w;
    return windowOf(q, w) && all(lessThanEqual(abs(w - vec2(pixel) - 0.5), vec2(1.5)));
}

// Where the line from `a` to `b` meets the drawn triangles around `pixel`, in which the depth gave the
// meet `p`, and the normal `n` there (on entry the face normal at `pixel`). A pixel shows one
// triangle, so within a pixel of an edge the meet may lie on the triangle beside it: the planes of the
// triangles that the 3 x 3 pixels around show are tried, each within the depth's continuity of the
// meet and crossing the line within those pixels. Across a convex edge the surface lies behind both
// planes, so a line `entering` it (from in front) meets it at the later of the two crossings and one
// leaving it (from behind) at the earlier; across a concave edge the surface lies behind either plane,
// and the other way round. `p` where the pixel's own plane crosses the line outside those pixels.
vec3 onDrawnFace(vec3 a, vec3 b, bool entering, vec3 p, ivec2 pixel, inout vec3 n) {
    vec3 d = b - a, s;
    float t, jump = kJumpPixels * abs(u_pixel.x * p.z + u_pixel.y);
    if (!surfaceAt(pixel, s) || !crossing(a, d, n, s, t) || !around(a + d * t, pixel)) return p;
    for (int y = -1; y <= 1; ++y) {
        for (int x = -1; x <= 1; ++x) {
            vec3 m, r;
            float u;
            ivec2 at = pixel + ivec2(x, y);
            if (at == pixel || !faceNormalAt(at, m) || dot(m, n) > kCosSameFace || !surfaceAt(at, r) ||
                !(abs(r.z - s.z) <= jump) || !crossing(a, d, m, r, u) || !around(a + d * u, pixel))
                continue;
            bool convex = dot(n - m, r - s) < 0.0;
            if (convex == entering ? u > t : u < t) {
                t = u;
                n = m;
                s = r;
            }
        }
    }
    return a + d * t;
}
#endif

// Narrows the step [lo, hi] of the line from `a` to `b` in which it passes from side `from` of the
// surface (in front of it or behind it) to the other, and whether the depth is continuous across the
// crossing found (not an edge).
bool refine(vec3 a, vec3 b, int from, inout float lo, inout float hi, out ivec2 pixel) {
    float gapLo = 0.0, gapHi = 0.0;
    ivec2 p;
    sideOf(mix(a, b, lo), p, gapLo);
    sideOf(mix(a, b, hi), pixel, gapHi);
    for (int i = 0; i < kRefine; ++i) {
        float mid = 0.5 * (lo + hi), gap;
        int side = sideOf(mix(a, b, mid), p, gap);
        if (side == kUnknown) return false;
        if (side == from) {
            lo = mid;
            gapLo = gap;
        } else {
            hi = mid;
            gapHi = gap;
            pixel = p;
        }
    }
    vec3 at = mix(a, b, hi);
    float jump = kJumpPixels * abs(u_pixel.x * at.z + u_pixel.y);
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
        if (before != kUnknown && side != kUnknown && side != before) {
            float lo = float(k - 1) / float(steps), hi = t;
            vec3 n;
            bool face;
            if (refine(a, b, before, lo, hi, pixel)) {
                uint seen = u_checkIds != 0 ? texelFetch(s_ids, pixel, 0).r : 0u;
                if ((u_checkIds == 0 || id == kAnyObject || seen == id) && normalAt(pixel, n, face)) {
                    vec3 p = mix(a, b, 0.5 * (lo + hi));
#if defined(FACE_NORMALS)
                    if (face) p = onDrawnFace(a, b, before == kFront, p, pixel, n);
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
