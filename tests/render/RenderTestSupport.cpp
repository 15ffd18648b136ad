#include "RenderTestSupport.hpp"

#include "TestData.hpp"

#include "spatter/placement/CollisionWorld.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace spatter::test {

Camera lookAt(const glm::dvec3& eye, const glm::dvec3& target) {
    Camera c;
    c.eye = eye;
    c.target = target;
    c.nearPlane = 0.05;
    return c;
}

Result<Renderer> makeRenderer(int width, int height, RendererSettings settings) {
    std::string why;
    GlContext* gl = headlessContext(why);
    if (!gl) return fail(why);
    settings.width = width;
    settings.height = height;
    return Renderer::create(*gl, settings);
}

Image renderView(Renderer& r, const Camera& camera, const RenderOptions& options, FrameStats* stats) {
    Result<FrameStats> st = r.render(camera, options);
    EXPECT_TRUE(st.ok()) << st.error();
    if (stats && st) *stats = st.value();
    Result<Image> im = r.readback();
    EXPECT_TRUE(im.ok()) << im.error();
    return im ? im.value() : Image{};
}

Image renderView(Renderer& r, const Camera& camera, View view, FrameStats* stats) {
    RenderOptions options;
    options.view = view;
    return renderView(r, camera, options, stats);
}

std::vector<uint8_t> whiteMask(const Image& image) {
    std::vector<uint8_t> mask(size_t(image.width) * size_t(image.height));
    for (size_t i = 0; i < mask.size(); ++i)
        mask[i] = image.rgba[i * 4] > 127 ? 1 : 0;
    return mask;
}

double iou(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t inter = 0, uni = 0;
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        inter += (a[i] && b[i]) ? 1 : 0;
        uni += (a[i] || b[i]) ? 1 : 0;
    }
    return uni == 0 ? std::numeric_limits<double>::quiet_NaN()
                    : double(inter) / double(uni); // fails any bound
}

size_t countSet(const std::vector<uint8_t>& mask) {
    return size_t(std::count_if(mask.begin(), mask.end(), [](uint8_t v) { return v != 0; }));
}

std::vector<uint8_t> referenceCoverage(const Scene& scene, const CoverageInputs& in, const Camera& camera,
                                       int width, int height) {
    std::vector<uint8_t> mask(size_t(width) * size_t(height), 0);
    // Every object in the world, so that rays stop at objects that take no decals too.
    Scene all = scene;
    for (SceneObject& o : all.objects)
        o.receivesDecals = true;
    WorldSettings ws;
    ws.useColliders = false;
    Result<CollisionWorld> world = CollisionWorld::build(all, {}, ws);
    EXPECT_TRUE(world.ok()) << world.error();
    if (!world) return mask;

    const bool useIds = scene.dynamicObjectCount() > 0;
    const CameraBasis basis = cameraBasis(camera);

    struct DecalRef {
        glm::dmat4 worldToBox;
        glm::dvec3 tangent, bitangent, normal, axis, halfSize;
        double cosMax;
        bool wrap;
        uint8_t id;
    };
    std::vector<DecalRef> refs;
    for (const Decal& d : in.decals) {
        if (d.object >= scene.objects.size() || d.type >= in.types.size()) continue;
        const glm::dmat4& xf = scene.objects[d.object].transform;
        const glm::dmat3 lin(xf);
        const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(lin));
        const glm::dmat4 boxToWorld = xf * glm::dmat4(d.boxToObject());
        const DecalType& type = in.types[d.type];
        DecalRef r;
        r.worldToBox = glm::inverse(boxToWorld);
        const glm::dvec3 t = lin * glm::dvec3(d.frame().tangent), b = lin * glm::dvec3(d.frame().bitangent);
        r.tangent = glm::normalize(t);
        r.bitangent = glm::normalize(b);
        r.normal = glm::normalize(normalMatrix * glm::dvec3(d.frame().normal));
        r.axis = glm::normalize(lin * glm::dvec3(d.projectionAxis())); // the box's depth lines
        r.halfSize = glm::dvec3(glm::length(t) * 0.5 * d.size.x, glm::length(b) * 0.5 * d.size.y,
                                glm::length(lin * glm::dvec3(d.frame().normal)) * d.halfDepth);
        double angle = type.maxAngleDeg;
        if (type.wrapAround) angle = std::max(angle, double(in.wrapMaxAngleDeg));
        r.cosMax = std::cos(angle * kPi / 180.0);
        r.wrap = type.wrapAround;
        r.id = d.objectId;
        refs.push_back(r);
    }

    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) {
            const glm::dvec3 dir = pixelDirection(camera, width, height, i, j);
            Ray ray;
            ray.origin = camera.eye;
            ray.direction = dir;
            ray.tnear = camera.nearPlane / glm::dot(dir, -basis.back); // the near plane clips like the GPU's
            const std::optional<Hit> hit = world->intersect(ray);
            if (!hit) continue;
            const SceneObject& obj = scene.objects[hit->object];
            if (!obj.receivesDecals) continue;
            const Mesh& mesh = *obj.mesh;
            const uint32_t* tri = &mesh.indices[size_t(hit->primitive) * 3];
            const glm::dvec3 a(mesh.positions[tri[0]]), b(mesh.positions[tri[1]]), c(mesh.positions[tri[2]]);
            // Barycentric coordinates of the object-space hit.
            const glm::dvec3 e1 = b - a, e2 = c - a, p = hit->localPosition - a;
            const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
            const double dp1 = glm::dot(p, e1), dp2 = glm::dot(p, e2);
            const double den = d11 * d22 - d12 * d12;
            double v = 0.0, w = 0.0;
            if (std::fabs(den) > 0.0) {
                v = (d22 * dp1 - d12 * dp2) / den;
                w = (d11 * dp2 - d12 * dp1) / den;
            }
            const double u = 1.0 - v - w;
            const glm::dvec3 nObj = u * glm::dvec3(mesh.normals[tri[0]]) +
                                    v * glm::dvec3(mesh.normals[tri[1]]) +
                                    w * glm::dvec3(mesh.normals[tri[2]]);
            const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(obj.transform)));
            glm::dvec3 n = glm::normalize(normalMatrix * nObj);
            // Two-sided like the geometry pass: a back face shows the reversed normal.
            const glm::dvec3 winding = normalMatrix * glm::cross(e1, e2);
            if (glm::dot(winding, -dir) < 0.0) n = -n;
            const uint8_t pixelId =
                useIds && hit->object < in.objectIds.size() ? in.objectIds[hit->object] : 0;

            bool covered = false;
            for (const DecalRef& r : refs) {
                if (useIds && r.id != pixelId) continue;
                const glm::dvec3 box = glm::dvec3(r.worldToBox * glm::dvec4(hit->position, 1.0));
                if (std::fabs(box.x) > 1.0 || std::fabs(box.y) > 1.0 || std::fabs(box.z) > 1.0) continue;
                if (std::min(glm::dot(n, r.normal), glm::dot(n, r.axis)) < r.cosMax) continue;
                if (r.wrap) {
                    const glm::dvec3 q = box * r.halfSize;
                    const double sx = glm::dot(n, r.tangent), sy = glm::dot(n, r.bitangent);
                    const double uvx = (q.x - q.z * sx) / r.halfSize.x, uvy = (q.y - q.z * sy) / r.halfSize.y;
                    if (std::fabs(uvx) > 1.0 || std::fabs(uvy) > 1.0) continue;
                }
                covered = true;
                break;
            }
            mask[size_t(j) * size_t(width) + size_t(i)] = covered ? 1 : 0;
        }
    return mask;
}

size_t coveredWhere(const Scene& scene, const std::vector<uint8_t>& coverage, const Camera& cam,
                    const std::function<bool(const std::optional<Hit>&)>& counts) {
    Result<CollisionWorld> world = CollisionWorld::build(scene);
    EXPECT_TRUE(world.ok()) << world.error();
    if (!world) return 0;
    size_t n = 0;
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) {
            if (!coverage[size_t(j) * kW + size_t(i)]) continue;
            Ray ray;
            ray.origin = cam.eye;
            ray.direction = pixelDirection(cam, kW, kH, i, j);
            if (counts(world->intersect(ray))) ++n;
        }
    return n;
}

void dumpImage(const std::string& name, const Image& image) {
    if (!std::getenv("SPATTER_TEST_IMAGES")) return;
    static const std::string dir = scratchDir("render-images");
    const std::string path = dir + "/" + name + ".png";
    if (writePng(path, image)) std::fprintf(stderr, "wrote %s\n", path.c_str());
}

void dumpMask(const std::string& name, const std::vector<uint8_t>& mask, int width, int height) {
    if (!std::getenv("SPATTER_TEST_IMAGES")) return;
    Image im;
    im.width = width;
    im.height = height;
    im.rgba.resize(mask.size() * 4);
    for (size_t i = 0; i < mask.size(); ++i) {
        const uint8_t v = mask[i] ? 255 : 0;
        im.rgba[i * 4] = im.rgba[i * 4 + 1] = im.rgba[i * 4 + 2] = v;
        im.rgba[i * 4 + 3] = 255;
    }
    dumpImage(name, im);
}

} // namespace spatter::test
