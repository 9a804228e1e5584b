// The height-bounds pyramid against a CPU reference, and its promise: every bilinearly
// interpolated height inside a texel's footprint lies between the texel's min and max.

#include "support/Fixtures.h"
#include "support/References.h"

#include "hfx/compute/BoundsPyramid.h"
#include "hfx/core/Error.h"
#include "hfx/core/HeightFieldTracer.h"

#include <algorithm>
#include <random>

namespace hfx::test {
namespace {

class Pyramid : public ClTest {
protected:
    std::vector<float> build(const std::vector<float>& heights, BoundsPyramid& pyramid) {
        cl::Buffer input(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                         heights.size() * sizeof(float), const_cast<float*>(heights.data()));
        pyramid.build(input);
        std::vector<float> out(2 * pyramid.totalTexels()); // (max, min) pairs
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
        BoundsPyramid pyramid(cl(), W, H, edges);
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
            for (int x = 0; x < W; ++x) {
                const auto corners = {sample(x, y), sample(x + 1, y), sample(x, y + 1), sample(x + 1, y + 1)};
                ASSERT_EQ(out[2 * (size_t(y) * W + x)], std::max(corners));
                ASSERT_EQ(out[2 * (size_t(y) * W + x) + 1], std::min(corners));
            }
        // Each coarser texel is the max and the min of the level-0 cells in its footprint.
        for (size_t k = 1; k < levels.size(); ++k)
            for (int y = 0; y < levels[k].height; ++y)
                for (int x = 0; x < levels[k].width; ++x) {
                    float hi = 0, lo = 1;
                    const int span = 1 << k;
                    for (int cy = y * span; cy < std::min(H, (y + 1) * span); ++cy)
                        for (int cx = x * span; cx < std::min(W, (x + 1) * span); ++cx) {
                            hi = std::max(hi, out[2 * (size_t(cy) * W + cx)]);
                            lo = std::min(lo, out[2 * (size_t(cy) * W + cx) + 1]);
                        }
                    const size_t texel = levels[k].offset + size_t(y) * levels[k].width + x;
                    ASSERT_EQ(out[2 * texel], hi) << "max, level " << k << " texel " << x << "," << y;
                    ASSERT_EQ(out[2 * texel + 1], lo) << "min, level " << k << " texel " << x << "," << y;
                }
        if (edges == EdgeMode::Wrap) {
            EXPECT_EQ(out, pyramidReference(heights, W, H));
        }
        // The top bounds the whole field.
        EXPECT_EQ(out[out.size() - 2], *std::max_element(heights.begin(), heights.end()));
        EXPECT_EQ(out.back(), *std::min_element(heights.begin(), heights.end()));
    }
}

// In every edge mode, including the seam of a longitude-latitude map (wrap-u), where a pyramid
// built as if clamped would miss the cell between the last column and the first.
TEST_F(Pyramid, ConservativeForTheBilinearSurface) {
    const int N = 64;
    const auto heights = randomField(N, N, 8);
    for (const EdgeMode edges : kEdgeModes) {
        BoundsPyramid pyramid(cl(), N, N, edges);
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
                const size_t texel = l.offset + size_t(ty) * l.width + tx;
                ASSERT_LE(h, out[2 * texel] + 1e-6) << "max, level " << k << ", " << edgeModeName(edges);
                ASSERT_GE(h, out[2 * texel + 1] - 1e-6) << "min, level " << k << ", " << edgeModeName(edges);
            }
        }
    }
}

TEST_F(Pyramid, RefusesBadSizes) {
    EXPECT_THROW(BoundsPyramid(cl(), 0, 4, EdgeMode::Wrap), Error);
    BoundsPyramid pyramid(cl(), 64, 64, EdgeMode::Wrap);
    cl::Buffer small(cl().context(), CL_MEM_READ_WRITE, 16);
    EXPECT_THROW(pyramid.build(small), Error);
}

} // namespace
} // namespace hfx::test
