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

} // namespace
} // namespace hfx::test
