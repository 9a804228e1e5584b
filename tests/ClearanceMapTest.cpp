// The clearance map (compute/ClearanceMap.h) against a plain double-precision reference of the
// same sweep, against the truth it promises (no light ray from the cell, sampled finely, meets
// its penumbra's cone edge past the map's climb) and against fields whose answer is known.

#include "support/Fields.h"
#include "support/Fixtures.h"
#include "support/References.h"

#include "hfx/compute/ClearanceMap.h"
#include "hfx/core/Error.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace hfx::test {
namespace {

class Clearance : public ClTest {
protected:
    std::vector<float> build(const std::vector<float>& heights, int n, EdgeMode edges, const ClearanceLight& light) {
        cl::Buffer input(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, heights.size() * sizeof(float),
                         const_cast<float*>(heights.data()));
        BoundsPyramid pyramid(cl(), n, n, edges);
        ClearanceMap map(cl(), n, n, edges);
        pyramid.build(input);
        map.build(input, pyramid, light);
        std::vector<float> out(heights.size());
        cl().queue().enqueueReadBuffer(map.buffer(), CL_TRUE, 0, out.size() * sizeof(float), out.data());
        return out;
    }
};

/// Lights of several directions (axis-aligned, diagonal, steep, grazing), each sign.
std::vector<ClearanceLight> someLights(int n) {
    std::vector<ClearanceLight> lights;
    const float texel = 1.0f / float(n);
    for (const glm::vec2 texelsPerClimb : {glm::vec2(12.0f, 0.0f), glm::vec2(-7.0f, 5.0f), glm::vec2(0.4f, -0.3f),
                                           glm::vec2(-3.0f, -40.0f)})
        lights.push_back(ClearanceLight::of(texelsPerClimb * texel, 2.0f));
    lights.push_back(ClearanceLight::of(glm::vec2(9.0f, 9.0f) * texel, 8.0f)); // a narrow penumbra
    return lights;
}

TEST_F(Clearance, MatchesTheDoubleReference) {
    constexpr int N = 64;
    const auto heights = sumOfSines(N, {{0.35, 2, 1, 0.0}, {0.15, -3, 4, 0.7}, {0.05, 7, -5, 0.2}});
    for (const EdgeMode edges : {EdgeMode::Wrap, EdgeMode::Clamp})
        for (const ClearanceLight& light : someLights(N)) {
            const std::vector<float> map = build(heights, N, edges, light);
            const std::vector<double> ref = clearanceReference(heights, N, edges, light);
            // float against double: a step's comparison may round the other way where the cone
            // edge grazes a corner, so a cell may end one step off; no more, and rarely.
            const double step = 1.0 / (std::max(std::abs(light.uvPerClimb.x), std::abs(light.uvPerClimb.y)) * N);
            int off = 0, zero = 0;
            for (size_t c = 0; c < map.size(); ++c) {
                ASSERT_NEAR(map[c], ref[c], step * 1.001 + 1e-5) << "cell " << c << ", " << edgeModeName(edges);
                off += std::abs(map[c] - ref[c]) > 1e-4 * (1.0 + ref[c]);
                zero += map[c] == 0.0f;
            }
            EXPECT_LE(off, int(map.size()) / 200) << edgeModeName(edges);
            std::printf("[clearance] %s light (%.3f, %.3f) penumbra %.3f: %d of %zu cells off a step, %d zero\n",
                        edgeModeName(edges), light.uvPerClimb.x, light.uvPerClimb.y, light.penumbra, off, map.size(),
                        zero);
        }
}

TEST_F(Clearance, NoLightRayFromACellMeetsItsConePastTheMap) {
    // The promise, sampled: from 3x3 points in every cell, on the surface, along the map's
    // direction and the corners of its slack, march each light ray in steps of 1/50 texel. Past
    // the first texel (the walk counts the penumbra from there) the surface must stay below the
    // cone edge h0 + d (1 - penumbra); within it, below the ray itself (hard shadow only) beyond
    // the shader's epsilon. The largest climb where either fails is where the walk must go on.
    constexpr int N = 32;
    const auto heights = sumOfSines(N, {{0.4, 1, 2, 0.3}, {0.2, 3, -2, 0.1}, {0.08, -5, 6, 0.9}});
    auto bilinear = [&](glm::dvec2 p) { // texel coordinates, wrapping
        const glm::dvec2 f = glm::floor(p), w = p - f;
        auto at = [&](int x, int y) { return double(heights[size_t(y & (N - 1)) * N + (x & (N - 1))]); };
        const int x = int(f.x), y = int(f.y);
        return glm::mix(glm::mix(at(x, y), at(x + 1, y), w.x), glm::mix(at(x, y + 1), at(x + 1, y + 1), w.x), w.y);
    };
    int rays = 0, reaching = 0;
    for (const ClearanceLight& light : someLights(N)) {
        const std::vector<float> map = build(heights, N, EdgeMode::Wrap, light);
        const glm::dvec2 g = glm::dvec2(light.uvPerClimb) * double(N);
        const double slack = double(light.slack) * N;
        const double texel = 1.0 / std::max(std::max(std::abs(g.x), std::abs(g.y)), 1e-9);
        for (int j = 0; j < N; ++j)
            for (int i = 0; i < N; ++i)
                for (int s = 0; s < 9; ++s) {
                    const glm::dvec2 p(i + 0.5 * (s % 3), j + 0.5 * (s / 3));
                    const double h0 = bilinear(p);
                    const glm::dvec2 dir = g + slack * glm::dvec2(s % 2 ? 1 : -1, s / 2 % 2 ? 1 : -1);
                    const double dStep = texel / 50.0;
                    double needed = 0.0;
                    for (double d = dStep; d <= 1.0 - h0; d += dStep) {
                        const double surface = bilinear(p + dir * d);
                        const bool dark = d <= texel ? surface > h0 + d + 1e-4
                                                     : surface >= h0 + d * (1.0 - light.penumbra);
                        if (dark) needed = d;
                    }
                    ++rays;
                    reaching += needed > 0.0;
                    ASSERT_GE(map[size_t(j) * N + i], needed)
                        << "cell (" << i << ", " << j << ") point " << s << " light (" << light.uvPerClimb.x << ", "
                        << light.uvPerClimb.y << ")";
                }
    }
    // The field must give the rays something to reach (else the check above cannot fail).
    EXPECT_GT(reaching, rays / 10);
}

TEST_F(Clearance, AFlatFieldIsClearEverywhereAndASpikeShadowsOnlyItsUpwindCells) {
    constexpr int N = 32;
    const ClearanceLight light = ClearanceLight::of(glm::vec2(8.0f / N, 0.0f), 2.0f); // +u, 8 texels per climb
    std::vector<float> flat(size_t(N) * N, 0.3f);
    for (float c : build(flat, N, EdgeMode::Clamp, light)) ASSERT_EQ(c, 0.0f);
    // One sample at 1 on the floor at 0, at (16, 16): cells it touches span samples 15..16.
    std::vector<float> spike(size_t(N) * N, 0.0f);
    spike[16 * N + 16] = 1.0f;
    const std::vector<float> map = build(spike, N, EdgeMode::Clamp, light);
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) {
            const float c = map[size_t(j) * N + i];
            const bool upwind = (j == 15 || j == 16) && i < 15;
            // A floor cell's rays climb 1 (from 0 to the top) over 8 texels: cells up to 8
            // texels before the spike's must walk at least to its distance, those further or off
            // its rows not at all (their boxes widen by the margins, not by a row).
            if (upwind && i >= 15 - 7) {
                EXPECT_GE(c, (15 - i - 1) / 8.0f) << i << ", " << j;
            }
            if (j < 14 || j > 17 || i < 15 - 10) {
                EXPECT_EQ(c, 0.0f) << i << ", " << j;
            }
            if (i > 16) {
                EXPECT_EQ(c, 0.0f) << i << ", " << j; // downwind
            }
        }
}

TEST_F(Clearance, RefusesBadSizesAndLights) {
    EXPECT_THROW(ClearanceMap(cl(), 48, 64, EdgeMode::Wrap), Error);
    ClearanceMap map(cl(), 16, 16, EdgeMode::Wrap);
    BoundsPyramid pyramid(cl(), 16, 16, EdgeMode::Wrap), other(cl(), 32, 32, EdgeMode::Wrap);
    cl::Buffer heights(cl().context(), CL_MEM_READ_WRITE, 16 * 16 * sizeof(float));
    EXPECT_THROW(map.build(heights, pyramid, {.uvPerClimb = {NAN, 0.0f}}), Error);
    EXPECT_THROW(map.build(heights, pyramid, {.uvPerClimb = {0.1f, 0.0f}, .penumbra = 1.0f}), Error);
    try {
        map.build(heights, other, ClearanceLight::of({0.1f, 0.0f}, 2.0f));
        FAIL() << "a pyramid of another size was taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("32x32"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace hfx::test
