// Sobel normals against analytic truth: for h = A sin(kx x + ky y), Sobel/8 gives exactly
// A cos(.) sin(kx) (1 + cos ky) / 2 (DESIGN.md), and approaches the true derivative A kx cos(.)
// as the wavelength grows.

#include "support/Fixtures.h"

#include "hfx/compute/SobelNormals.h"
#include "hfx/compute/shared/SobelMath.h"
#include "hfx/core/Error.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace hfx::test {
namespace {

struct Wave {
    double amplitude, m, n, phase;
};

class Sobel : public ClTest {
protected:
    std::vector<cl_float4> run(const std::vector<float>& heights, const SobelConfig& config) {
        cl::Buffer input(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                         heights.size() * sizeof(float), const_cast<float*>(heights.data()));
        SobelNormals sobel(cl(), config);
        sobel.run(input);
        std::vector<cl_float4> out(heights.size());
        cl().queue().enqueueReadBuffer(sobel.output(), CL_TRUE, 0, out.size() * sizeof(cl_float4),
                                       out.data());
        return out;
    }
};

glm::dvec3 normalFromSlopes(double dhdx, double dhdy, double scale) {
    return glm::normalize(glm::dvec3(-dhdx * scale, -dhdy * scale, 1.0));
}

TEST_F(Sobel, SumOfSinesMatchesAnalyticNormals) {
    constexpr int N = 128;
    constexpr float depthScale = 0.05f;
    const std::vector<Wave> waves = {{0.2, 3, 1, 0.4}, {0.1, -2, 4, 1.3}};
    std::vector<float> heights(N * N);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            double h = 0.5;
            for (const Wave& w : waves)
                h += w.amplitude * std::sin(2 * std::numbers::pi * (w.m * x + w.n * y) / N + w.phase);
            heights[y * N + x] = float(h);
        }
    const auto out = run(heights, {.width = N, .height = N, .normalDepth = depthScale});

    double maxDiscreteError = 0, maxAnalyticAngle = 0;
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            double sobelX = 0, sobelY = 0, trueX = 0, trueY = 0;
            for (const Wave& w : waves) {
                const double kx = 2 * std::numbers::pi * w.m / N, ky = 2 * std::numbers::pi * w.n / N;
                const double c = w.amplitude * std::cos(kx * x + ky * y + w.phase);
                sobelX += c * std::sin(kx) * (1 + std::cos(ky)) / 2;
                sobelY += c * std::sin(ky) * (1 + std::cos(kx)) / 2;
                trueX += c * kx;
                trueY += c * ky;
            }
            const cl_float4 o = out[y * N + x];
            const glm::dvec3 gpu(o.s[0], o.s[1], o.s[2]);
            EXPECT_NEAR(o.s[3], heights[y * N + x], 0.0f) << "height not passed through";
            const glm::dvec3 discrete = normalFromSlopes(sobelX, sobelY, depthScale * N);
            const glm::dvec3 analytic = normalFromSlopes(trueX, trueY, depthScale * N);
            maxDiscreteError = std::max(maxDiscreteError, glm::length(gpu - discrete));
            maxAnalyticAngle = std::max(
                maxAnalyticAngle, std::acos(std::clamp(glm::dot(gpu, analytic), -1.0, 1.0)));
        }
    // Float rounding of 9 taps and a square root.
    EXPECT_LT(maxDiscreteError, 2e-5);
    // Truncation error of the stencil: slope error about 5k^2/12 relative, k = 2 pi 4.5 / 128
    // for the steepest term, times slopes near 0.4 here: about 0.2 degrees.
    EXPECT_LT(maxAnalyticAngle * 180 / std::numbers::pi, 0.35);
}

TEST_F(Sobel, ClampedEdgesOfARampKeepTheInteriorExact) {
    constexpr int W = 48, H = 32;
    std::vector<float> heights(W * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) heights[y * W + x] = 0.2f + 0.01f * x + 0.005f * y;
    const float depthScale = 0.1f;
    const auto out = run(heights, {.width = W, .height = H, .edges = EdgeMode::Clamp, .normalDepth = depthScale});
    const glm::dvec3 expected = glm::normalize(glm::dvec3(-0.01 * depthScale * W, -0.005 * depthScale * H, 1));
    for (int y = 1; y < H - 1; ++y)
        for (int x = 1; x < W - 1; ++x) {
            const cl_float4 o = out[y * W + x];
            ASSERT_NEAR(o.s[0], expected.x, 1e-5) << x << "," << y;
            ASSERT_NEAR(o.s[1], expected.y, 1e-5) << x << "," << y;
        }
    // At a clamped edge the one-sided difference halves the x slope; wrapping would flip it.
    const cl_float4 edge = out[10 * W + 0];
    EXPECT_NEAR(edge.s[0] / edge.s[2], -0.005 * depthScale * W, 1e-5);
}

TEST_F(Sobel, KernelMatchesSharedCpuMath) {
    // Widths that are a multiple of 4 run the four-texels-per-item kernel, others the one-texel
    // kernel: both, in every edge mode (wrapped, clamped, and the longitude-latitude grid's
    // wrapped u with clamped v), against the same host math.
    struct Case {
        int W, H;
        EdgeMode edges;
    };
    for (const Case k : {Case{32, 32, EdgeMode::Wrap}, Case{30, 17, EdgeMode::Wrap}, Case{36, 12, EdgeMode::Clamp},
                         Case{22, 9, EdgeMode::Clamp}, Case{40, 10, EdgeMode::WrapU}, Case{26, 11, EdgeMode::WrapU}}) {
        const int W = k.W, H = k.H;
        std::vector<float> heights(W * H);
        for (int i = 0; i < W * H; ++i) heights[i] = float((i * 7919) % 101) / 100.0f; // rough field
        const auto out = run(heights, {.width = W, .height = H, .edges = k.edges, .normalDepth = 0.03f});
        auto at = [&](int x, int y) {
            x = wrapsU(k.edges) ? (x + W) % W : std::clamp(x, 0, W - 1);
            y = wrapsV(k.edges) ? (y + H) % H : std::clamp(y, 0, H - 1);
            return heights[y * W + x];
        };
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                float expected[3];
                hfx_normal_from_slopes(
                    hfx_sobel_dx(at(x - 1, y - 1), at(x + 1, y - 1), at(x - 1, y), at(x + 1, y),
                                 at(x - 1, y + 1), at(x + 1, y + 1)),
                    hfx_sobel_dy(at(x - 1, y - 1), at(x, y - 1), at(x + 1, y - 1), at(x - 1, y + 1),
                                 at(x, y + 1), at(x + 1, y + 1)),
                    0.03f * W, 0.03f * H, expected);
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(out[y * W + x].s[c], expected[c], 1e-6) << W << "x" << H << " at " << x << "," << y;
                ASSERT_EQ(out[y * W + x].s[3], heights[y * W + x]) << W << "x" << H;
            }
    }
}

TEST_F(Sobel, RejectsBadConfigurationAndSmallBuffers) {
    EXPECT_THROW(SobelNormals(cl(), {.width = 0, .height = 16}), Error);
    EXPECT_THROW(SobelNormals(cl(), {.normalDepth = -1.0f}), Error);
    EXPECT_THROW(SobelNormals(cl(), {.normalDepth = 0.0f}), Error);
    SobelNormals sobel(cl(), {.width = 64, .height = 64});
    cl::Buffer small(cl().context(), CL_MEM_READ_WRITE, 16 * 16 * sizeof(float));
    try {
        sobel.run(small);
        FAIL() << "a too small buffer was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("64x64"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace hfx::test
