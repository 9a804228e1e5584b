// The CPU ocean query against the device: the same sea, choppy, in cascades, at a time the query
// was never stepped to and in the middle of a wind change. On each cascade's grid points it is
// the device's Eulerian height, and anywhere the sum of the cascades is the surface the renderer
// draws (bilinear between texels), to float rounding: far inside 1 cm on a sea of 2 m waves.

#include "support/Fixtures.h"

#include "hfx/compute/OceanQuery.h"
#include "hfx/core/Error.h"
#include "hfx/core/Random.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hfx::test {
namespace {

class OceanQueryTest : public ClTest {
protected:
    std::vector<float> meters(const OceanField& o, int c) {
        std::vector<float> out(size_t(o.config().size) * o.config().size);
        cl().queue().enqueueReadBuffer(o.cascade(c).meters, CL_TRUE, 0, out.size() * sizeof(float),
                                       out.data());
        return out;
    }
    /// What the renderer draws at p (metres): each cascade's heights sampled bilinearly, in double.
    double rendered(const OceanField& o, const std::vector<std::vector<float>>& grids,
                    glm::vec2 p) {
        const int N = o.config().size;
        double sum = 0;
        for (int c = 0; c < o.cascadeCount(); ++c) {
            const double L = o.cascade(c).patchMeters;
            auto texel = [&](double m) { return (m - L * std::floor(m / L)) / L * N; };
            const double x = texel(p.x), y = texel(p.y);
            const int i = int(std::floor(x)), j = int(std::floor(y));
            const double ax = x - i, ay = y - j;
            auto at = [&](int a, int b) {
                return double(grids[size_t(c)][size_t(((b % N + N) % N) * N + (a % N + N) % N)]);
            };
            sum += (1 - ay) * ((1 - ax) * at(i, j) + ax * at(i + 1, j)) +
                   ay * ((1 - ax) * at(i, j + 1) + ax * at(i + 1, j + 1));
        }
        return sum;
    }
    std::vector<glm::vec2> scattered(const OceanField& o, int count) {
        SplitMix64 random(7);
        const double L = o.config().patchMeters;
        std::vector<glm::vec2> points;
        for (int i = 0; i < count; ++i)
            points.emplace_back(float(random.uniform(-2.0 * L, 3.0 * L)),
                                float(random.uniform(-2.0 * L, 3.0 * L)));
        points.emplace_back(8000.0f, -5000.0f); // far out: reduced to each patch in double
        return points;
    }
    /// Max |query - device| on cascade c's grid points, and over scattered points the max
    /// |query - rendered|.
    void compare(const OceanField& o, OceanQuery& q, double t, double& onGrid, double& anywhere) {
        std::vector<std::vector<float>> grids;
        for (int c = 0; c < o.cascadeCount(); ++c)
            grids.push_back(meters(o, c));
        onGrid = 0;
        const int N = o.config().size;
        for (int c = 0; c < o.cascadeCount(); ++c) {
            const float texel = o.cascade(c).patchMeters / float(N);
            std::vector<glm::vec2> points;
            for (int j = 0; j < N; j += 3)
                for (int i = 0; i < N; i += 5)
                    points.emplace_back(float(i) * texel, float(j) * texel);
            const std::vector<float> h = q.cascadeHeights(c, points, t);
            for (size_t k = 0; k < points.size(); ++k) {
                const int i = int(std::lround(points[k].x / texel)),
                          j = int(std::lround(points[k].y / texel));
                onGrid =
                    std::max(onGrid, double(std::abs(h[k] - grids[size_t(c)][size_t(j * N + i)])));
            }
        }
        const std::vector<glm::vec2> points = scattered(o, 1000);
        const std::vector<float> h = q.heights(points, t);
        anywhere = 0;
        for (size_t k = 0; k < points.size(); ++k)
            anywhere = std::max(anywhere, std::abs(h[k] - rendered(o, grids, points[k])));
    }
};

OceanConfig twoMetreSea() {
    OceanConfig config{.size = 256, .cascades = 3, .choppiness = 1.0f};
    config.sea.wind.windSpeed = 10.0f; // fully developed: Hs = 0.21 U^2 / g = 2.1 m
    return config;
}

TEST_F(OceanQueryTest, HeightsAreTheDevicesWithinACentimetreOnTwoMetreWaves) {
    OceanField ocean(cl(), twoMetreSea());
    const double hs = 4.0 * ocean.sigmaMeters();
    ASSERT_GT(hs, 1.5);
    ASSERT_LT(hs, 3.0);
    OceanQuery query(ocean); // made at t = 0, asked for a time the field jumps to
    ocean.setTime(37.25);
    double onGrid, anywhere;
    compare(ocean, query, 37.25, onGrid, anywhere);
    std::printf("Hs %.2f m: query - device on the grids %.2e m, query - rendered surface %.2e m\n",
                hs, onGrid, anywhere);
    EXPECT_LT(onGrid, 1e-4);
    EXPECT_LT(anywhere, 1e-4);
    // Nothing is cached wrongly: another time, then the first again.
    ocean.setTime(2.5);
    compare(ocean, query, 2.5, onGrid, anywhere);
    EXPECT_LT(onGrid, 1e-4);
    EXPECT_LT(anywhere, 1e-4);
}

TEST_F(OceanQueryTest, FollowsAWindChangeInProgress) {
    OceanField ocean(cl(), twoMetreSea());
    ocean.setTime(3.0);
    ocean.setWind(14.0f, 1.0f, 8.0);
    for (int i = 0; i < 4; ++i)
        ocean.step(1.0); // half way
    OceanQuery query(ocean);
    double onGrid, anywhere;
    compare(ocean, query, ocean.time(), onGrid, anywhere);
    EXPECT_LT(onGrid, 1e-4);
    EXPECT_LT(anywhere, 1e-4);
    // A query that did not take the new spectra would miss by metres.
    OceanField stale(cl(), twoMetreSea());
    OceanQuery old(stale);
    const std::vector<glm::vec2> points = scattered(ocean, 200);
    const std::vector<float> a = query.heights(points, ocean.time()),
                             b = old.heights(points, ocean.time());
    double differ = 0;
    for (size_t k = 0; k < a.size(); ++k)
        differ = std::max(differ, double(std::abs(a[k] - b[k])));
    EXPECT_GT(differ, 0.5);
    old.update(ocean);
    EXPECT_EQ(old.heights(points, ocean.time()), a);
}

TEST_F(OceanQueryTest, WithoutChoppinessItIsTheHeightField) {
    OceanConfig config = twoMetreSea();
    config.choppiness = 0.0f;
    config.cascades = 1;
    OceanField ocean(cl(), config);
    OceanQuery query(ocean);
    double onGrid, anywhere;
    compare(ocean, query, 0.0, onGrid, anywhere);
    EXPECT_LT(onGrid, 1e-4);
    EXPECT_LT(anywhere, 1e-4);
}

TEST_F(OceanQueryTest, BadInputIsRefusedByName) {
    OceanField ocean(cl(), {.size = 64, .cascades = 1});
    OceanQuery query(ocean);
    const std::vector<glm::vec2> points{{1.0f, 2.0f},
                                        {std::numeric_limits<float>::quiet_NaN(), 0.0f}};
    EXPECT_EQ(messageOf([&] { query.heights(points, 0.0); }), "OceanQuery: point 1 is not finite (nan, 0)");
    EXPECT_NE(
        messageOf([&] { query.heights(std::span(points).first(1), std::nan("")); }).find("time"),
        std::string::npos);
    std::vector<float> out(3);
    EXPECT_NE(messageOf([&] { query.heights(points, 0.0, out); }).find("3 outputs"),
              std::string::npos);
    EXPECT_THROW(query.cascadeHeights(1, points, 0.0), Error);
    OceanField other(cl(), {.size = 32, .cascades = 1});
    EXPECT_NE(messageOf([&] { query.update(other); }).find("32"), std::string::npos);
    EXPECT_EQ(query.heights(std::span(points).first(1), 0.0).size(), 1u)
        << "a refused update changed nothing";
}

} // namespace
} // namespace hfx::test
