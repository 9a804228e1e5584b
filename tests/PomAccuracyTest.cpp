// POM's hit point against the exact intersection of the bilinear surface, per pixel, at several
// view angles. The shader writes its final texcoords and depth fraction to a float attachment;
// the CPU traces the same pixel's ray through HeightFieldTracer in double precision.

#include "support/Fields.h"
#include "support/References.h"
#include "support/Fixtures.h"

#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <glm/mat4x4.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace hfx::test {
namespace {

constexpr int kField = 64;
constexpr int kImage = 192;
constexpr float kDepthScale = 0.1f; // texture widths, as the comparison issue measures

struct Measured {
    ErrorStats texels;    ///< |uv_gpu - uv_exact| * field size
    ErrorStats depth;     ///< |depth fraction_gpu - exact|
    size_t pixels = 0;    ///< pixels covered by the plane
    double fetches = 0;   ///< mean height fetches per pixel
};

Measured renderAndCompare(const std::vector<float>& heights, double angle, const char* tag) {
    SurfaceTextures textures({.width = kField, .height = kField, .mipmaps = false, .normalDepth = kDepthScale});
    textures.uploadTexels(sobelReference(heights, kField, kDepthScale).data());
    const Mesh plane(makePlane({.size = 2.0f}));
    PlaneView view{.planeSize = 2.0f, .camera = cameraAtAngle(angle, 8.0f, 1.0f)};
    RenderTarget target(kImage, kImage, true);
    target.bind();
    target.clear();
    SurfaceRenderer renderer;
    const SurfaceMaterial material{.depthScale = kDepthScale,
                                   .minSamples = 8,
                                   .maxSamples = 50,
                                   .lodThreshold = 100.0f,
                                   .shadows = false};
    renderer.draw(plane, glm::mat4(1.0f), textures, material, view.camera, {},
                  {.technique = Technique::ParallaxOcclusion, .traceOutput = true});
    const std::vector<glm::vec4> trace = target.readTrace();

    const HeightFieldTracer exact(heights, kField, kField, EdgeMode::Wrap);
    std::vector<double> texelErrors, depthErrors;
    double fetches = 0;
    Measured m;
    for (int y = 0; y < kImage; ++y)
        for (int x = 0; x < kImage; ++x) {
            const glm::vec4 t = trace[size_t(y) * kImage + x];
            glm::dvec2 uv0;
            glm::dvec3 toEye;
            const bool onPlane = view.pixelRay(x, y, kImage, kImage, uv0, toEye);
            if (t.w == 0.0f) continue; // not drawn
            // Pixels whose centre lies within half a pixel of the plane's edge may be drawn by
            // GL and missed by the CPU ray, or the other way round.
            if (!onPlane) continue;
            ++m.pixels;
            const auto hit = exact.traceView(uv0, toEye, kDepthScale);
            EXPECT_TRUE(hit.has_value()) << "ray of pixel " << x << "," << y << " found no surface";
            if (!hit) continue;
            texelErrors.push_back(glm::length(glm::dvec2(t.x, t.y) - hit->uv) * kField);
            depthErrors.push_back(std::abs(double(t.z) - hit->t));
            fetches += std::floor(t.w); // the integer part counts fetches (see surface.frag)
        }
    m.texels = statistics(texelErrors);
    m.depth = statistics(depthErrors);
    m.fetches = m.pixels ? fetches / double(m.pixels) : 0.0;
    std::printf("[%s %4.0f deg] %zu px: texel error mean %.3f p95 %.3f max %.2f | depth mean %.4f "
                "p95 %.4f | fetches %.1f\n",
                tag, angle, m.pixels, m.texels.mean, m.texels.p95, m.texels.max, m.depth.mean,
                m.depth.p95, m.fetches);
    if (::testing::Test::HasFailure() || std::getenv("HFX_TEST_WRITE_IMAGES"))
        writeImage(outputPath(std::string("pom_accuracy_") + tag + ".png"), target.readColor());
    return m;
}

struct Bound {
    double angle, mean, p95;
};

class PomAccuracy : public GlTest {};

TEST_F(PomAccuracy, SmoothFieldMatchesExactIntersection) {
    const auto heights = sumOfSines(kField, {{0.25, 2, 1, 0.3}, {0.15, -1, 3, 1.1}, {0.08, 5, 4, 2.0}});
    // Bounds with 2-4x headroom over what llvmpipe gives (the printed figures: at 75 degrees a
    // mean of 0.011 and p95 of 0.025 texel); a wrong parallax direction or scale, or a hit at the
    // nearest sample instead of the segment intersection, moves these by tenths to whole texels.
    for (const Bound b : {Bound{0, 0.005, 0.01}, Bound{30, 0.01, 0.02}, Bound{60, 0.02, 0.04},
                          Bound{75, 0.05, 0.1}}) {
        const Measured m = renderAndCompare(heights, b.angle, "sines");
        ASSERT_GT(m.pixels, size_t(kImage * kImage / 10)) << "plane barely visible at " << b.angle;
        EXPECT_LT(m.texels.mean, b.mean) << "at " << b.angle << " degrees";
        EXPECT_LT(m.texels.p95, b.p95) << "at " << b.angle << " degrees";
        // Depth fraction of the hit (what gl_FragDepth is made from): measured p95 <= 0.0011.
        EXPECT_LT(m.depth.p95, 0.004) << "at " << b.angle << " degrees";
    }
}

TEST_F(PomAccuracy, SharpFieldMostlyMatchesExactIntersection) {
    const auto heights = blocks(kField, 4);
    // Thin mortar lines between samples can be stepped over at grazing angles: a few pixels
    // land whole texels off, which the mean feels and the 95th percentile does not.
    for (const Bound b : {Bound{0, 0.01, 0.02}, Bound{45, 0.1, 0.1}, Bound{75, 0.2, 0.5}}) {
        const Measured m = renderAndCompare(heights, b.angle, "blocks");
        EXPECT_LT(m.texels.mean, b.mean) << "at " << b.angle << " degrees";
        EXPECT_LT(m.texels.p95, b.p95) << "at " << b.angle << " degrees";
    }
}

TEST_F(PomAccuracy, MoreSamplesAtGrazingAngles) {
    const auto heights = sumOfSines(kField, {{0.3, 1, 2, 0.0}});
    const Measured headOn = renderAndCompare(heights, 0, "samples");
    const Measured grazing = renderAndCompare(heights, 75, "samples");
    // Looking straight down the shader takes minSamples steps (plus the entry fetch at most);
    // at 75 degrees cos = 0.26, so about 8 + 0.74 * 42 = 39 steps if it runs to the bottom.
    EXPECT_LE(headOn.fetches, 9.5);
    EXPECT_GT(grazing.fetches, headOn.fetches * 1.5);
}

} // namespace
} // namespace hfx::test
