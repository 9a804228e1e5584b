// The max-height pyramid against a CPU reference, and its promise: no bilinearly interpolated
// height inside a texel's footprint exceeds the texel.

#include "support/Fixtures.h"
#include "support/References.h"

#include "hfx/compute/MaxPyramid.h"
#include "hfx/core/Error.h"
#include "hfx/core/HeightFieldTracer.h"

#include <algorithm>
#include <random>

namespace hfx::test {
namespace {

class Pyramid : public ClTest {
protected:
    std::vector<float> build(const std::vector<float>& heights, MaxPyramid& pyramid) {
        cl::Buffer input(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                         heights.size() * sizeof(float), const_cast<float*>(heights.data()));
        pyramid.build(input);
        std::vector<float> out(pyramid.totalFloats());
        cl().queue().enqueueReadBuffer(pyramid.buffer(), CL_TRUE, 0, out.size() * sizeof(float),
                                       out.data());
        return out;
    }
};

std::vector<float> randomField(int w, int h, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> f(size_t(w) * h);
    for (float& v : f)
        v = unit(random);
    return f;
}

TEST_F(Pyramid, MatchesCpuReferenceAtEveryLevel) {
    for (const EdgeMode edges : kEdgeModes) {
        const int W = 37, H = 20; // odd sizes: lone last rows and columns
        const auto heights = randomField(W, H, 4);
        MaxPyramid pyramid(cl(), W, H, edges);
        const auto out = build(heights, pyramid);
        const auto& levels = pyramid.levels();
        ASSERT_EQ(levels.back().width, 1);
        ASSERT_EQ(levels.back().height, 1);
        auto sample = [&](int x, int y) {
            x = wrapsU(edges) ? x % W : std::min(x, W - 1);
            y = wrapsV(edges) ? y % H : std::min(y, H - 1);
            return heights[size_t(y) * W + x];
        };
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                ASSERT_EQ(out[size_t(y) * W + x],
                          std::max({sample(x, y), sample(x + 1, y), sample(x, y + 1),
                                    sample(x + 1, y + 1)}));
        // Each coarser texel is the max of the level-0 cells in its footprint.
        for (size_t k = 1; k < levels.size(); ++k)
            for (int y = 0; y < levels[k].height; ++y)
                for (int x = 0; x < levels[k].width; ++x) {
                    float expected = 0;
                    const int span = 1 << k;
                    for (int cy = y * span; cy < std::min(H, (y + 1) * span); ++cy)
                        for (int cx = x * span; cx < std::min(W, (x + 1) * span); ++cx)
                            expected = std::max(expected, out[size_t(cy) * W + cx]);
                    ASSERT_EQ(out[levels[k].offset + size_t(y) * levels[k].width + x], expected)
                        << "level " << k << " texel " << x << "," << y;
                }
        if (edges == EdgeMode::Wrap) {
            EXPECT_EQ(out, pyramidReference(heights, W, H));
        }
        // The top bounds the whole field.
        EXPECT_EQ(out.back(), *std::max_element(heights.begin(), heights.end()));
    }
}

// In every edge mode, including the seam of a longitude-latitude map (wrap-u), where a pyramid
// built as if clamped would miss the cell between the last column and the first.
TEST_F(Pyramid, ConservativeForTheBilinearSurface) {
    const int N = 64;
    const auto heights = randomField(N, N, 8);
    for (const EdgeMode edges : kEdgeModes) {
        MaxPyramid pyramid(cl(), N, N, edges);
        const auto out = build(heights, pyramid);
        const HeightFieldTracer surface(heights, N, N, edges);
        std::mt19937 random(2);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        for (int i = 0; i < 20000; ++i) {
            // A point in texel space x in [0, N): cell floor(x), texcoord (x + 0.5) / N.
            const double x = unit(random) * N, y = unit(random) * N;
            const double h = surface.heightAt({(x + 0.5) / N, (y + 0.5) / N});
            for (size_t k = 0; k < pyramid.levels().size(); ++k) {
                const PyramidLevel& l = pyramid.levels()[k];
                const int tx = int(x) >> k, ty = int(y) >> k;
                ASSERT_LE(h, out[l.offset + size_t(ty) * l.width + tx] + 1e-6)
                    << "level " << k << ", " << edgeModeName(edges);
            }
        }
    }
}

TEST_F(Pyramid, RefusesBadSizes) {
    EXPECT_THROW(MaxPyramid(cl(), 0, 4, EdgeMode::Wrap), Error);
    MaxPyramid pyramid(cl(), 64, 64, EdgeMode::Wrap);
    cl::Buffer small(cl().context(), CL_MEM_READ_WRITE, 16);
    EXPECT_THROW(pyramid.build(small), Error);
}

} // namespace
} // namespace hfx::test
