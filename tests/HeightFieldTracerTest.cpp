// The ground-truth tracer against cases with closed-form answers and against brute-force
// marching with bisection.

#include "hfx/core/Error.h"
#include "hfx/core/HeightFieldTracer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hfx {
namespace {

TEST(HeightFieldTracer, FlatFieldHitAtItsHeight) {
    const HeightFieldTracer flat(std::vector<float>(16 * 16, 0.25f), 16, 16, EdgeMode::Wrap);
    // Straight down from the top: reaches h = 0.25 after a depth fraction 0.75.
    auto hit = flat.traceView({0.3, 0.6}, {0, 0, 1}, 0.1);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 0.75, 1e-12);
    EXPECT_NEAR(hit->uv.x, 0.3, 1e-12);
    // At 45 degrees the uv moves by depthScale per unit of depth fraction.
    hit = flat.traceView({0.3, 0.6}, {1, 0, 1}, 0.1);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->uv.x, 0.3 - 0.075, 1e-12);
}

TEST(HeightFieldTracer, RampHitMatchesClosedForm) {
    // h = x / (N - 1) along x between the first and last texel centres (clamped edges).
    constexpr int N = 9;
    std::vector<float> h(N * N);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) h[y * N + x] = float(x) / (N - 1);
    const HeightFieldTracer ramp(h, N, N, EdgeMode::Clamp);
    EXPECT_NEAR(ramp.heightAt({0.5, 0.5}), 0.5, 1e-7);
    // Ray from (u0, top) going -u: u(t) = u0 - a t, z = 1 - t, surface h(u) = (u N - 0.5) / 8.
    const double u0 = 0.8, a = 0.2;
    const auto hit = ramp.intersect({u0, 0.5, 1.0}, {-a, 0.0, -1.0}, 1.0);
    ASSERT_TRUE(hit);
    // (u0 - a t) N - 0.5 = 8 (1 - t)  ->  t = (8 + 0.5 - u0 N) / (8 - a N)
    const double t = (8 + 0.5 - u0 * N) / (8 - a * N);
    EXPECT_NEAR(hit->t, t, 1e-12);
}

TEST(HeightFieldTracer, AgreesWithFineMarching) {
    constexpr int N = 16;
    std::mt19937 random(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> h(N * N);
    for (float& v : h) v = unit(random);
    const HeightFieldTracer tracer(h, N, N, EdgeMode::Wrap);
    for (int i = 0; i < 200; ++i) {
        const glm::dvec2 uv0(unit(random), unit(random));
        const glm::dvec3 toEye(2 * unit(random) - 1, 2 * unit(random) - 1, 0.2 + unit(random));
        const double depth = 0.1;
        const auto hit = tracer.traceView(uv0, toEye, depth);
        ASSERT_TRUE(hit);
        // March in steps far below a cell, then bisect the first sign change.
        const glm::dvec2 d = -glm::dvec2(toEye) / toEye.z * depth;
        auto f = [&](double t) { return tracer.heightAt(uv0 + t * d) - (1 - t); };
        double lo = 0, hi = -1;
        for (int s = 1; s <= 20000; ++s) {
            const double t = s / 20000.0;
            if (f(t) >= 0) {
                hi = t;
                break;
            }
            lo = t;
        }
        ASSERT_GT(hi, 0);
        for (int b = 0; b < 60; ++b) ((f(0.5 * (lo + hi)) >= 0) ? hi : lo) = 0.5 * (lo + hi);
        EXPECT_NEAR(hit->t, hi, 1e-9) << "ray " << i;
    }
}

TEST(HeightFieldTracer, WrapUTilesAlongUAndClampsAlongV) {
    constexpr int N = 8;
    std::vector<float> h(N * N);
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) h[j * N + i] = float(i) / N + float(j) / (N * N);
    const HeightFieldTracer grid(h, N, N, EdgeMode::WrapU);
    // Half a texel beyond u = 0 lies between the last and the first column.
    EXPECT_NEAR(grid.heightAt({0.0, 0.5 / N}), 0.5 * (h[N - 1] + h[0]), 1e-12);
    // Below v = 0 the first row is held, above v = 1 the last.
    EXPECT_NEAR(grid.heightAt({2.5 / N, -0.3}), h[2], 1e-12);
    EXPECT_NEAR(grid.heightAt({2.5 / N, 1.3}), h[(N - 1) * N + 2], 1e-12);
}

TEST(HeightFieldTracer, RejectsMismatchedSize) {
    EXPECT_THROW(HeightFieldTracer(std::vector<float>(10), 4, 4, EdgeMode::Wrap), Error);
}

} // namespace
} // namespace hfx
