// A flat quad crossing the relief must be clipped where the displaced surface is, not where the
// polygon is: POM writes gl_FragDepth of the displaced point.

#include "support/Fields.h"
#include "support/References.h"
#include "support/Fixtures.h"

#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <glm/gtc/matrix_transform.hpp>

namespace hfx::test {
namespace {

class DepthOutput : public GlTest {};

TEST_F(DepthOutput, QuadIsClippedAtTheDisplacedSurface) {
    constexpr int field = 64, image = 160;
    constexpr float depthScale = 0.15f, planeSize = 2.0f;
    const auto heights = sumOfSines(field, {{0.3, 2, 1, 0.0}, {0.15, -1, 2, 0.7}});
    SurfaceTextures textures({.width = field, .height = field, .mipmaps = false, .normalDepth = depthScale});
    textures.uploadTexels(sobelReference(heights, field, depthScale).data());
    textures.setAlbedo(Image{1, 1, 3, {0.5f, 0.5f, 0.5f}});
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
    const auto heights = sumOfSines(field, {{0.3, 2, 1, 0.0}, {0.15, -1, 2, 0.7}});
    SurfaceTextures textures({.width = field, .height = field, .mipmaps = false, .normalDepth = depthScale});
    textures.uploadTexels(sobelReference(heights, field, depthScale).data());
    textures.setAlbedo(Image{1, 1, 3, {0.5f, 0.5f, 0.5f}});
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

} // namespace
} // namespace hfx::test
