#include "spatter/core/GalleryScene.hpp"
#include "Pi.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/core/UvOverlap.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

namespace spatter {

namespace {

// Layout in metres (see GalleryScene.hpp).
constexpr float kHalfWidth = 10.0f;
constexpr float kFloorBack = -4.0f, kFloorFront = 8.0f;
constexpr float kWallTop = 4.0f, kWallBottom = -0.1f, kWallThickness = 0.4f;
constexpr float kBackWallFront = kFloorBack + kWallThickness; // z of the back wall's front face
constexpr float kSideWallFront = 4.0f;                        // side walls run from the back wall to here
constexpr float kTargetZ = -3.1f;                             // target origins (plate centre plane)
constexpr float kPlateY = 1.5f, kPlateRadius = 0.4f, kPlateHalfDepth = 0.03f;
constexpr float kTargetSpan = 5.0f; // targets spread over x in [-kTargetSpan, kTargetSpan]
constexpr int kMaxTargets = 8;

enum MaterialId {
    BrickRed,
    BrickGrey,
    Concrete,
    Wood,
    Metal,
    Stone,
    TargetWhite,
    TargetRed,
    SteelDark,
    Cloth
};

std::vector<Material> makeMaterials() {
    auto m = [](const char* name, glm::vec3 color, float roughness, float metallic) {
        Material mat;
        mat.name = name;
        mat.baseColorFactor = glm::vec4(color, 1.0f);
        mat.roughness = roughness;
        mat.metallic = metallic;
        return mat;
    };
    // Order matches MaterialId.
    return {m("brick_red", {0.56f, 0.22f, 0.16f}, 0.85f, 0.0f),
            m("brick_grey", {0.42f, 0.42f, 0.44f}, 0.9f, 0.0f),
            m("concrete", {0.5f, 0.49f, 0.46f}, 0.95f, 0.0f),
            m("wood", {0.55f, 0.38f, 0.2f}, 0.7f, 0.0f),
            m("metal", {0.62f, 0.64f, 0.67f}, 0.35f, 1.0f),
            m("stone", {0.72f, 0.67f, 0.58f}, 0.8f, 0.0f),
            m("target_white", {0.92f, 0.92f, 0.9f}, 0.5f, 0.0f),
            m("target_red", {0.8f, 0.07f, 0.05f}, 0.45f, 0.0f),
            m("steel_dark", {0.2f, 0.21f, 0.23f}, 0.5f, 1.0f),
            m("cloth", {0.2f, 0.32f, 0.55f}, 0.9f, 0.0f)};
}

// ---- deterministic noise -------------------------------------------------------------------------

uint32_t mixBits(uint32_t h) {
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

// Uniform in [0, 1) from integer coordinates and a seed.
float hashUnit(int x, int y, int z, uint32_t seed) {
    uint32_t h = mixBits(seed ^ 0x9e3779b9u);
    h = mixBits(h ^ uint32_t(x));
    h = mixBits(h ^ (uint32_t(y) * 0x85ebca6bu));
    h = mixBits(h ^ (uint32_t(z) * 0xc2b2ae35u));
    return float(h >> 8) * (1.0f / 16777216.0f);
}

// Smooth value noise in [-1, 1].
float valueNoise(const glm::vec3& p, uint32_t seed) {
    const glm::vec3 f = glm::floor(p);
    const glm::vec3 t = p - f;
    const glm::vec3 w = t * t * (3.0f - 2.0f * t);
    const int x = int(f.x), y = int(f.y), z = int(f.z);
    float c[2][2][2];
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 2; ++k)
                c[i][j][k] = hashUnit(x + i, y + j, z + k, seed);
    auto lerp = [](float a, float b, float s) { return a + (b - a) * s; };
    const float x00 = lerp(c[0][0][0], c[1][0][0], w.x), x10 = lerp(c[0][1][0], c[1][1][0], w.x);
    const float x01 = lerp(c[0][0][1], c[1][0][1], w.x), x11 = lerp(c[0][1][1], c[1][1][1], w.x);
    return 2.0f * lerp(lerp(x00, x10, w.y), lerp(x01, x11, w.y), w.z) - 1.0f;
}

// Fractal sum of value noise, in [-1, 1].
float fbm(const glm::vec3& p, uint32_t seed, int octaves) {
    float sum = 0.0f, amplitude = 1.0f, total = 0.0f, frequency = 1.0f;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * valueNoise(p * frequency, seed + uint32_t(o) * 0x632be5abu);
        total += amplitude;
        amplitude *= 0.5f;
        frequency *= 2.03f;
    }
    return sum / total;
}

// V-groove profile: `bottom` at distance 0 from a joint, rising linearly to `surface` at `halfWidth`.
float groove(float distance, float halfWidth, float bottom, float surface) {
    if (distance >= halfWidth) return surface;
    return bottom + (surface - bottom) * std::max(distance, 0.0f) / halfWidth;
}

// Lattice coordinates of V-grooves: each joint and the two groove edges, plus, when support > 0,
// lines that far outside the edges so that the edges' tilted normals do not shade the whole face.
void addGrooveBreaks(std::vector<float>& breaks, float joint, float halfWidth, float support = 0.0f) {
    breaks.insert(breaks.end(), {joint - halfWidth, joint, joint + halfWidth});
    if (support > 0.0f)
        breaks.insert(breaks.end(), {joint - halfWidth - support, joint + halfWidth + support});
}

glm::dmat4 translation(double x, double y, double z) {
    return glm::translate(glm::dmat4(1.0), glm::dvec3(x, y, z));
}

glm::dmat4 placed(double x, double y, double z, double yaw) {
    return glm::rotate(translation(x, y, z), yaw, glm::dvec3(0.0, 1.0, 0.0));
}

void setMaterial(Mesh& mesh, int material) {
    mesh.submeshes = {Submesh{0, uint32_t(mesh.indices.size()), material}};
}

// Detail-dependent resolution.
struct Resolution {
    int detail;
    float floorStep;  // floor grid spacing
    bool relief;      // bricks, floor joints, crate planks, arch blocks
    int bevelSteps;   // rows per face on rounded box edges
    float boxMaxEdge; // lattice step on walls, crates
    int pillarSegments;
    float pillarStep; // profile spacing along the pillar shaft
    float archStep;   // path spacing of the arch
    int archCornerSteps;
    int plateSegments;
};

Resolution resolutionFor(int detail) {
    switch (detail) {
    case 0:
        return {0, 1.0f, false, 1, 2.0f, 12, 1.2f, 0.6f, 1, 16};
    case 1:
        return {1, 0.5f, true, 1, 0.5f, 24, 0.4f, 0.25f, 1, 32};
    case 2:
        return {2, 0.25f, true, 2, 0.3f, 48, 0.1f, 0.1f, 2, 48};
    default:
        return {3, 0.125f, true, 3, 0.1f, 96, 0.05f, 0.05f, 3, 96};
    }
}

// ---- floor ---------------------------------------------------------------------------------------

// Concrete floor: a grid over the whole gallery with slab joints every 2 m (relief), per-slab
// settling and noise. Object space is centred; the transform moves it to z in [kFloorBack, kFloorFront].
SceneObject makeFloor(const Resolution& res, uint32_t seed) {
    const float halfDepth = 0.5f * (kFloorFront - kFloorBack);
    const float centerZ = 0.5f * (kFloorFront + kFloorBack);
    constexpr float kSlab = 2.0f, kJointHalf = 0.008f, kJointDepth = 0.006f;
    std::vector<float> xBreaks, zBreaks;
    if (res.relief) {
        for (float x = -kHalfWidth + kSlab; x < kHalfWidth - 0.5f * kSlab; x += kSlab)
            addGrooveBreaks(xBreaks, x, kJointHalf);
        for (float z = -halfDepth + kSlab; z < halfDepth - 0.5f * kSlab; z += kSlab)
            addGrooveBreaks(zBreaks, z, kJointHalf);
    }
    Mesh mesh = makeGrid(makeSamples(-kHalfWidth, kHalfWidth, res.floorStep, xBreaks),
                         makeSamples(-halfDepth, halfDepth, res.floorStep, zBreaks));
    const bool relief = res.relief;
    const bool fine = res.detail >= 2;
    displace(mesh, [=](const glm::vec3& p, const glm::vec3&) {
        float h = 0.008f * fbm(p * 0.6f, seed, 3);
        if (fine) h += 0.0015f * fbm(p * 6.0f, seed + 1u, 2);
        if (!relief) return h;
        const float sx = (p.x + kHalfWidth) / kSlab, sz = (p.z + halfDepth) / kSlab;
        const float ix = std::floor(sx), iz = std::floor(sz);
        const float settle = -0.003f * hashUnit(int(ix), int(iz), 0, seed + 2u);
        const float dx = kSlab * std::min(sx - ix, 1.0f - (sx - ix));
        const float dz = kSlab * std::min(sz - iz, 1.0f - (sz - iz));
        return h + groove(std::min(dx, dz), kJointHalf, -kJointDepth, settle);
    });
    setMaterial(mesh, Concrete);
    return makeSceneObject("floor", std::move(mesh), translation(0.0, 0.0, centerZ));
}

// ---- walls ---------------------------------------------------------------------------------------

struct WallSpec {
    const char* name;
    float length;
    glm::dmat4 transform; // maps the wall's local +Z face (the brick face) into the gallery
    int material;
    float brickLength, brickHeight;
};

// A bevelled slab of `length` x (kWallTop - kWallBottom) x kWallThickness centred on its origin, with
// brick relief on the +Z face: running bond, V-shaped mortar joints, bricks recessed by a few
// millimetres each with its own tilt. Relief only ever moves the face inward.
Mesh makeWall(const WallSpec& spec, const Resolution& res, uint32_t seed) {
    const glm::vec3 half(0.5f * spec.length, 0.5f * (kWallTop - kWallBottom), 0.5f * kWallThickness);
    const float floorY = -0.5f * (kWallTop + kWallBottom); // object y of the gallery floor (y = 0)
    constexpr float kBevel = 0.02f, kMortar = 0.012f, kMortarDepth = 0.015f;
    const float L = spec.brickLength, H = spec.brickHeight;

    BoxSettings box;
    box.halfExtents = half;
    box.bevel = kBevel;
    box.bevelSteps = res.bevelSteps;
    box.maxEdge = res.relief ? std::max(res.boxMaxEdge, 0.5f * L) : res.boxMaxEdge;
    if (res.relief) {
        // Head joints of both courses (every half brick) and bed joints from the floor up.
        for (int k = 1; - half.x + 0.5f * L * float(k) < half.x; ++k)
            addGrooveBreaks(box.breaks[0], -half.x + 0.5f * L * float(k), kMortar);
        const float firstBed = floorY - H * std::floor((floorY + half.y) / H);
        for (int k = 0; firstBed + H * float(k) < half.y; ++k)
            addGrooveBreaks(box.breaks[1], firstBed + H * float(k), kMortar);
    }
    Mesh mesh = makeBeveledBox(box);
    if (!res.relief) return mesh;

    const glm::vec2 flat(half.x - kBevel, half.y - kBevel);
    displace(mesh, [=](const glm::vec3& p, const glm::vec3&) {
        if (p.z < half.z - 1e-4f || std::fabs(p.x) > flat.x + 1e-4f || std::fabs(p.y) > flat.y + 1e-4f)
            return 0.0f;
        const float s = p.x + half.x, t = p.y - floorY;
        const float row = std::floor(t / H);
        const float lt = t - row * H;
        const float offset = (int(row) & 1) ? 0.5f * L : 0.0f;
        const float col = std::floor((s - offset) / L);
        const float ls = s - offset - col * L;
        const int r = int(row), c = int(col);
        const float recess = 0.002f + 0.004f * hashUnit(r, c, 0, seed);
        const float tiltS = 0.008f * (2.0f * hashUnit(r, c, 1, seed) - 1.0f);
        const float tiltT = 0.012f * (2.0f * hashUnit(r, c, 2, seed) - 1.0f);
        const float rough = 0.001f * fbm(glm::vec3(p.x, p.y, 0.0f) * 4.0f, seed + 7u, 2);
        const float surface = -(recess + 0.006f + tiltS * (ls - 0.5f * L) + tiltT * (lt - 0.5f * H)) + rough;
        const float toJoint = std::min(std::min(ls, L - ls), std::min(lt, H - lt));
        return groove(toJoint, kMortar, -kMortarDepth, surface);
    });
    return mesh;
}

// ---- pillars -------------------------------------------------------------------------------------

void appendArc(std::vector<glm::vec2>& profile, glm::vec2 center, float radius, float from, float to,
               int steps) {
    for (int k = 0; k <= steps; ++k) {
        const float a = from + (to - from) * float(k) / float(steps);
        profile.push_back(center + radius * glm::vec2(std::cos(a), std::sin(a)));
    }
}

// Metal pillar on a round plinth with a capital; the shaft has 12 flutes (from detail 2) and dents.
Mesh makePillar(const Resolution& res, uint32_t seed) {
    constexpr float kBaseR = 0.34f, kBaseTop = 0.25f, kShaftR = 0.24f, kCapBottom = 3.72f, kCapR = 0.32f;
    constexpr float kBottom = -0.05f, kTop = kWallTop, kRound = 0.03f;
    const int arcSteps = res.bevelSteps;
    std::vector<glm::vec2> profile;
    profile.emplace_back(0.0f, kBottom);
    profile.emplace_back(kBaseR, kBottom);
    appendArc(profile, {kBaseR - kRound, kBaseTop - kRound}, kRound, 0.0f, 0.5f * kPiF, arcSteps);
    // Concave fillet from the plinth's top into the shaft.
    appendArc(profile, {kShaftR + kRound, kBaseTop + kRound}, kRound, 1.5f * kPiF, kPiF, arcSteps);
    for (float y : makeSamples(kBaseTop + kRound, kCapBottom - kRound, res.pillarStep))
        if (y > kBaseTop + kRound && y < kCapBottom - kRound) profile.emplace_back(kShaftR, y);
    appendArc(profile, {kShaftR + kRound, kCapBottom - kRound}, kRound, kPiF, 0.5f * kPiF, arcSteps);
    appendArc(profile, {kCapR - kRound, kCapBottom + kRound}, kRound, 1.5f * kPiF, 2.0f * kPiF, arcSteps);
    appendArc(profile, {kCapR - kRound, kTop - kRound}, kRound, 0.0f, 0.5f * kPiF, arcSteps);
    profile.emplace_back(0.0f, kTop);
    Mesh mesh = makeLathe(profile, res.pillarSegments);

    const bool flutes = res.detail >= 2;
    displace(mesh, [=](const glm::vec3& p, const glm::vec3&) {
        const float r = std::sqrt(p.x * p.x + p.z * p.z);
        if (r > kShaftR + 1e-3f || p.y < kBaseTop + kRound || p.y > kCapBottom - kRound) return 0.0f;
        const float fade =
            std::min(1.0f, std::min(p.y - kBaseTop - kRound, kCapBottom - kRound - p.y) / 0.15f);
        float h = 0.0015f * fbm(p * 5.0f, seed, 3);
        if (flutes) h -= 0.012f * (0.5f - 0.5f * std::cos(12.0f * std::atan2(p.x, p.z)));
        return h * fade;
    });
    return mesh;
}

// ---- crates --------------------------------------------------------------------------------------

// A wooden crate centred on its origin: bevelled cube, flush frame boards around every face and
// three recessed planks per face panel (horizontal on the sides, along X on top and bottom).
Mesh makeCrate(float half, const Resolution& res, uint32_t seed) {
    constexpr float kBevel = 0.015f, kStep = 0.008f, kRecess = 0.012f, kGrooveHalf = 0.006f,
                    kGrooveDepth = 0.006f;
    constexpr float kSupport = 0.004f;
    constexpr int kPlanks = 3;
    const float frame = 0.16f * half;
    const float panel = half - frame - kStep; // half size of the recessed panel
    const float plank = 2.0f * panel / float(kPlanks);

    BoxSettings box;
    box.halfExtents = glm::vec3(half);
    box.bevel = kBevel;
    box.bevelSteps = res.bevelSteps;
    box.maxEdge = res.boxMaxEdge;
    if (res.relief)
        for (int a = 0; a < 3; ++a) {
            std::vector<float>& b = box.breaks[size_t(a)];
            for (float side : {-1.0f, 1.0f}) // frame step and its support lines
                b.insert(b.end(), {side * (half - frame + kSupport), side * (half - frame), side * panel,
                                   side * (panel - kSupport)});
            if (a == 2) continue; // grooves run across y (sides) and x (top, bottom)
            for (int k = 1; k < kPlanks; ++k)
                addGrooveBreaks(b, -panel + plank * float(k), kGrooveHalf, kSupport);
        }
    Mesh mesh = makeBeveledBox(box);
    if (!res.relief) return mesh;

    const float flat = half - kBevel;
    displace(mesh, [=](const glm::vec3& p, const glm::vec3&) {
        int axis = -1;
        for (int a = 0; a < 3; ++a)
            if (std::fabs(p[a]) >= half - 1e-4f) axis = a;
        if (axis < 0) return 0.0f;
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        if (std::fabs(p[u]) > flat + 1e-4f || std::fabs(p[v]) > flat + 1e-4f) return 0.0f;
        auto inset = [&](float c) { return std::clamp((half - frame - std::fabs(c)) / kStep, 0.0f, 1.0f); };
        const float weight = std::min(inset(p[u]), inset(p[v]));
        if (weight <= 0.0f) return 0.0f;
        const float across = axis == 1 ? p.x : p.y; // coordinate that crosses the planks
        const float rel = (std::clamp(across, -panel, panel) + panel) / plank;
        const int index = std::min(kPlanks - 1, int(rel));
        const float within = (rel - float(index)) * plank;
        const float warp = 0.002f * hashUnit(axis * 2 + (p[axis] > 0.0f ? 1 : 0), index, 0, seed);
        const float toJoint =
            std::min(index > 0 ? within : plank, index < kPlanks - 1 ? plank - within : plank);
        const float surface = -(kRecess + warp);
        return weight * groove(toJoint, kGrooveHalf, -(kRecess + kGrooveDepth), surface);
    });
    return mesh;
}

// ---- arch ----------------------------------------------------------------------------------------

// A stone arch: a rounded-rectangle section swept up the left pier, over a half circle and down
// the right pier, closed by flat caps below the floor. Block joints every ~0.7 m.
struct ArchShape {
    float centerRadius = 2.3f, spring = 1.6f, bottom = -0.05f, halfWidth = 0.3f, halfDepth = 0.3f;
    float pier() const { return spring - bottom; }
    float length() const { return 2.0f * pier() + kPiF * centerRadius; }
    // Path point and tangent at arc length s.
    void at(float s, glm::vec3& p, glm::vec3& t) const {
        if (s <= pier()) {
            p = {-centerRadius, bottom + s, 0.0f};
            t = {0.0f, 1.0f, 0.0f};
        } else if (s <= pier() + kPiF * centerRadius) {
            const float a = kPiF - (s - pier()) / centerRadius;
            p = {centerRadius * std::cos(a), spring + centerRadius * std::sin(a), 0.0f};
            t = {std::sin(a), -std::cos(a), 0.0f};
        } else {
            p = {centerRadius, spring - (s - pier() - kPiF * centerRadius), 0.0f};
            t = {0.0f, -1.0f, 0.0f};
        }
    }
    // Arc length of the section plane through p (inverse of at()).
    float arcLength(const glm::vec3& p) const {
        if (p.y <= spring) return p.x < 0.0f ? p.y - bottom : length() - (p.y - bottom);
        const float a = std::atan2(p.y - spring, p.x);
        return pier() + (kPiF - std::clamp(a, 0.0f, kPiF)) * centerRadius;
    }
};

Mesh makeArch(const Resolution& res, uint32_t seed) {
    const ArchShape shape;
    constexpr float kCorner = 0.03f, kJointHalf = 0.012f, kJointDepth = 0.012f;

    // Section: rounded rectangle in (n, b) = (outward in the arch plane, +Z), counter-clockwise.
    std::vector<glm::vec2> loop;
    const glm::vec2 inner(shape.halfWidth - kCorner, shape.halfDepth - kCorner);
    const glm::vec2 corners[4] = {
        {inner.x, inner.y}, {-inner.x, inner.y}, {-inner.x, -inner.y}, {inner.x, -inner.y}};
    for (int c = 0; c < 4; ++c) {
        const float a0 = 0.5f * kPiF * float(c);
        for (int k = 0; k <= res.archCornerSteps; ++k)
            loop.push_back(corners[c] +
                           kCorner *
                               glm::vec2(std::cos(a0 + 0.5f * kPiF * float(k) / float(res.archCornerSteps)),
                                         std::sin(a0 + 0.5f * kPiF * float(k) / float(res.archCornerSteps))));
        // Straight side to the next corner, subdivided.
        const glm::vec2 from = loop.back();
        const glm::vec2 to = corners[(c + 1) % 4] +
                             kCorner * glm::vec2(std::cos(a0 + 0.5f * kPiF), std::sin(a0 + 0.5f * kPiF));
        const int pieces =
            std::max(1, int(std::ceil(glm::length(to - from) / std::max(res.archStep, 0.15f))));
        for (int k = 1; k < pieces; ++k)
            loop.push_back(from + (to - from) * (float(k) / float(pieces)));
    }
    std::vector<float> loopV(loop.size());
    float perimeter = 0.0f;
    for (size_t k = 0; k < loop.size(); ++k) {
        loopV[k] = perimeter;
        perimeter += glm::length(loop[(k + 1) % loop.size()] - loop[k]);
    }

    // Block joints: three blocks per pier (the last at the spring line), nine voussoirs.
    std::vector<float> joints;
    for (int k = 1; k <= 3; ++k)
        joints.push_back(shape.pier() * float(k) / 3.0f);
    for (int k = 1; k < 9; ++k)
        joints.push_back(shape.pier() + kPiF * shape.centerRadius * float(k) / 9.0f);
    for (int k = 3; k >= 1; --k)
        joints.push_back(shape.length() - shape.pier() * float(k) / 3.0f);
    std::vector<float> breaks;
    if (res.relief)
        for (float j : joints)
            addGrooveBreaks(breaks, j, kJointHalf);
    const std::vector<float> path = makeSamples(0.0f, shape.length(), res.archStep, breaks);

    Mesh mesh;
    const uint32_t ringSize = uint32_t(loop.size());
    glm::vec3 p, t;
    shape.at(0.0f, p, t);
    mesh.positions.push_back(p);
    mesh.uvs.emplace_back(0.0f, 0.0f);
    for (float s : path) {
        shape.at(s, p, t);
        const glm::vec3 b(0.0f, 0.0f, 1.0f), n = glm::cross(b, t);
        for (size_t k = 0; k < loop.size(); ++k) {
            mesh.positions.push_back(p + loop[k].x * n + loop[k].y * b);
            mesh.uvs.emplace_back(s, std::min(loopV[k], perimeter - loopV[k]));
        }
    }
    shape.at(shape.length(), p, t);
    mesh.positions.push_back(p);
    mesh.uvs.emplace_back(shape.length(), 0.0f);
    const uint32_t endCap = uint32_t(mesh.positions.size() - 1);
    const uint32_t rings = uint32_t(path.size());
    for (uint32_t k = 0; k < ringSize; ++k) {
        const uint32_t k1 = (k + 1) % ringSize;
        mesh.indices.insert(mesh.indices.end(), {0u, 1u + k1, 1u + k});
        for (uint32_t r = 0; r + 1 < rings; ++r) {
            const uint32_t a = 1 + r * ringSize, c = a + ringSize;
            mesh.indices.insert(mesh.indices.end(), {a + k, a + k1, c + k1, a + k, c + k1, c + k});
        }
        const uint32_t last = 1 + (rings - 1) * ringSize;
        mesh.indices.insert(mesh.indices.end(), {last + k, last + k1, endCap});
    }
    computeNormals(mesh);
    computeTangents(mesh);
    if (!res.relief) return mesh;

    displace(mesh, [=](const glm::vec3& q, const glm::vec3&) {
        const float s = shape.arcLength(q);
        const auto next = std::upper_bound(joints.begin(), joints.end(), s);
        const int block = int(next - joints.begin());
        float toJoint = 1e9f;
        if (next != joints.end()) toJoint = *next - s;
        if (next != joints.begin()) toJoint = std::min(toJoint, s - *(next - 1));
        const float surface =
            -0.005f * hashUnit(block, 0, 0, seed) + 0.002f * fbm(q * 3.0f, seed + 1u, 2) - 0.002f;
        return groove(toJoint, kJointHalf, -kJointDepth, surface);
    });
    return mesh;
}

// ---- targets -------------------------------------------------------------------------------------

// A bullseye target on a stand. Origin on the floor below the plate centre; the plate faces +Z with
// its front at z = +kPlateHalfDepth. Submeshes: white plate, red rings, dark steel stand.
Mesh makeTarget(const Resolution& res) {
    constexpr float kRim = 0.01f, kBand = 0.08f, kGrooveHalf = 0.003f, kGrooveDepth = 0.0015f;
    constexpr int kBands = 5; // red bull, white, red, white, red rim band
    const int arcSteps = res.bevelSteps;
    // Lathe about +Y with y along the plate's axis, rotated to face +Z below.
    std::vector<glm::vec2> profile;
    profile.emplace_back(0.0f, -kPlateHalfDepth);
    for (float r : makeSamples(0.0f, kPlateRadius - kRim, res.relief ? 0.1f : 0.2f))
        if (r > 0.0f && r < kPlateRadius - kRim) profile.emplace_back(r, -kPlateHalfDepth);
    appendArc(profile, {kPlateRadius - kRim, -kPlateHalfDepth + kRim}, kRim, -0.5f * kPiF, 0.0f, arcSteps);
    appendArc(profile, {kPlateRadius - kRim, kPlateHalfDepth - kRim}, kRim, 0.0f, 0.5f * kPiF, arcSteps);
    std::vector<float> breaks;
    for (int b = 1; b < kBands; ++b) {
        if (res.relief)
            addGrooveBreaks(breaks, kBand * float(b), kGrooveHalf);
        else
            breaks.push_back(kBand * float(b));
    }
    const std::vector<float> radii =
        makeSamples(0.0f, kPlateRadius - kRim, res.relief ? 0.5f * kBand : kBand, breaks);
    for (size_t i = radii.size() - 1; i-- > 1;) {
        float y = kPlateHalfDepth;
        for (int b = 1; b < kBands; ++b)
            if (res.relief && std::fabs(radii[i] - kBand * float(b)) < 1e-5f) y -= kGrooveDepth;
        profile.emplace_back(radii[i], y);
    }
    profile.emplace_back(0.0f, kPlateHalfDepth);
    const Mesh plate = makeLathe(profile, res.plateSegments);

    Mesh mesh;
    appendMesh(mesh, plate,
               glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, kPlateY, 0.0f)), 0.5f * kPiF,
                           glm::vec3(1, 0, 0)));
    const size_t plateTriangles = mesh.triangleCount();
    constexpr float kPostR = 0.025f, kPostZ = -kPlateHalfDepth - 0.015f, kBaseHalfY = 0.03f;
    appendMesh(mesh, makeCylinder(kPostR, kPlateY - 0.05f, std::max(8, res.plateSegments / 4), 0.005f),
               glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.05f, kPostZ)));
    BoxSettings base;
    base.halfExtents = {0.25f, kBaseHalfY, 0.15f};
    base.bevel = 0.01f;
    base.bevelSteps = res.bevelSteps;
    base.maxEdge = 0.25f;
    appendMesh(mesh, makeBeveledBox(base),
               glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, kBaseHalfY - 0.005f, kPostZ)));

    // Sort triangles into white plate, red bands on the front face, stand.
    std::vector<uint32_t> groups[3];
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const uint32_t* tri = &mesh.indices[3 * t];
        int group = 2;
        if (t < plateTriangles) {
            group = 0;
            const glm::vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]],
                            c = mesh.positions[tri[2]];
            const glm::vec3 center = (a + b + c) / 3.0f;
            const bool front = glm::cross(b - a, c - a).z > 0.0f && center.z > kPlateHalfDepth - 0.005f;
            const float r = glm::length(glm::vec2(center.x, center.y - kPlateY));
            if (front && (int(r / kBand) % 2) == 0) group = 1;
        }
        groups[group].insert(groups[group].end(), tri, tri + 3);
    }
    mesh.indices.clear();
    mesh.submeshes.clear();
    const int materials[3] = {TargetWhite, TargetRed, SteelDark};
    for (int g = 0; g < 3; ++g) {
        mesh.submeshes.push_back({uint32_t(mesh.indices.size()), uint32_t(groups[g].size()), materials[g]});
        mesh.indices.insert(mesh.indices.end(), groups[g].begin(), groups[g].end());
    }
    return mesh;
}

// ---- banners -------------------------------------------------------------------------------------

// A cloth banner 1 m wide and 1.4 m long, hanging down from its origin in the x-y plane and facing
// +Z; its UVs map it once onto the unit square (no overlap), for texture-space decals.
Mesh makeBanner(const Resolution& res) {
    const float step = res.detail == 0 ? 0.1f : 0.04f;
    Mesh grid = makeGrid(makeSamples(-0.5f, 0.5f, step), makeSamples(0.0f, 1.4f, step));
    Mesh mesh;
    // Rotating +90 degrees about X takes the grid's +Y normal to +Z and its z to -y (hanging down).
    appendMesh(mesh, grid,
               glm::mat4(glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, 1, 0), glm::vec4(0, -1, 0, 0),
                         glm::vec4(0, 0, 0, 1)));
    fitUvsToUnitSquare(mesh);
    computeTangents(mesh);
    setMaterial(mesh, Cloth);
    return mesh;
}

} // namespace

Scene makeGalleryScene(const GallerySettings& settings) {
    const Resolution res = resolutionFor(std::clamp(settings.detail, 0, 3));
    const int targetCount = std::clamp(settings.targetCount, 0, kMaxTargets);
    Rng rng(settings.seed);

    Scene scene;
    scene.source = "builtin:gallery";
    scene.materials = makeMaterials();

    scene.objects.push_back(makeFloor(res, rng.next()));

    const float sideLength = kSideWallFront - kBackWallFront + 0.05f; // overlaps the back wall slightly
    const double wallY = 0.5 * double(kWallTop + kWallBottom);
    const double sideZ = double(kSideWallFront) - 0.5 * double(sideLength);
    const double sideX = double(kHalfWidth) - 0.5 * double(kWallThickness);
    const WallSpec walls[3] = {
        {"wall_back", 2.0f * kHalfWidth, translation(0.0, wallY, kFloorBack + 0.5 * kWallThickness), BrickRed,
         0.75f, 0.25f},
        {"wall_left", sideLength, placed(-sideX, wallY, sideZ, 0.5 * kPiF), BrickGrey, 0.8f, 0.4f},
        {"wall_right", sideLength, placed(sideX, wallY, sideZ, -0.5 * kPiF), BrickGrey, 0.8f, 0.4f},
    };
    for (const WallSpec& w : walls) {
        Mesh mesh = makeWall(w, res, rng.next());
        setMaterial(mesh, w.material);
        scene.objects.push_back(makeSceneObject(w.name, std::move(mesh), w.transform));
    }

    const glm::vec2 pillarSpots[4] = {{-7.5f, -2.0f}, {7.5f, -2.0f}, {-7.5f, 3.5f}, {7.5f, 3.5f}};
    for (int i = 0; i < 4; ++i) {
        const double yaw = kPiF + rng.uniform(-0.3f, 0.3f);
        Mesh mesh = makePillar(res, rng.next());
        setMaterial(mesh, Metal);
        scene.objects.push_back(makeSceneObject("pillar_" + std::to_string(i), std::move(mesh),
                                                placed(pillarSpots[i].x, 0.0, pillarSpots[i].y, yaw)));
    }

    struct CrateSpot {
        float x, z;    // position on the floor, or offset from the centre of the crate below
        float half;    // half edge length
        int stackedOn; // index of the crate below, or -1 on the floor
    };
    const CrateSpot crates[6] = {{-5.8f, 0.6f, 0.5f, -1},   {-6.9f, -0.6f, 0.45f, -1},
                                 {0.05f, -0.04f, 0.35f, 0}, {5.6f, 0.2f, 0.5f, -1},
                                 {6.6f, 1.5f, 0.4f, -1},    {-0.06f, 0.03f, 0.35f, 3}};
    glm::dvec3 crateCenter[6];
    for (int i = 0; i < 6; ++i) {
        const CrateSpot& c = crates[i];
        const double yaw = rng.uniform(-0.5f, 0.5f);
        const double jx = rng.uniform(-0.05f, 0.05f), jz = rng.uniform(-0.05f, 0.05f);
        glm::dvec3 center(c.x + jx, c.half - 0.005, c.z + jz);
        if (c.stackedOn >= 0) {
            const glm::dvec3 below = crateCenter[c.stackedOn];
            center = glm::dvec3(below.x + c.x + jx, below.y + crates[c.stackedOn].half + c.half - 0.003,
                                below.z + c.z + jz);
        }
        crateCenter[i] = center;
        Mesh mesh = makeCrate(c.half, res, rng.next());
        setMaterial(mesh, Wood);
        scene.objects.push_back(makeSceneObject("crate_" + std::to_string(i), std::move(mesh),
                                                placed(center.x, center.y, center.z, yaw)));
    }

    Mesh arch = makeArch(res, rng.next());
    setMaterial(arch, Stone);
    scene.objects.push_back(makeSceneObject("arch", std::move(arch), translation(0.0, 0.0, -1.0)));

    const std::shared_ptr<const Mesh> target = shareMesh(makeTarget(res)); // one mesh for every target
    for (int i = 0; i < targetCount; ++i) {
        const float x =
            targetCount == 1 ? 0.0f : -kTargetSpan + 2.0f * kTargetSpan * float(i) / float(targetCount - 1);
        scene.objects.push_back(
            makeSceneObject("target_" + std::to_string(i), target, translation(x, 0.0, kTargetZ), true));
    }

    const std::shared_ptr<const Mesh> banner = shareMesh(makeBanner(res));
    for (int i = 0; i < std::clamp(settings.bannerCount, 0, 2); ++i)
        scene.objects.push_back(makeSceneObject("banner_" + std::to_string(i), banner,
                                                translation(i == 0 ? -6.0 : 6.0, 3.4, -2.6), true));
    return scene;
}

} // namespace spatter
