// Picking on meshes (pickMesh): a ray through a pixel's centre picks the texcoords that pixel's
// trace output holds and the depth it wrote, on the decal wall's bricks drawn on a sphere (curved,
// with a silhouette fade), under a triplanar mapping and on two sheets of one mesh where the
// later one shows in front of the first one's deep relief; a shot at the pick lands there; on a
// plane it is pickSurface on the plane's frame; a MeshPicker picks what pickMesh picks, to the
// bit; bad input is refused by name.

#include "support/Fields.h"
#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/HeightFieldTracer.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/DecalWallEffect.h"
#include "hfx/effects/GasPlanetEffect.h"
#include "hfx/effects/Impacts.h"
#include "hfx/effects/Picking.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <utility>
#include <vector>

namespace hfx::test {
namespace {

class Picking : public DeviceTest {};

/// What a drawn frame's pixels say against pickMesh through their centres.
struct Agreement {
    size_t covered = 0;    // pixels the mesh drew
    size_t missed = 0;     // ... that the CPU's ray picked nothing on
    size_t off = 0;        // ... whose pick lies more than 0.01 texels from the trace output's hit
    size_t depthOff = 0;   // ... whose pick's window depth is more than 1e-5 from the pixel's
    double worst = 0.0;    // texels
    std::vector<int> projections = std::vector<int>(4, 0); // picks per projection (-1, 0, 1, 2)
};

/// Draws `mesh` under `model` and compares every covered pixel's trace output with `pick` of the
/// ray through its centre (`checkDepth`: and the depth it wrote with the pick's point's).
Agreement compare(const Mesh& mesh, const glm::mat4& model, const std::vector<SurfaceLayer>& layers,
                  const SurfaceMaterial& material, const Camera& camera, int W, int H, int texels, bool checkDepth,
                  const std::function<std::optional<MeshPick>(const Ray&, glm::dvec2 pixel)>& pick) {
    RenderTarget target(W, H, true);
    target.bind();
    target.clear();
    SurfaceRenderer renderer;
    renderer.draw(mesh, model, layers, material, camera, DirectionalLight{.direction = {0.4f, 0.8f, 0.45f}},
                  {.technique = Technique::Hierarchical, .traceOutput = true});
    const std::vector<glm::vec4> trace = target.readTrace();
    const std::vector<float> depth = target.readDepth();
    const glm::dmat4 viewProj(camera.viewProjection());
    Agreement a;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t i = size_t(y) * W + x;
            if (!(depth[i] < 1.0f)) continue;
            ++a.covered;
            const std::optional<MeshPick> p = pick(camera.rayThroughPixel(x + 0.5, y + 0.5, W, H), {x + 0.5, y + 0.5});
            if (!p) {
                ++a.missed;
                continue;
            }
            ++a.projections[size_t(p->projection + 1)];
            const double error = glm::length(p->uv - glm::dvec2(trace[i])) * texels;
            a.worst = std::max(a.worst, error);
            a.off += error > 0.01;
            const glm::dvec4 clip = viewProj * glm::dvec4(p->world, 1.0);
            a.depthOff += checkDepth && std::abs(0.5 * clip.z / clip.w + 0.5 - depth[i]) > 1e-5;
        }
    return a;
}

TEST(PickMesh, OnAPlaneItIsPickSurfaceOnThePlanesFrame) {
    // A subdivided plane, turned, moved and mirrored or not: every triangle has the plane's frame,
    // so the mesh's pick is the frame's, to rounding; from behind, both pick nothing.
    const PlaneConfig plane{.size = 4.0f, .texcoordScale = 2.0f, .subdivisions = 3};
    const MeshData mesh = makePlane(plane);
    const HeightFieldTracer heights(sumOfSines(64, {{0.3, 2, 1, 0.0}, {0.15, -3, 5, 1.0}}), 64, 64, EdgeMode::Wrap);
    const SurfaceMaterial material{.depthScale = 0.06f};
    const glm::mat4 turned = glm::rotate(glm::translate(glm::mat4(1.0f), {0.3f, 0.5f, -0.2f}), 1.1f, glm::vec3(1, 0.2f, 0));
    for (const glm::mat4& model : {turned, glm::scale(turned, {-1.0f, 1.0f, 1.0f})}) {
        const SurfaceFrame frame = SurfaceFrame::ofPlane(plane, model);
        const glm::dvec3 centre(model * glm::vec4(0, 0, 0, 1));
        size_t picked = 0;
        for (int j = -6; j <= 6; ++j)
            for (int i = -6; i <= 6; ++i) {
                // Rays from in front of the plane and from behind it, at up to 70 degrees.
                for (const double side : {1.0, -1.0}) {
                    const glm::dvec3 aim = centre + 0.28 * i * frame.tangent / glm::length(frame.tangent) +
                                           0.28 * j * frame.bitangent / glm::length(frame.bitangent);
                    const glm::dvec3 eye = aim + side * 1.5 * frame.normal + 0.3 * (i + j) * frame.tangent;
                    const Ray ray{eye, glm::normalize(aim - eye)};
                    const auto a = pickMesh(ray, mesh, model, heights, material);
                    const auto b = pickSurface(ray, frame, heights, material.depthScale, {0.0, 0.0, 2.0, 2.0});
                    ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << i << "," << j << " from side " << side;
                    if (!a) continue;
                    ++picked;
                    EXPECT_LT(glm::length(a->uv - b->uv), 1e-9);
                    EXPECT_LT(glm::length(a->world - b->world), 1e-9);
                    EXPECT_EQ(a->projection, -1);
                }
            }
        EXPECT_GT(picked, 100u);
    }
}

TEST(PickMesh, BadInputIsRefusedByName) {
    const MeshData sphere = makeSphere({});
    const HeightFieldTracer heights(std::vector<float>(64, 0.5f), 8, 8, EdgeMode::Wrap);
    const Ray ray{{0, 0, 3}, {0, 0, -1}};
    const SurfaceMaterial material;
    EXPECT_TRUE(pickMesh(ray, sphere, glm::mat4(1.0f), heights, material));
    EXPECT_EQ(messageOf([&] { pickMesh({{0, 0, 3}, {0, 0, 0}}, sphere, glm::mat4(1.0f), heights, material); }),
              "pickMesh: the ray must be finite and have a direction, got origin (0, 0, 3) and direction (0, 0, 0)");
    glm::mat4 flat(1.0f);
    flat[1][1] = 0.0f;
    EXPECT_NE(messageOf([&] { pickMesh(ray, sphere, flat, heights, material); })
                  .find("pickMesh: the model matrix scales some axis to 0"),
              std::string::npos);
    glm::mat4 broken(1.0f);
    broken[3][0] = std::nanf("");
    EXPECT_NE(messageOf([&] { pickMesh(ray, sphere, broken, heights, material); }).find("pickMesh: the model matrix must be finite, got the columns (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (nan, 0, 0, 1)"), std::string::npos);
    MeshData torn = sphere;
    torn.indices[5] = uint32_t(torn.vertices.size());
    EXPECT_NE(messageOf([&] { pickMesh(ray, torn, glm::mat4(1.0f), heights, material); }).find("index"), std::string::npos);
    EXPECT_EQ(messageOf([&] { pickMesh(ray, sphere, glm::mat4(1.0f), heights, SurfaceMaterial{.depthScale = -1.0f}); }),
              "SurfaceMaterial.depthScale must be in [0, 1], got -1");
    // A shading model's look is not the pick's: a water look's environment image, which only
    // GL could check, is not asked about (the pick runs on any thread, with no GL context).
    SurfaceMaterial water{.shading = Shading::Water};
    water.water.environment = 12345;
    EXPECT_TRUE(pickMesh(ray, sphere, glm::mat4(1.0f), heights, water));
    // From inside the closed sphere every face the ray meets first is a back face: nothing.
    EXPECT_FALSE(pickMesh({{0, 0, 0}, {0.3, 0.2, -1}}, sphere, glm::mat4(1.0f), heights, material));
}

TEST(MeshPicker, PicksWhatPickMeshPicksToTheBit) {
    // Its hierarchy passes over triangles and crosses the rest as pickMesh does: on a sphere, a
    // cylinder and a clipped plane, under a turned, scaled and moved model and its mirror, 1,500
    // rays each from around the mesh (some past it, some from inside; half of them with a
    // pixel's neighbours) pick the same triangle and the same texcoords and point to the bit, or
    // nothing both.
    const HeightFieldTracer heights(sumOfSines(64, {{0.3, 2, 1, 0.0}, {0.15, -3, 5, 1.0}}), 64, 64, EdgeMode::Wrap);
    SurfaceMaterial clipped{.depthScale = 0.06f, .silhouetteFade = 0.2f};
    clipped.clipToPatch = true;
    clipped.patchBounds = {0.1f, 0.0f, 0.9f, 0.8f};
    const std::vector<std::pair<MeshData, SurfaceMaterial>> meshes{
        {makeSphere({}), {.depthScale = 0.04f, .silhouetteFade = 0.25f}},
        {makeCylinder({.radius = 0.6f, .height = 2.0f, .segments = 48}), {.depthScale = 0.05f}},
        {makePlane({.size = 2.0f, .subdivisions = 4}), clipped}};
    const glm::mat4 turned =
        glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), {0.4f, -0.3f, 0.2f}), 0.7f, glm::vec3(0.3f, 1, 0.1f)),
                   glm::vec3(1.3f, 0.8f, 1.1f));
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (const auto& [mesh, material] : meshes) {
        const MeshPicker picker(mesh);
        EXPECT_GT(picker.nodeCount(), mesh.indices.size() / 3 / 4) << "no hierarchy";
        for (const glm::mat4& model : {glm::mat4(1.0f), turned, glm::scale(turned, {-1.0f, 1.0f, 1.0f})}) {
            const glm::dvec3 centre(model * glm::vec4(0, 0, 0, 1));
            size_t picked = 0;
            for (int k = 0; k < 1500; ++k) {
                const glm::dvec3 from = centre + (k % 10 == 0 ? 0.2 : 3.0) * glm::dvec3(unit(random), unit(random), unit(random));
                const glm::dvec3 to = centre + 1.2 * glm::dvec3(unit(random), unit(random), unit(random));
                const Ray ray{from, glm::normalize(to - from)};
                // Every other ray with neighbours spread from 0 to 19 texels: its relief faded
                // or flat past the level of detail.
                std::optional<PixelNeighbours> neighbours;
                if (k % 2 == 1) {
                    const double apart = 0.03 * (k % 20);
                    neighbours = PixelNeighbours{{from, glm::normalize(to + glm::dvec3(apart, 0.0, 0.0) - from)},
                                                 {from, glm::normalize(to + glm::dvec3(0.0, apart, 0.0) - from)}};
                }
                const auto a = pickMesh(ray, mesh, model, heights, material, neighbours);
                const auto b = picker.pick(ray, model, heights, material, neighbours);
                ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << k;
                if (!a) continue;
                ++picked;
                ASSERT_EQ(a->triangle, b->triangle) << "ray " << k;
                ASSERT_EQ(a->uv, b->uv) << "ray " << k;
                ASSERT_EQ(a->world, b->world) << "ray " << k;
            }
            std::printf("[mesh picker] %zu triangles, %zu nodes: %zu of 1500 rays picked\n", mesh.indices.size() / 3,
                        picker.nodeCount(), picked);
            EXPECT_GT(picked, 150u);
        }
    }
    MeshData broken = makeSphere({});
    broken.indices[5] = 1u << 30;
    EXPECT_NE(messageOf([&] { MeshPicker{broken}; }).find("index"), std::string::npos);
    const MeshPicker picker(makeSphere({}));
    EXPECT_NE(messageOf([&] { picker.pick({{0, 0, 3}, {0, 0, 0}}, glm::mat4(1.0f), heights, {}); })
                  .find("MeshPicker::pick: the ray must be finite"),
              std::string::npos);
    EXPECT_NE(messageOf([&] { picker.pick({{0, 0, 3}, {0, 0, -1}}, glm::mat4(0.0f), heights, {}); })
                  .find("MeshPicker::pick: the model matrix"),
              std::string::npos);
}

TEST_F(Picking, ABrickWallOnASpherePicksWhatItsPixelsTraceAndAShotLandsThere) {
    // The decal wall's bricks on a turned, stretched sphere, its relief fading at the silhouette,
    // and the same mirrored (its winding turned): each pixel's trace output (hier, exact) is the
    // pick through its centre, and so is its depth. (2 pixels are off by up to 1.3 texels in u,
    // beside the north pole: in its last ring of triangles dP/du is nearly 0, and the GPU's
    // float rounding of the inverse frame moves u by up to 0.01 there, a sliver of the surface.)
    constexpr int W = 256, H = 192;
    DecalWallEffect wall(cl(), {.bricks = {.size = 128}});
    const MeshData data = makeSphere({});
    const Mesh sphere(data);
    const glm::mat4 model = glm::scale(glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1, 2, 0.5f))),
                                       glm::vec3(1.2f, 1.0f, 1.1f));
    SurfaceMaterial material = wall.material();
    material.depthScale = 0.02f;
    material.lodThreshold = 100.0f;
    material.silhouetteFade = 0.25f;
    wall.setMaterial(material);
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 3.2f, 0.5f, 0.35f);
    camera.aspect = float(W) / float(H);
    const HeightFieldTracer heights = wall.heightTracer();
    for (const glm::mat4& m : {model, glm::scale(model, {-1.0f, 1.0f, 1.0f})}) {
        const bool mirrored = glm::determinant(glm::mat3(m)) < 0.0f;
        const Agreement a = compare(sphere, m, wall.layers(), material, camera, W, H, 128, true,
                                    [&](const Ray& ray, glm::dvec2) { return pickMesh(ray, data, m, heights, material); });
        std::printf("[bricks on a sphere%s] %zu pixels, %zu picked nothing, %zu off the trace by more than 0.01 "
                    "texels (%.2g at most), %zu depths off by more than 1e-5\n",
                    mirrored ? ", mirrored" : "", a.covered, a.missed, a.off, a.worst, a.depthOff);
        ASSERT_GT(a.covered, size_t(W * H / 5));
        EXPECT_LE(a.missed, a.covered / 1000);
        EXPECT_LE(a.off, a.covered / 200);
        EXPECT_LE(a.depthOff, a.covered / 200);
    }

    // A bullet along the middle pixel's ray, routed to the wall on the sphere (WallImpacts on the
    // mesh): it takes the wall's pick there, and the crater's deepest texel is there, within a
    // texel.
    const Ray middle = camera.rayThroughPixel(W / 2 + 0.5, H / 2 + 0.5, W, H);
    const auto picked = wall.pick(middle, data, model, wall.material());
    ASSERT_TRUE(picked);
    WallImpacts onSphere(wall, data, model);
    ImpactReceiver* receivers[] = {&onSphere};
    const auto routed = routeImpact({.origin = middle.origin, .direction = middle.direction}, receivers);
    ASSERT_TRUE(routed);
    EXPECT_LT(glm::length(routed->hit.uv - picked->uv), 1e-12);
    EXPECT_LT(glm::length(routed->hit.normal - picked->normal), 1e-12);
    EXPECT_NEAR(glm::dot(picked->normal, -middle.direction), 1.0, 0.3) << "the sphere's normal faces the eye";
    wall.update(1.0 / 30.0);
    const std::vector<float> after = wall.readHeights();
    const int deepest = int(std::min_element(after.begin(), after.end()) - after.begin());
    const glm::dvec2 landed((deepest % 128 + 0.5) / 128, (deepest / 128 + 0.5) / 128);
    const glm::dvec2 aimed = picked->uv - glm::floor(picked->uv);
    EXPECT_LT(glm::length(landed - aimed) * 128, 1.0) << "stamp landed at " << landed.x << "," << landed.y
                                                      << ", aimed at " << aimed.x << "," << aimed.y;
    // A receiver on a bad mesh or model is refused when made, by name.
    MeshData torn = data;
    torn.indices[2] = uint32_t(torn.vertices.size());
    EXPECT_NE(messageOf([&] { WallImpacts(wall, torn, model); }).find("index"), std::string::npos);
    EXPECT_NE(messageOf([&] { WallImpacts(wall, data, glm::mat4(0.0f)); }).find("WallImpacts: the model matrix scales"),
              std::string::npos);
}

TEST_F(Picking, ATriplanarSpherePicksItsHeaviestProjection) {
    // The same under a triplanar mapping: a pixel's trace output is its heaviest projection's
    // trace (the depth it writes is the projections' blend, not checked here), and so is the pick.
    constexpr int W = 256, H = 192, kField = 64;
    const SineRelief relief(kField, 0.04f);
    const MeshData data = makeSphere({});
    const Mesh sphere(data);
    const glm::mat4 model = glm::rotate(glm::mat4(1.0f), 0.4f, glm::normalize(glm::vec3(0.3f, 1, 0.2f)));
    const SurfaceMaterial material{.depthScale = 0.04f, .lodThreshold = 100.0f, .silhouetteFade = 0.25f,
                                   .triplanar = {.scale = 1.5f, .sharpness = 2.0f}};
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 3.0f, 0.8f, 0.5f);
    camera.aspect = float(W) / float(H);
    const HeightFieldTracer heights(relief.heights, kField, kField, EdgeMode::Wrap);
    const Agreement a = compare(sphere, model, {{&relief.textures}}, material, camera, W, H, kField, false,
                                [&](const Ray& ray, glm::dvec2) { return pickMesh(ray, data, model, heights, material); });
    std::printf("[triplanar sphere] %zu pixels, %zu picked nothing, %zu off the trace by more than 0.01 texels "
                "(%.2g at most); picks along x, y, z: %d, %d, %d\n",
                a.covered, a.missed, a.off, a.worst, a.projections[1], a.projections[2], a.projections[3]);
    ASSERT_GT(a.covered, size_t(W * H / 5));
    EXPECT_LE(a.missed, a.covered / 1000);
    EXPECT_LE(a.off, a.covered / 200);
    EXPECT_EQ(a.projections[0], 0) << "a triplanar pick reported the mesh's texcoords";
    for (int axis = 1; axis <= 3; ++axis) EXPECT_GT(a.projections[size_t(axis)], int(a.covered / 20)) << "xyz"[axis - 1];
}

TEST_F(Picking, ANearerPartOfTheMeshInFrontOfADeepHitIsWhatIsPicked) {
    // Two overlapping sheets of one mesh, the lower 0.03 below the upper (a fifth of the relief's
    // depth) and shifted along it: where the upper sheet's relief runs deeper than the lower's
    // surface, the lower sheet's relief shows in front of it though the ray entered it later.
    // The draw's depth test keeps it, and the pick must too (it picked the sheet entered first).
    constexpr int W = 256, H = 192, kField = 64;
    const SineRelief relief(kField, 0.08f);
    MeshData data = makePlane({.size = 2.0f, .subdivisions = 2});
    const MeshData lower = makePlane({.size = 2.0f, .subdivisions = 2});
    const uint32_t upperVertices = uint32_t(data.vertices.size()), upperTriangles = uint32_t(data.indices.size() / 3);
    for (Vertex v : lower.vertices) {
        v.position += glm::vec3(0.37f, -0.03f, 0.21f);
        data.vertices.push_back(v);
    }
    for (const uint32_t i : lower.indices) data.indices.push_back(i + upperVertices);
    data.convex = false; // (makePlane's claim, which two overlapping sheets break)
    const Mesh sheets(data);
    const SurfaceMaterial material{.depthScale = 0.08f, .lodThreshold = 100.0f};
    Camera camera = Camera::orbit({0.2f, 0.0f, 0.1f}, 2.6f, 0.4f, 0.75f);
    camera.aspect = float(W) / float(H);
    const HeightFieldTracer heights(relief.heights, kField, kField, EdgeMode::Wrap);
    size_t inFront = 0; // picks on the lower sheet where the ray crossed the upper one first
    const Agreement a = compare(sheets, glm::mat4(1.0f), {{&relief.textures}}, material, camera, W, H, kField, true,
                                [&](const Ray& ray, glm::dvec2) {
                                    const auto p = pickMesh(ray, data, glm::mat4(1.0f), heights, material);
                                    const glm::dvec3 upper = ray.origin - ray.direction * (ray.origin.y / ray.direction.y);
                                    inFront += p && p->triangle >= upperTriangles && std::abs(upper.x) < 1.0 &&
                                               std::abs(upper.z) < 1.0;
                                    return p;
                                });
    std::printf("[two sheets] %zu pixels, %zu picked nothing, %zu off the trace by more than 0.01 texels (%.2g at "
                "most), %zu depths off by more than 1e-5; %zu picks on the lower sheet where the ray entered the "
                "upper\n",
                a.covered, a.missed, a.off, a.worst, a.depthOff, inFront);
    ASSERT_GT(a.covered, size_t(W * H / 4));
    EXPECT_GT(inFront, a.covered / 50) << "the lower sheet never showed through the upper's relief";
    EXPECT_LE(a.missed, a.covered / 1000);
    EXPECT_LE(a.off, a.covered / 200);
    EXPECT_LE(a.depthOff, a.covered / 200);
}

TEST_F(Picking, GivenThePixelsNeighboursAPickFadesTheReliefWithTheLevelOfDetail) {
    // A plane whose far half lies past the level of detail: its relief fades to normal mapping
    // over the level below lodThreshold, flat past it. A pick given its pixel's neighbours in its
    // 2x2 quad (those the draw's derivatives difference) has the draw's mip level and picks what
    // the pixel shows there too. Without them it picks the relief's hit, far from what many of
    // those pixels show.
    constexpr int W = 256, H = 192, kField = 128;
    const SineRelief relief(kField, 0.05f);
    const MeshData data = makePlane({.size = 2.0f, .texcoordScale = 4.0f, .subdivisions = 2});
    const Mesh plane(data);
    const glm::mat4 model = glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 1, 0));
    const SurfaceMaterial material{.depthScale = 0.05f, .lodThreshold = 3.0f};
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.2f, 0.2f, 0.45f);
    camera.aspect = float(W) / float(H);
    const HeightFieldTracer heights(relief.heights, kField, kField, EdgeMode::Wrap);
    size_t faded = 0, flat = 0; // pixels whose pick moved off the hit, and those at the polygon
    const Agreement given = compare(plane, model, {{&relief.textures}}, material, camera, W, H, kField, true,
                                    [&](const Ray& ray, glm::dvec2 pixel) {
                                        const auto p = pickMesh(ray, data, model, heights, material,
                                                                PixelNeighbours::of(camera, pixel.x, pixel.y, W, H));
                                        const auto hit = pickMesh(ray, data, model, heights, material);
                                        if (p && hit && glm::length(p->uv - hit->uv) * kField > 0.01) {
                                            ++faded;
                                            flat += glm::length(p->world - p->entry) < 1e-9;
                                        }
                                        return p;
                                    });
    const Agreement without =
        compare(plane, model, {{&relief.textures}}, material, camera, W, H, kField, true,
                [&](const Ray& ray, glm::dvec2) { return pickMesh(ray, data, model, heights, material); });
    std::printf("[level of detail] %zu pixels, %zu faded (%zu of them flat); given the neighbours %zu picked "
                "nothing, %zu off the trace by more than 0.01 texels (%.2g at most), %zu depths off by more "
                "than 1e-5; without them %zu off (%.2g texels at most), %zu depths off\n",
                given.covered, faded, flat, given.missed, given.off, given.worst, given.depthOff, without.off,
                without.worst, without.depthOff);
    ASSERT_GT(given.covered, size_t(W * H / 5));
    EXPECT_GT(faded - flat, given.covered / 20) << "too few pixels in the fade";
    EXPECT_GT(flat, given.covered / 20) << "too few pixels past the level of detail";
    EXPECT_LE(given.missed, given.covered / 1000);
    EXPECT_LE(given.off, given.covered / 200);
    EXPECT_LE(given.depthOff, given.covered / 200);
    EXPECT_GT(without.off, given.covered / 10);
    EXPECT_GT(without.depthOff, given.covered / 10);
    // Neighbours whose rays are not rays are refused by name.
    const Ray middle = camera.rayThroughPixel(W / 2, H / 2, W, H);
    EXPECT_NE(messageOf([&] {
                  pickMesh(middle, data, model, heights, material, PixelNeighbours{middle, {{0, 0, 0}, {0, 0, 0}}});
              }).find("pickMesh: the neighbours' ray up must be finite and have a direction"),
              std::string::npos);
}

TEST_F(Picking, AnImpactOnThePlanetLandsOnTheTexelItsPixelShows) {
    // PlanetImpacts picks the gas giant as drawn: fired along a pixel's ray, an impact's hit is
    // that pixel's trace output (its surface is the gas's detail, 4 texels a cell here, faded at
    // the silhouette), wherever the planet stands and however far it has turned.
    constexpr int W = 192, H = 128;
    GasPlanetEffect planet(cl(), {.gas = {.width = 64, .height = 32, .initialBands = 4.0f}, .stormsPerSecond = 0.0f});
    planet.update(3.0);
    const MeshData data = makeSphere({});
    const Mesh sphere(data);
    const glm::mat4 placement = glm::scale(glm::translate(glm::mat4(1.0f), {2.0f, 0.5f, -1.0f}), glm::vec3(1.5f));
    PlanetImpacts target(planet, data, placement);
    SurfaceMaterial material = planet.material();
    material.lodThreshold = 100.0f;
    planet.setMaterial(material);
    Camera camera = Camera::orbit({2.0f, 0.5f, -1.0f}, 4.5f, 0.7f, 0.3f);
    camera.aspect = float(W) / float(H);
    RenderTarget frame(W, H, true);
    frame.bind();
    frame.clear();
    SurfaceRenderer renderer;
    renderer.draw(sphere, placement * planet.modelMatrix(), planet.layers(), material, camera,
                  DirectionalLight{.direction = {0.9f, 0.2f, 0.3f}}, {.technique = Technique::Hierarchical, .traceOutput = true});
    const std::vector<glm::vec4> trace = frame.readTrace();
    const std::vector<float> depth = frame.readDepth();
    const int texels = planet.surfaceWidth();
    ASSERT_GT(texels, 64) << "no detail: the test wants a surface finer than the gas";
    size_t covered = 0, missed = 0, off = 0;
    double worst = 0.0;
    for (int y = 2; y < H; y += 5)
        for (int x = 2; x < W; x += 5) {
            const size_t i = size_t(y) * W + x;
            if (!(depth[i] < 1.0f)) continue;
            ++covered;
            const auto hit = target.hit(camera.rayThroughPixel(x + 0.5, y + 0.5, W, H));
            if (!hit) {
                ++missed;
                continue;
            }
            glm::dvec2 d = hit->uv - glm::dvec2(trace[i]);
            d.x -= std::round(d.x); // the hit's longitude is wrapped into [0, 1)
            const double error = glm::length(d * glm::dvec2(texels, planet.surfaceHeight()));
            worst = std::max(worst, error);
            off += error > 0.01;
        }
    std::printf("[planet impacts] %zu pixels, %zu missed, %zu off the trace by more than 0.01 texels (%.2g at most)\n",
                covered, missed, off, worst);
    ASSERT_GT(covered, 150u);
    EXPECT_EQ(missed, 0u);
    EXPECT_LE(off, covered / 100);
    EXPECT_NE(messageOf([&] { PlanetImpacts(planet, data, glm::mat4(0.0f)); }).find("PlanetImpacts: the model matrix"),
              std::string::npos);
}

} // namespace
} // namespace hfx::test
