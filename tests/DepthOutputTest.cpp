// A flat quad crossing the relief must be clipped where the displaced surface is, not where the
// polygon is: POM writes gl_FragDepth of the displaced point.

#include "support/Fields.h"
#include "support/References.h"
#include "support/Fixtures.h"

#include "hfx/core/Gl.h"
#include "hfx/core/HeightFieldTracer.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/PlanetRings.h"
#include "hfx/effects/ShadowMap.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/tools/AccuracyProbe.h"

#include <glm/gtc/matrix_transform.hpp>

#include <array>
#include <cmath>
#include <cstdio>

namespace hfx::test {
namespace {

class DepthOutput : public GlTest {};

/// The draws the engine-convention tests compare: POM, and hier walking in the draw and in a
/// compute pass.
const std::pair<const char*, DrawOptions> kPomAndHier[] = {
    {"pom", {.technique = Technique::ParallaxOcclusion}},
    {"hier in the draw", {.technique = Technique::Hierarchical, .tracePass = TracePass::InDraw}},
    {"hier in a compute pass", {.technique = Technique::Hierarchical, .tracePass = TracePass::Compute}}};

TEST_F(DepthOutput, QuadIsClippedAtTheDisplacedSurface) {
    constexpr int field = 64, image = 160;
    constexpr float depthScale = 0.15f, planeSize = 2.0f;
    const SineRelief relief(field, depthScale);
    const std::vector<float>& heights = relief.heights;
    const SurfaceTextures& textures = relief.textures;
    const Mesh plane(makePlane({.size = planeSize}));
    PlaneView view{.planeSize = planeSize, .camera = cameraAtAngle(40, 8.0f, 1.0f)};

    // The red quad sits at h = 0.5: depthScale texture units = depthScale * planeSize world units
    // is the full depth, so half of it below the polygon.
    constexpr float quadHeight = 0.5f;
    const glm::mat4 quadModel = glm::translate(
        glm::mat4(1.0f), glm::vec3(0.0f, -(1.0f - quadHeight) * depthScale * planeSize, 0.0f));

    RenderTarget target(image, image);
    target.bind();
    target.clear();
    SurfaceRenderer renderer;
    renderer.draw(plane, glm::mat4(1.0f), textures,
                  {.depthScale = depthScale, .lodThreshold = 100.0f, .shadows = false},
                  view.camera, {});
    renderer.drawFlat(plane, quadModel, view.camera, {1.0f, 0.0f, 0.0f, 1.0f});
    const Image color = target.readColor();

    const HeightFieldTracer exact(heights, field, field, EdgeMode::Wrap);
    size_t agree = 0, judged = 0, expectRed = 0, expectSurface = 0;
    for (int y = 0; y < image; ++y)
        for (int x = 0; x < image; ++x) {
            glm::dvec2 uv0;
            glm::dvec3 toEye;
            if (!view.pixelRay(x, y, image, image, uv0, toEye)) continue;
            const auto hit = exact.traceView(uv0, toEye, depthScale);
            ASSERT_TRUE(hit.has_value());
            // Near the crossing line the linear search's small error decides; judge elsewhere.
            if (std::abs(hit->height - quadHeight) < 0.04) continue;
            // The quad ends where the plane does: a ray that reaches its level outside the
            // patch sees past it.
            const glm::dvec2 atQuad =
                uv0 - glm::dvec2(toEye) / toEye.z * double(depthScale) * double(1.0f - quadHeight);
            if (atQuad.x < 0.01 || atQuad.x > 0.99 || atQuad.y < 0.01 || atQuad.y > 0.99) continue;
            const bool surfaceInFront = hit->height > quadHeight;
            const int row = image - 1 - y; // readColor is top row first
            const bool red = color.at(x, row, 0) > 0.9f && color.at(x, row, 1) < 0.1f;
            ++judged;
            (surfaceInFront ? expectSurface : expectRed)++;
            if (red != surfaceInFront) ++agree;
        }
    // Both outcomes must be common, or the test could pass with depth output broken.
    ASSERT_GT(expectRed, judged / 5);
    ASSERT_GT(expectSurface, judged / 5);
    const double agreement = double(agree) / double(judged);
    if (agreement < 0.98) writeImage(outputPath("depth_output.png"), color);
    // 2% covers pixels whose POM hit lands on the other side of h = 0.5 than the exact one,
    // steep slopes seen along the search direction.
    EXPECT_GT(agreement, 0.98) << judged << " pixels judged";
}

// The surface program declares its depth output conservative (layout(depth_greater)), so that a
// GPU keeps its early depth test against what is already drawn: the depth it writes must then
// never lie in front of the polygon's own. Every technique that writes depth, on a plane and on
// a sphere seen by a wide lens (towards its rim a surface's inward normal points back against the
// camera's axis, where parallax mapping's offset-limited point comes nearer), and the exact
// tracer's walks in the draw and in a compute pass.
TEST_F(DepthOutput, NoTechniqueWritesADepthInFrontOfThePolygon) {
    constexpr int field = 64, W = 240, H = 180;
    constexpr float depthScale = 0.12f;
    const SineRelief relief(field, depthScale);
    const SurfaceTextures& textures = relief.textures;
    const Mesh plane(makePlane({.size = 2.0f}));
    const Mesh sphere(makeSphere({}));
    Camera wide = Camera::orbit({0.0f, 0.0f, 0.0f}, 1.7f, 0.5f, 0.3f);
    wide.fovY = 1.6f;
    wide.aspect = float(W) / float(H);
    wide.nearPlane = 0.05f;
    Camera grazing = cameraAtAngle(75, 3.0f, float(W) / float(H));
    struct Scene {
        const char* name;
        const Mesh* mesh;
        Camera camera;
        float depthScale;
    };
    // The sphere's relief in its own texcoords: a unit of u is its circumference.
    const Scene scenes[] = {{"plane at 75 degrees", &plane, grazing, depthScale},
                            {"sphere, wide lens", &sphere, wide, 0.02f}};
    struct Drawn {
        const char* name;
        DrawOptions options;
    };
    const Drawn drawn[] = {{"parallax", {.technique = Technique::ParallaxOffset}},
                           {"steep", {.technique = Technique::SteepParallax}},
                           {"relief", {.technique = Technique::Relief}},
                           {"pom", {.technique = Technique::ParallaxOcclusion}},
                           {"hier in the draw", {.technique = Technique::Hierarchical, .tracePass = TracePass::InDraw}},
                           {"hier in a compute pass", {.technique = Technique::Hierarchical, .tracePass = TracePass::Compute}}};
    const DirectionalLight light{.direction = {0.6f, 0.5f, 0.4f}};
    RenderTarget target(W, H);
    SurfaceRenderer renderer;
    for (const Scene& scene : scenes) {
        SCOPED_TRACE(scene.name);
        const SurfaceMaterial material{.depthScale = scene.depthScale, .lodThreshold = 100.0f};
        auto depthOf = [&](const DrawOptions& options) {
            target.bind();
            target.clear();
            renderer.draw(*scene.mesh, glm::mat4(1.0f), textures, material, scene.camera, light, options);
            return target.readDepth();
        };
        // Normal mapping writes no depth: the rasteriser's, the polygon's.
        const std::vector<float> polygon = depthOf({.technique = Technique::NormalMapping});
        size_t covered = 0;
        for (float d : polygon) covered += d < 1.0f;
        ASSERT_GT(covered, size_t(W * H / 5));
        for (const Drawn& d : drawn) {
            SCOPED_TRACE(d.name);
            const std::vector<float> traced = depthOf(d.options);
            size_t inFront = 0, behind = 0, uncovered = 0;
            float worst = 0.0f;
            for (size_t i = 0; i < polygon.size(); ++i) {
                if (polygon[i] >= 1.0f) continue;
                if (traced[i] >= 1.0f) ++uncovered; // a finite patch's ray that left it, discarded
                else if (traced[i] < polygon[i]) ++inFront, worst = std::max(worst, polygon[i] - traced[i]);
                else if (traced[i] > polygon[i]) ++behind;
            }
            EXPECT_EQ(inFront, 0u) << "by up to " << worst << " in window depth";
            // Not vacuous: the relief is written, behind the polygon, on most of it.
            EXPECT_GT(behind, covered / 2) << covered << " pixels covered, " << uncovered << " not drawn";
        }
    }
}

/// The distance along the view of a window depth, by the camera's convention.
double eyeDepth(float depth, const Camera& camera) {
    const double n = camera.nearPlane, f = camera.farPlane;
    if (camera.reversedZ) return n * f / (double(depth) * (f - n) + n); // clip depth = window depth, near at 1
    const double ndc = 2.0 * depth - 1.0;
    return 2.0 * n * f / (f + n - ndc * (f - n));
}

/// Reversed Z for the scope: GL's [0, 1] clip depth, as an engine that uses it sets it.
struct ZeroToOneClipDepth {
    ZeroToOneClipDepth() { glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE); }
    ~ZeroToOneClipDepth() { glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE); }
};

// An engine with a reversed-Z depth buffer (near at 1, GL_ZERO_TO_ONE, GL_GREATER, cleared to 0)
// gets the frame GL's default depth gives: the same sky behind, the relief's traced depth clipping
// a quad crossing it at the same pixels, the same shadows from a shadow map drawn under that state
// (its pass draws with GL's default), every depth the same distance from the eye and every walk as
// long, for POM and for hier walking in the draw and in a compute pass.
TEST_F(DepthOutput, AReversedZViewDrawsTheFrameGlsDefaultDepthDraws) {
    constexpr int field = 64, W = 200, H = 150;
    constexpr float depthScale = 0.15f, planeSize = 2.0f, quadHeight = 0.5f;
    const SineRelief relief(field, depthScale);
    const SurfaceTextures& textures = relief.textures;
    const Mesh plane(makePlane({.size = planeSize}));
    const glm::mat4 quadModel = glm::translate(glm::mat4(1.0f), glm::vec3(0.2f, -(1.0f - quadHeight) * depthScale * planeSize, 0.0f)) *
                                glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
    const SurfaceMaterial material{.depthScale = depthScale, .lodThreshold = 100.0f};
    // Two depth ranges: a usual one, and one under twice its near plane, where a clip depth of the
    // other convention's near plane (-1) lies beyond the far one, so that only the convention's own
    // planes give the beam start's rays their direction (else hier walks from the top: the same
    // hits in more fetches, which the trace output counts).
    Camera camera = cameraAtAngle(55, 4.0f, float(W) / float(H));
    ShadowMap map(512);
    DirectionalLight light{.direction = {0.5f, 0.8f, 0.3f}};
    map.fit(light.direction, {0.0f, 0.0f, 0.0f}, 1.6f);
    light.shadowMap = &map;
    RenderTarget target(W, H, true);
    SurfaceRenderer renderer;
    const glm::vec4 background{0.2f, 0.3f, 0.4f, 1.0f};
    DirectionalLight unshadowed = light;
    unshadowed.shadowMap = nullptr;
    auto frame = [&](const DrawOptions& options, bool reversed, std::vector<float>& depth,
                     const DirectionalLight& lit, std::vector<glm::vec4>* trace = nullptr) {
        Camera c = camera;
        c.reversedZ = reversed;
        {
            const ShadowMap::Scope casting(map);
            renderer.drawShadow(plane, glm::mat4(1.0f), textures, material, map, options);
            renderer.drawFlatShadow(plane, quadModel, map);
        }
        target.bind();
        target.clear(background, {}, reversed ? 0.0f : 1.0f);
        renderer.drawSky(c, lit, WaterLook{});
        DrawOptions o = options;
        o.traceOutput = trace != nullptr;
        renderer.draw(plane, glm::mat4(1.0f), textures, material, c, lit, o);
        if (trace) *trace = target.readTrace();
        renderer.drawFlat(plane, quadModel, c, {1.0f, 0.0f, 0.0f, 1.0f}, &lit);
        depth = target.readDepth();
        return target.readColor();
    };
    const auto& drawn = kPomAndHier;
    for (const glm::vec2 range : {glm::vec2(0.5f, 20.0f), glm::vec2(3.0f, 5.8f)})
    for (const auto& [name, options] : drawn) {
        SCOPED_TRACE(name);
        SCOPED_TRACE(testing::Message() << "near " << range.x << ", far " << range.y);
        camera.nearPlane = range.x;
        camera.farPlane = range.y;
        std::vector<float> standardDepth, reversedDepth, unusedDepth;
        std::vector<glm::vec4> standardTrace, reversedTrace;
        const Image standard = frame(options, false, standardDepth, light, &standardTrace);
        const Image noShadowMap = frame(options, false, unusedDepth, unshadowed);
        Image reversed;
        {
            const ZeroToOneClipDepth zeroToOne;
            reversed = frame(options, true, reversedDepth, light, &reversedTrace);
        }
        Camera reversedCamera = camera;
        reversedCamera.reversedZ = true;
        size_t covered = 0, red = 0, shadowed = 0, differ = 0, walkedApart = 0;
        double worstDepth = 0.0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const size_t i = size_t(y) * W + x; // readDepth's order: bottom row first
                const int row = H - 1 - y;          // readColor's: top row first
                const bool drawnStandard = standardDepth[i] < 1.0f, drawnReversed = reversedDepth[i] > 0.0f;
                EXPECT_EQ(drawnStandard, drawnReversed) << "pixel " << x << ", " << y;
                float diff = 0.0f;
                for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(standard.at(x, row, c) - reversed.at(x, row, c)));
                differ += diff > 2.0f / 255.0f;
                if (!drawnStandard || !drawnReversed) continue;
                ++covered;
                walkedApart += std::floor(standardTrace[i].w) != std::floor(reversedTrace[i].w); // the fetches made
                red += standard.at(x, row, 0) > 0.5f && standard.at(x, row, 1) < 0.1f;
                shadowed += standard.at(x, row, 1) < noShadowMap.at(x, row, 1) - 0.1f; // the quad's shadow
                const double a = eyeDepth(standardDepth[i], camera), b = eyeDepth(reversedDepth[i], reversedCamera);
                worstDepth = std::max(worstDepth, std::abs(a - b) / a);
            }
        // Not vacuous: the quad shows through the relief and hides in it, and shadows fall.
        ASSERT_GT(covered, size_t(W * H / 4));
        EXPECT_GT(red, covered / 50);
        EXPECT_LT(red, covered / 2);
        EXPECT_GT(shadowed, covered / 200);
        // Where the quad and the relief cross, their depths' roundings may decide a pixel apart.
        EXPECT_LT(differ, covered / 500) << covered << " pixels covered";
        EXPECT_LT(worstDepth, 1e-3) << "the relative difference of the distances along the view";
        EXPECT_EQ(walkedApart, 0u) << "pixels whose walk made another number of fetches";
        if (differ >= covered / 500) {
            writeImage(outputPath(std::string("reversed_z_") + name + "_standard.png"), standard);
            writeImage(outputPath(std::string("reversed_z_") + name + "_reversed.png"), reversed);
        }
    }
}

// An engine's own projection (Camera::customProjection): an off-axis frustum, a VR eye's or a tile
// of a wider view, draws exactly its part of the frame the symmetric lens draws over the whole
// view, each technique's relief, its self-shadows and its depth, hier in the draw and in a compute
// pass; so does the same camera made from the engine's matrices (Camera::fromMatrices).
TEST_F(DepthOutput, AnOffAxisFrustumDrawsItsPartOfTheWideFrame) {
    constexpr int field = 64, W = 160, H = 120; // the right half of a 2W x H view
    constexpr float depthScale = 0.12f;
    const SineRelief relief(field, depthScale);
    const SurfaceTextures& textures = relief.textures;
    const Mesh plane(makePlane({.size = 2.0f}));
    const SurfaceMaterial material{.depthScale = depthScale, .lodThreshold = 100.0f};
    const DirectionalLight light{.direction = {0.6f, 0.5f, 0.4f}};
    Camera wide = Camera::orbit({-0.6f, 0.0f, 0.0f}, 2.6f, 0.2f, 0.8f);
    wide.aspect = 2.0f * W / H;
    wide.nearPlane = 0.1f;
    wide.farPlane = 20.0f;
    const float top = wide.nearPlane * std::tan(0.5f * wide.fovY), right = top * wide.aspect;
    Camera half = wide;
    half.customProjection = glm::frustum(0.0f, right, -top, top, wide.nearPlane, wide.farPlane);
    const Camera engine = Camera::fromMatrices(wide.view(), *half.customProjection);
    RenderTarget wideTarget(2 * W, H), halfTarget(W, H);
    SurfaceRenderer renderer;
    auto draw = [&](const RenderTarget& target, const Camera& camera, const DrawOptions& options, std::vector<float>& depth) {
        target.bind();
        target.clear({0.2f, 0.3f, 0.4f, 1.0f});
        renderer.draw(plane, glm::mat4(1.0f), textures, material, camera, light, options);
        depth = target.readDepth();
        return target.readColor();
    };
    const std::pair<const char*, DrawOptions> drawn[] = {
        {"pom", {.technique = Technique::ParallaxOcclusion}},
        {"hier in the draw", {.technique = Technique::Hierarchical, .texelShadows = TexelShadowChoice::Off, .tracePass = TracePass::InDraw}},
        {"hier in a compute pass", {.technique = Technique::Hierarchical, .texelShadows = TexelShadowChoice::Off, .tracePass = TracePass::Compute}}};
    for (const auto& [name, options] : drawn)
        for (const Camera* camera : {static_cast<const Camera*>(&half), &engine}) {
            SCOPED_TRACE(testing::Message() << name << (camera == &engine ? ", from the engine's matrices" : ""));
            std::vector<float> wideDepth, halfDepth;
            const Image whole = draw(wideTarget, wide, options, wideDepth), part = draw(halfTarget, *camera, options, halfDepth);
            size_t covered = 0, apart = 0;
            float worstDepth = 0.0f;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    float diff = 0.0f;
                    for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(part.at(x, y, c) - whole.at(W + x, y, c)));
                    apart += diff > 2.0f / 255.0f;
                    const float a = halfDepth[size_t(y) * W + x], b = wideDepth[size_t(y) * 2 * W + W + x];
                    covered += a < 1.0f;
                    worstDepth = std::max(worstDepth, std::abs(a - b));
                }
            ASSERT_GT(covered, size_t(W * H / 3));
            EXPECT_LE(apart, covered / 1000) << covered << " pixels covered";
            EXPECT_LT(worstDepth, 1e-5f) << "in window depth";
        }
}

// A mirror's view (an engine's planar reflection: its view times a reflection, Camera::mirrored)
// draws the frame flipped left to right: each pixel shows what the unmirrored view shows at its
// mirror image, the sky, a plane's relief and a sphere's (a closed mesh whose back faces are culled:
// a mirror turns the winding of its front faces), with the same depth, for POM and for hier walking
// in the draw and in a compute pass (whose rays draw keeps the front faces' fragments).
TEST_F(DepthOutput, AMirrorsViewDrawsTheFrameFlippedLeftToRight) {
    constexpr int field = 64, W = 200, H = 150;
    const SineRelief relief(field, 0.12f);
    const Mesh plane(makePlane({.size = 2.0f})), sphere(makeSphere({.radius = 0.4f}));
    const glm::mat4 sphereModel = glm::translate(glm::mat4(1.0f), glm::vec3(0.4f, 0.5f, -0.2f));
    const DirectionalLight light{.direction = {0.6f, 0.5f, 0.4f}};
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 3.0f, 0.5f, 0.6f);
    camera.aspect = float(W) / float(H);
    const Camera mirror = Camera::fromMatrices(glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f)) * camera.view(),
                                               camera.projection());
    ASSERT_TRUE(mirror.mirrored);
    RenderTarget target(W, H);
    SurfaceRenderer renderer;
    auto draw = [&](const Camera& c, const DrawOptions& options, std::vector<float>& depth) {
        target.bind();
        target.clear();
        renderer.drawSky(c, light, WaterLook{});
        renderer.draw(plane, glm::mat4(1.0f), relief.textures, {.depthScale = 0.12f, .lodThreshold = 100.0f}, c, light, options);
        renderer.draw(sphere, sphereModel, relief.textures, {.depthScale = 0.02f, .lodThreshold = 100.0f}, c, light, options);
        depth = target.readDepth();
        return target.readColor();
    };
    const auto& drawn = kPomAndHier;
    for (const auto& [name, options] : drawn) {
        SCOPED_TRACE(name);
        std::vector<float> depth, mirroredDepth;
        const Image seen = draw(camera, options, depth), mirrored = draw(mirror, options, mirroredDepth);
        if (options.tracePass == TracePass::Compute) {
            EXPECT_TRUE(renderer.tracer().last().computeTrace);
        }
        size_t covered = 0, apart = 0;
        float worstDepth = 0.0f;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const int flipped = W - 1 - x;
                float diff = 0.0f;
                for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(mirrored.at(x, y, c) - seen.at(flipped, y, c)));
                apart += diff > 2.0f / 255.0f;
                const float a = mirroredDepth[size_t(y) * W + x], b = depth[size_t(y) * W + flipped];
                covered += b < 1.0f;
                worstDepth = std::max(worstDepth, std::abs(a - b));
            }
        std::printf("[mirror] %s: %zu of %zu pixels apart, depths within %g\n", name, apart, size_t(W) * H, worstDepth);
        ASSERT_GT(covered, size_t(W * H / 3));
        EXPECT_LE(apart, covered / 1000) << covered << " pixels covered";
        EXPECT_LT(worstDepth, 1e-5f) << "in window depth";
        if (apart > covered / 1000) {
            writeImage(outputPath(std::string("mirror_") + name + "_seen.png"), seen);
            writeImage(outputPath(std::string("mirror_") + name + "_mirrored.png"), mirrored);
        }
    }
}

// An engine's planar reflection: the wall standing in the water seen in it, drawn with the
// camera's view times the reflection about the water (y = 0) and a projection whose near plane is
// the water (obliqueNearPlane), so that what lies under it is clipped. Each pixel whose relief lies
// above the water shows what the same mirror's view shows with the plain projection, its hit at the
// same point; each pixel whose relief lies under it shows the sky behind, as does every pixel of
// the sky (its directions unprojected through the tilted far plane); for POM and for hier walking
// in the draw and in a compute pass, the beam start's rays begun on the tilted near plane.
TEST_F(DepthOutput, APlanarReflectionsObliqueNearPlaneClipsTheReliefAtTheWater) {
    constexpr int field = 64, W = 200, H = 150;
    constexpr float depthScale = 0.12f;
    const SineRelief relief(field, depthScale);
    const Mesh wall(makePlane({.size = 2.0f}));
    // Upright, facing +z, from y = -0.7 to 1.3: it stands in the water.
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.3f, 0.0f)) *
                            glm::rotate(glm::mat4(1.0f), 1.5707963f, glm::vec3(1.0f, 0.0f, 0.0f));
    const SurfaceMaterial material{.depthScale = depthScale, .lodThreshold = 100.0f};
    const DirectionalLight light{.direction = {0.5f, 0.7f, 0.5f}};
    Camera camera = Camera::orbit({0.0f, 0.2f, 0.0f}, 3.0f, 0.4f, 0.25f);
    camera.aspect = float(W) / float(H);
    const glm::mat4 mirrorView = camera.view() * glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, -1.0f, 1.0f));
    const glm::vec4 water = glm::transpose(glm::inverse(mirrorView)) * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f);
    const Camera plain = Camera::fromMatrices(mirrorView, camera.projection());
    const Camera clipped = Camera::fromMatrices(mirrorView, obliqueNearPlane(camera.projection(), water));
    ASSERT_LT(plain.position.y, 0.0f) << "the mirror's eye lies under the water";
    RenderTarget target(W, H, true);
    SurfaceRenderer renderer;
    auto draw = [&](const Camera& c, const DrawOptions* options, std::vector<float>& depth, std::vector<glm::vec4>& trace) {
        target.bind();
        target.clear();
        renderer.drawSky(c, light, WaterLook{});
        if (options) {
            DrawOptions o = *options;
            o.traceOutput = true;
            renderer.draw(wall, model, relief.textures, material, c, light, o);
        }
        depth = target.readDepth();
        trace = target.readTrace();
        return target.readColor();
    };
    std::vector<float> skyDepth;
    std::vector<glm::vec4> skyTrace;
    const Image sky = draw(plain, nullptr, skyDepth, skyTrace);
    auto worldAt = [&](const Camera& c, int x, int y, float depth) {
        const glm::dvec4 p = glm::inverse(glm::dmat4(c.viewProjection())) *
                             glm::dvec4((x + 0.5) / W * 2.0 - 1.0, (y + 0.5) / H * 2.0 - 1.0, 2.0 * depth - 1.0, 1.0);
        return glm::dvec3(p) / p.w;
    };
    const auto& drawn = kPomAndHier;
    for (const auto& [name, options] : drawn) {
        SCOPED_TRACE(name);
        std::vector<float> plainDepth, clippedDepth;
        std::vector<glm::vec4> plainTrace, clippedTrace;
        const Image whole = draw(plain, &options, plainDepth, plainTrace), cut = draw(clipped, &options, clippedDepth, clippedTrace);
        size_t above = 0, under = 0, skyward = 0, apart = 0, walkedApart = 0;
        double worstHit = 0.0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const int row = H - 1 - y;
                const size_t i = size_t(y) * W + x;
                // 0.25 above or under: a hit lies up to the relief's depth (0.24) from its polygon.
                const double height = plainDepth[i] < 1.0f ? worldAt(plain, x, y, plainDepth[i]).y : 1e9;
                const bool isSky = plainDepth[i] >= 1.0f, kept = !isSky && height > 0.25, gone = !isSky && height < -0.25;
                if (!isSky && !kept && !gone) continue;
                const Image& expected = kept ? whole : sky;
                float diff = 0.0f;
                for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(cut.at(x, row, c) - expected.at(x, row, c)));
                apart += diff > 2.0f / 255.0f;
                (kept ? above : gone ? under : skyward)++;
                if (kept) walkedApart += std::floor(plainTrace[i].w) != std::floor(clippedTrace[i].w); // the fetches made
                if (kept && clippedDepth[i] < 1.0f)
                    worstHit = std::max(worstHit, glm::length(worldAt(clipped, x, y, clippedDepth[i]) -
                                                              worldAt(plain, x, y, plainDepth[i])));
            }
        std::printf("[reflection] %s: %zu pixels above the water, %zu under, %zu of the sky; %zu apart; hits within %g; %zu walks of "
                    "another length\n",
                    name, above, under, skyward, apart, worstHit, walkedApart);
        ASSERT_GT(above, size_t(W * H / 10));
        ASSERT_GT(under, size_t(W * H / 20));
        ASSERT_GT(skyward, size_t(W * H / 10));
        EXPECT_LE(apart, (above + under + skyward) / 1000);
        EXPECT_LT(worstHit, 1e-3) << "world units (the wall is 2 across)";
        // (The clipped view's rays are its rasteriser's interpolation of another projection: an
        // H200 walked 7 of 5114 to another length, llvmpipe none.)
        EXPECT_LE(walkedApart, above / 250) << "pixels whose walk made another number of fetches";
        if (apart > (above + under + skyward) / 1000) {
            writeImage(outputPath(std::string("reflection_") + name + "_plain.png"), whole);
            writeImage(outputPath(std::string("reflection_") + name + "_clipped.png"), cut);
        }
    }
}

// An orthographic camera (an editor's or a top-down game's view, Camera::customProjection from
// glm::ortho): every pixel's ray runs along the view axis, so hier's walk finds, at every pixel,
// the exact hit of that parallel ray on the bilinear relief (HeightFieldTracer), and writes its
// depth, in the draw and in a compute pass; the sky behind is the one colour of the one view
// direction. Rays from the camera's position through the same pixels would hit elsewhere.
TEST_F(DepthOutput, AnOrthographicViewTracesEachPixelsParallelRayToItsExactHit) {
    constexpr int field = 64, W = 160, H = 120;
    constexpr float depthScale = 0.15f, planeSize = 2.0f;
    const SineRelief relief(field, depthScale);
    const Mesh plane(makePlane({.size = planeSize}));
    const SurfaceMaterial material{.depthScale = depthScale, .lodThreshold = 100.0f};
    const DirectionalLight light{.direction = {0.6f, 0.5f, 0.4f}};
    const Camera lens = cameraAtAngle(62, 1.6f, float(W) / float(H));
    const float halfHeight = 0.9f, halfWidth = halfHeight * float(W) / float(H);
    const Camera camera = Camera::fromMatrices(lens.view(), glm::ortho(-halfWidth, halfWidth, -halfHeight, halfHeight, 0.2f, 10.0f));
    ASSERT_TRUE(camera.orthographic());
    const HeightFieldTracer exact(relief.heights, field, field, EdgeMode::Wrap);
    RenderTarget target(W, H, true);
    SurfaceRenderer renderer;
    const glm::dmat4 viewProj(camera.viewProjection());
    for (const TracePass pass : {TracePass::InDraw, TracePass::Compute}) {
        SCOPED_TRACE(pass == TracePass::Compute ? "in a compute pass" : "in the draw");
        target.bind();
        target.clear({0, 0, 0, 1}, {0, 0, 0, 0});
        renderer.drawSky(camera, light, WaterLook{});
        renderer.draw(plane, glm::mat4(1.0f), relief.textures, material, camera, light,
                      {.technique = Technique::Hierarchical, .traceOutput = true, .tracePass = pass});
        EXPECT_EQ(renderer.tracer().last().computeTrace, pass == TracePass::Compute);
        const std::vector<glm::vec4> trace = target.readTrace();
        const std::vector<float> depth = target.readDepth();
        const Image colour = target.readColor();
        size_t traced = 0, off = 0, depthOff = 0, elsewhere = 0, skyApart = 0, sky = 0;
        double worst = 0.0, worstDepth = 0.0;
        glm::vec3 skyColour(-1.0f);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const size_t i = size_t(y) * W + x;
                glm::dvec2 uv0;
                glm::dvec3 toEye;
                if (!planePixelRay(camera, planeSize, x, y, W, H, uv0, toEye)) {
                    if (depth[i] < 1.0f) continue; // (the plane's rim)
                    const glm::vec3 c(colour.at(x, H - 1 - y, 0), colour.at(x, H - 1 - y, 1), colour.at(x, H - 1 - y, 2));
                    if (skyColour.x < 0.0f) skyColour = c;
                    skyApart += glm::length(c - skyColour) > 1.5f / 255.0f;
                    ++sky;
                    continue;
                }
                const auto hit = exact.traceView(uv0, toEye, depthScale);
                if (!hit || !(trace[i].z > 0.0f)) continue;
                ++traced;
                const double error = glm::length(glm::dvec2(trace[i]) - hit->uv) * field; // texels
                worst = std::max(worst, error);
                off += error > 0.01;
                // The hit's point in the world (makePlane: u along +x, v along -z) and its depth.
                const glm::dvec3 p((hit->uv.x - 0.5) * planeSize, -(1.0 - hit->height) * depthScale * planeSize,
                                   (0.5 - hit->uv.y) * planeSize);
                const glm::dvec4 clip = viewProj * glm::dvec4(p, 1.0);
                const double windowDepth = 0.5 * clip.z / clip.w + 0.5;
                worstDepth = std::max(worstDepth, std::abs(windowDepth - depth[i]));
                // (An H200's draw: within 2.1e-5, its hits up to 0.006 texels off; the relief spans 0.02.)
                depthOff += std::abs(windowDepth - depth[i]) > 1e-4;
                // The same pixel's ray from the camera's position: a perspective relief's hit.
                const glm::dvec3 from = glm::dvec3(camera.position) - glm::dvec3((uv0.x - 0.5) * planeSize, 0.0, (0.5 - uv0.y) * planeSize);
                const auto perspective = exact.traceView(uv0, glm::dvec3(from.x, -from.z, from.y) / double(planeSize), depthScale);
                elsewhere += perspective && glm::length(perspective->uv - hit->uv) * field > 0.5;
            }
        std::printf("[orthographic] %zu traced pixels, %zu off the exact hit by more than 0.01 texels (%.2g at most); depths "
                    "within %.2g; %zu would hit elsewhere from the camera's position; %zu sky pixels, %zu apart\n",
                    traced, off, worst, worstDepth, elsewhere, sky, skyApart);
        ASSERT_GT(traced, size_t(W * H / 3));
        ASSERT_GT(sky, size_t(W * H / 20));
        EXPECT_GT(elsewhere, traced / 2);
        EXPECT_LE(off, traced / 1000);
        EXPECT_EQ(depthOff, 0u);
        EXPECT_EQ(skyApart, 0u);
    }
    // Looking at the horizon, where the sky's colour changes fastest with the direction: one colour.
    const Camera level = Camera::fromMatrices(glm::lookAt(glm::vec3(0.0f, 0.5f, 3.0f), glm::vec3(0.0f, 0.45f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)),
                                              glm::ortho(-halfWidth, halfWidth, -halfHeight, halfHeight, 0.2f, 10.0f));
    target.bind();
    target.clear();
    renderer.drawSky(level, light, WaterLook{});
    const Image sky = target.readColor();
    float spread = 0.0f;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) spread = std::max(spread, std::abs(sky.at(x, y, c) - sky.at(0, 0, c)));
    EXPECT_LE(spread, 1.5f / 255.0f) << "the sky of one view direction";
}

/// An engine's multisampled colour and depth target (MSAA), resolved into a RenderTarget's colour.
struct MultisampledTarget {
    MultisampledTarget(int w, int h, int samples)
        : width(w), height(h), fbo(GlFramebuffer::create()), colour(GlRenderbuffer::create()),
          depth(GlRenderbuffer::create()) {
        glNamedRenderbufferStorageMultisample(colour.id(), samples, GL_RGBA8, width, height);
        glNamedRenderbufferStorageMultisample(depth.id(), samples, GL_DEPTH_COMPONENT32F, width, height);
        glNamedFramebufferRenderbuffer(fbo.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour.id());
        glNamedFramebufferRenderbuffer(fbo.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
    }
    void bind(const glm::vec4& background) const {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glViewport(0, 0, width, height);
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, &background.x);
        const float far = 1.0f;
        glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far);
    }
    Image resolved(const RenderTarget& into) const {
        glBlitNamedFramebuffer(fbo.id(), into.framebuffer(), 0, 0, width, height, 0, 0, width, height,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
        return into.readColor();
    }
    int width, height;
    GlFramebuffer fbo;
    GlRenderbuffer colour, depth;
};

// An engine's multisampled target (MSAA): a fragment shades once for the samples its polygon
// covers and writes one traced depth for all of them. Every technique then draws the
// single-sampled frame wherever a pixel's samples all show one thing (the sky, the relief, a quad
// crossing it, a nearer plane over it), and only the pixels on an edge between two of them are
// blended. The exact tracer walks in the draw there (its compute pass needs one fragment a pixel),
// and its deferred light walks write only the samples their own draw wrote: their frame is the
// one whose draw walks those rays itself.
TEST_F(DepthOutput, AMultisampledTargetDrawsTheSingleSampledFrameButAtItsEdges) {
    constexpr int field = 64, W = 200, H = 150, samples = 4;
    constexpr float depthScale = 0.12f, planeSize = 2.0f, quadHeight = 0.5f;
    const SineRelief relief(field, depthScale);
    const SurfaceTextures& textures = relief.textures;
    SineRelief green(field, depthScale);
    green.textures.setAlbedo(Image{1, 1, 3, {0.2f, 0.6f, 0.2f}});
    const Mesh plane(makePlane({.size = planeSize})), cover(makePlane({.size = 0.6f}));
    const glm::mat4 quadModel = glm::translate(glm::mat4(1.0f), glm::vec3(0.2f, -(1.0f - quadHeight) * depthScale * planeSize, 0.0f)) *
                                glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
    const glm::mat4 nearer = glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f, 0.35f, 0.3f));
    const SurfaceMaterial material{.depthScale = depthScale, .lodThreshold = 100.0f};
    const DirectionalLight light{.direction = {0.7f, 0.45f, 0.3f}};
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.2f, 0.3f, 1.0f);
    camera.aspect = float(W) / float(H);
    const glm::vec4 background{0.2f, 0.3f, 0.4f, 1.0f};
    RenderTarget single(W, H), resolve(W, H);
    MultisampledTarget msaa(W, H, samples);
    GLint got = 0;
    glGetNamedRenderbufferParameteriv(msaa.colour.id(), GL_RENDERBUFFER_SAMPLES, &got);
    ASSERT_GE(got, samples) << "the context has no " << samples << "x multisampling";
    ASSERT_EQ(glCheckNamedFramebufferStatus(msaa.fbo.id(), GL_DRAW_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    SurfaceRenderer renderer;
    auto scene = [&](const DrawOptions& options) {
        renderer.drawSky(camera, light, WaterLook{});
        renderer.draw(cover, nearer, green.textures, material, camera, light, {.technique = Technique::NormalMapping});
        renderer.draw(plane, glm::mat4(1.0f), textures, material, camera, light, options);
        renderer.drawFlat(plane, quadModel, camera, {1.0f, 0.0f, 0.0f, 1.0f}, &light);
    };
    // Shaded once a fragment, or once a sample (an engine's sample-rate shading: each sample
    // writes its own traced depth, and appends its own light walk).
    bool perSample = false;
    auto multisampled = [&](const DrawOptions& options) {
        msaa.bind(background);
        if (perSample) glEnable(GL_SAMPLE_SHADING), glMinSampleShading(1.0f);
        scene(options);
        glDisable(GL_SAMPLE_SHADING);
        return msaa.resolved(resolve);
    };
    // What a pixel of the single-sampled frame shows: 0 the sky, 1 the relief (grey), 2 the quad
    // (red), 3 the nearer plane (green); -1 for a pixel by an edge between two of them.
    auto shows = [&](const Image& frame, const std::vector<float>& depth, int x, int y) {
        if (depth[size_t(y) * W + x] >= 1.0f) return 0;
        const int row = H - 1 - y;
        const float r = frame.at(x, row, 0), g = frame.at(x, row, 1), b = frame.at(x, row, 2);
        return r > g + 0.1f && r > b + 0.1f ? 2 : g > r + 0.1f ? 3 : 1;
    };
    auto inside = [&](const Image& frame, const std::vector<float>& depth, int x, int y) {
        const int what = shows(frame, depth, x, y);
        for (int v = std::max(y - 1, 0); v <= std::min(y + 1, H - 1); ++v)
            for (int u = std::max(x - 1, 0); u <= std::min(x + 1, W - 1); ++u)
                if (shows(frame, depth, u, v) != what) return -1;
        return what;
    };
    auto apart = [](const Image& a, const Image& b, int x, int y) {
        float diff = 0.0f;
        for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(a.at(x, y, c) - b.at(x, y, c)));
        return diff > 2.0f / 255.0f;
    };
    const std::pair<const char*, DrawOptions> drawn[] = {
        {"pom", {.technique = Technique::ParallaxOcclusion}},
        {"hier", {.technique = Technique::Hierarchical}},
        {"hier, its compute pass asked", {.technique = Technique::Hierarchical, .texelShadows = TexelShadowChoice::Off, .tracePass = TracePass::Compute}},
        {"hier, its texel shadows' light walks deferred", {.technique = Technique::Hierarchical, .texelShadows = TexelShadowChoice::On, .deferShadowWalks = true}}};
    int fragmentWalks = 0;
    for (const bool sampleRate : {false, true}) {
        perSample = sampleRate;
        const char* shading = sampleRate ? "per sample" : "per fragment";
        SCOPED_TRACE(shading);
        for (const auto& [name, options] : drawn) {
            SCOPED_TRACE(name);
            single.bind();
            single.clear(background);
            scene(options);
            const Image one = single.readColor();
            const std::vector<float> depth = single.readDepth();
            const Image many = multisampled(options);
            std::array<size_t, 4> interior{};
            size_t edges = 0, blended = 0, interiorApart = 0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    const int what = inside(one, depth, x, y);
                    const bool differ = apart(one, many, x, H - 1 - y);
                    if (what < 0) ++edges, blended += differ;
                    else ++interior[size_t(what)], interiorApart += differ;
                }
            const size_t total = size_t(W) * H - edges;
            std::printf("[msaa] %s, %s: %zu of %zu pixels inside apart; %zu of %zu by an edge blended\n", shading, name, interiorApart, total,
                        blended, edges);
            // Not vacuous: each thing shows, and the target is multisampled (its edges are blended).
            for (size_t what = 0; what < interior.size(); ++what) EXPECT_GT(interior[what], size_t(W * H / 100)) << "shows " << what;
            EXPECT_GT(blended, edges / 4) << "no edge antialiased";
            EXPECT_LE(interiorApart, total / 1000);
            if (interiorApart > total / 1000) {
                writeImage(outputPath(std::string("msaa_") + shading + "_" + name + "_single.png"), one);
                writeImage(outputPath(std::string("msaa_") + shading + "_" + name + "_resolved.png"), many);
            }
        }
        // The compute pass asked: a multisampled draw walks in the draw, and the deferred walks are
        // taken and write the frame the draw that walks them itself gives, edges included.
        (void)multisampled(drawn[2].second);
        EXPECT_FALSE(renderer.tracer().last().computeTrace);
        const Image deferred = multisampled(drawn[3].second);
        EXPECT_TRUE(renderer.tracer().last().deferredShadows);
        const int walks = renderer.tracer().deferredWalks();
        DrawOptions walked = drawn[3].second;
        walked.deferShadowWalks = false;
        const Image inDraw = multisampled(walked);
        size_t deferredApart = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) deferredApart += apart(deferred, inDraw, x, y);
        std::printf("[msaa] %s, deferred light walks: %d rays; %zu pixels apart from the walks in the draw\n", shading, walks, deferredApart);
        EXPECT_GT(walks, 100) << "too few rays deferred to tell";
        if (sampleRate) {
            EXPECT_GT(walks, 2 * fragmentWalks) << "shaded once a fragment still";
        }
        fragmentWalks = walks;
        EXPECT_LE(deferredApart, size_t(W * H / 10000));
    }
}

// A view whose depth convention is not the GL state's would be drawn wrong without a word (its
// traced depths written for the other convention, its depth test facing the wrong way, half the
// scene clipped): every draw refuses it by name before it changes anything.
TEST_F(DepthOutput, AViewThatIsNotGlsDepthConventionIsRefusedByName) {
    constexpr int field = 32;
    const auto heights = sumOfSines(field, {{0.3, 2, 1, 0.0}});
    SurfaceTextures textures({.width = field, .height = field, .mipmaps = false, .normalDepth = 0.1f});
    textures.uploadTexels(sobelReference(heights, field, 0.1f).data());
    const Mesh plane(makePlane({}));
    const SurfaceMaterial material{.depthScale = 0.1f};
    RenderTarget target(64, 64);
    target.bind();
    target.clear({0.25f, 0.5f, 0.75f, 1.0f});
    const Image before = target.readColor();
    SurfaceRenderer renderer;
    PlanetRings rings;
    const Camera standard = cameraAtAngle(40, 3.0f, 1.0f);
    Camera reversed = standard;
    reversed.reversedZ = true;
    const DirectionalLight light;
    auto refusals = [&](const Camera& camera) {
        std::vector<std::string> messages;
        messages.push_back(messageOf([&] { renderer.draw(plane, glm::mat4(1.0f), textures, material, camera, light); }));
        messages.push_back(messageOf([&] { renderer.drawFlat(plane, glm::mat4(1.0f), camera, glm::vec4(1.0f)); }));
        messages.push_back(messageOf([&] { rings.draw(glm::mat4(1.0f), camera, light); }));
        return messages;
    };
    for (const std::string& m : refusals(reversed))
        EXPECT_NE(m.find("reversed-Z (Camera::reversedZ), but the clip depth mode is GL_NEGATIVE_ONE_TO_ONE"),
                  std::string::npos) << m;
    {
        const ZeroToOneClipDepth zeroToOne;
        for (const std::string& m : refusals(standard))
            EXPECT_NE(m.find("the clip depth mode is GL_ZERO_TO_ONE"), std::string::npos) << m;
        glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
        for (const std::string& m : refusals(reversed))
            EXPECT_NE(m.find("the clip origin is GL_UPPER_LEFT"), std::string::npos) << m;
    }
    glDepthRange(1.0, 0.0);
    for (const std::string& m : refusals(standard))
        EXPECT_NE(m.find("the depth range must have its near below its far (glDepthRange), got 1 and 0"),
                  std::string::npos) << m;
    glDepthRange(0.0, 1.0);
    EXPECT_EQ(target.readColor().pixels, before.pixels) << "a refused draw left pixels behind";
    // The state put back, both conventions draw.
    EXPECT_EQ(refusals(standard), std::vector<std::string>(3, "(no error)"));
}

} // namespace
} // namespace hfx::test
