// Decal stamping against its analytic profile, a plain CPU reference (no binning), the [0,1]
// promise under thousands of overlapping stamps, wrapping, healing and refusals.

#include "support/Fixtures.h"
#include "support/References.h"

#include "hfx/compute/DecalMap.h"
#include "hfx/compute/shared/DecalMath.h"
#include "hfx/core/Error.h"

#include <cmath>
#include <random>

namespace hfx::test {
namespace {

class Decals : public ClTest {
protected:
    std::vector<float> read(const cl::Buffer& buffer, size_t count) {
        std::vector<float> out(count);
        cl().queue().enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(float), out.data());
        return out;
    }
};

/// Every stamp over every texel, in batch order: what binning must reproduce.
std::vector<float> reference(const DecalConfig& c, const std::vector<float>& base, std::vector<float> damage,
                             const std::vector<BulletHole>& stamps) {
    const int W = c.width, H = c.height;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            float& d = damage[size_t(y) * W + x];
            for (const BulletHole& s : stamps) {
                float dx = (x + 0.5f) - s.u * W, dy = (y + 0.5f) - s.v * H;
                if (wrapsU(c.edges)) dx -= W * std::rint(dx / W);
                if (wrapsV(c.edges)) dy -= H * std::rint(dy / H);
                const float r = std::sqrt(dx * dx + dy * dy) / (s.radius * W);
                d = hfx_apply_damage(d, hfx_crater_profile(r, s.depth, s.rimHeight, s.rimWidth),
                                     base[size_t(y) * W + x]);
            }
        }
    return damage;
}

TEST_F(Decals, SingleStampMatchesAnalyticProfile) {
    const DecalConfig config{.width = 128, .height = 128, .baseHeight = 0.6f};
    DecalMap map(cl(), config);
    const BulletHole hole{.u = 0.4f, .v = 0.55f, .radius = 0.1f, .depth = 0.4f, .rimHeight = 0.1f, .rimWidth = 0.3f};
    map.addBulletHole(hole);
    map.step(0.01);
    const auto h = read(map.buffer(), 128 * 128);
    double maxError = 0;
    int touched = 0;
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) {
            const double r = std::hypot(x + 0.5 - 0.4 * 128, y + 0.5 - 0.55 * 128) / (0.1 * 128);
            double expected = 0.6;
            if (r < 1) expected -= 0.4 * (1 - r * r);
            const double s = (r - 1) / 0.3;
            if (std::abs(s) < 1) expected += 0.1 * (1 - s * s) * (1 - s * s);
            maxError = std::max(maxError, std::abs(h[y * 128 + x] - expected));
            touched += std::abs(expected - 0.6) > 1e-3;
        }
    EXPECT_LT(maxError, 1e-5);
    EXPECT_GT(touched, 400); // the crater covers pi (1.3 * 12.8)^2 texels, about 870
    // The bottom of the bowl: 0.6 - 0.4 (r is not exactly 0 at any texel centre).
    EXPECT_NEAR(*std::min_element(h.begin(), h.end()), 0.2f, 0.01f);
}

TEST_F(Decals, KernelMatchesUnbinnedReference) {
    for (const EdgeMode edges : kEdgeModes) {
        const DecalConfig config{.width = 100, .height = 72, .edges = edges, .tileSize = 16};
        std::vector<float> base(100 * 72);
        for (size_t i = 0; i < base.size(); ++i) base[i] = 0.5f + 0.4f * std::sin(float(i) * 0.37f);
        DecalMap map(cl(), config, base);
        std::mt19937 random(unsigned(edges) + 1);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::vector<float> damage(base.size(), 0.0f);
        for (int batch = 0; batch < 3; ++batch) {
            std::vector<BulletHole> stamps;
            for (int i = 0; i < 400; ++i)
                stamps.push_back({unit(random), unit(random), 0.005f + 0.08f * unit(random), unit(random),
                                  0.2f * unit(random), 0.1f + unit(random)});
            map.addBulletHoles(stamps);
            map.step(0.1);
            std::vector<float> footprint = damage;
            decalsReference(config, base, footprint, stamps);
            damage = reference(config, base, damage, stamps);
            for (size_t i = 0; i < damage.size(); ++i) ASSERT_NEAR(footprint[i], damage[i], 1e-6) << i;
            const auto gpu = read(map.damage(), damage.size());
            double maxDiff = 0;
            for (size_t i = 0; i < gpu.size(); ++i) maxDiff = std::max(maxDiff, double(std::abs(gpu[i] - damage[i])));
            EXPECT_LT(maxDiff, 1e-6) << "batch " << batch << ", edges " << edgeModeName(edges);
        }
    }
}

TEST_F(Decals, TenThousandOverlappingStampsStayInRange) {
    DecalMap map(cl(), {.width = 256, .height = 256, .baseHeight = 0.5f});
    std::mt19937 random(7);
    std::normal_distribution<float> around(0.5f, 0.03f);
    std::vector<BulletHole> stamps;
    for (int i = 0; i < 10000; ++i)
        stamps.push_back({std::clamp(around(random), 0.0f, 0.999f), std::clamp(around(random), 0.0f, 0.999f), 0.02f,
                          1.0f, 1.0f, 0.5f});
    map.addBulletHoles(stamps);
    map.step(0.1);
    const auto h = read(map.buffer(), 256 * 256);
    float lo = 1, hi = 0;
    for (float v : h) {
        ASSERT_TRUE(std::isfinite(v));
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    EXPECT_GE(lo, 0.0f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_EQ(lo, 0.0f); // such a storm digs to the bottom...
    EXPECT_EQ(hi, 1.0f); // ...and piles rims to the top
}

TEST_F(Decals, StampOnAnEdgeWraps) {
    const int N = 64;
    DecalMap map(cl(), {.width = N, .height = N});
    map.addBulletHole({.u = 0.0f, .v = 0.5f, .radius = 0.08f});
    map.step(0.1);
    const auto d = read(map.damage(), N * N);
    const int row = N / 2;
    // Centre on the left edge: texel x and texel N-1-x are mirror images.
    for (int x = 0; x < 6; ++x) EXPECT_FLOAT_EQ(d[row * N + x], d[row * N + N - 1 - x]) << x;
    EXPECT_LT(d[row * N + N - 1], -0.1f);

    DecalMap clamped(cl(), {.width = N, .height = N, .edges = EdgeMode::Clamp});
    clamped.addBulletHole({.u = 0.0f, .v = 0.5f, .radius = 0.08f});
    clamped.step(0.1);
    const auto c = read(clamped.damage(), N * N);
    EXPECT_LT(c[row * N], -0.1f);
    EXPECT_EQ(c[row * N + N - 1], 0.0f);
}

TEST_F(Decals, DamageHeals) {
    const int N = 32;
    DecalMap map(cl(), {.width = N, .height = N, .healRate = 0.5f});
    map.addBulletHole({.u = 0.5f, .v = 0.5f, .radius = 0.2f});
    map.step(0.01);
    const auto before = read(map.damage(), N * N);
    map.step(1.0);
    map.step(1.0);
    const auto after = read(map.damage(), N * N);
    for (size_t i = 0; i < before.size(); ++i) EXPECT_NEAR(after[i], before[i] * std::exp(-1.0f), 1e-6);
}

TEST_F(Decals, BadStampsAreRefusedAndNothingIsQueued) {
    DecalMap map(cl(), {.width = 32, .height = 32, .maxStampsPerBatch = 100});
    map.addBulletHole({.u = 0.5f, .v = 0.5f});
    auto message = [&](const BulletHole& h) {
        try {
            map.addBulletHoles({BulletHole{}, h}); // a good stamp first: all or nothing
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message({.u = 1.2f}).find("outside the map"), std::string::npos);
    EXPECT_NE(message({.v = -0.1f}).find("outside the map"), std::string::npos);
    EXPECT_NE(message({.u = NAN}).find("outside the map"), std::string::npos);
    EXPECT_NE(message({.radius = 0.0f}).find("radius"), std::string::npos);
    EXPECT_NE(message({.radius = -0.1f}).find("radius"), std::string::npos);
    EXPECT_NE(message({.depth = -1.0f}).find("depth"), std::string::npos);
    EXPECT_EQ(map.pendingStamps(), 1u);
    EXPECT_THROW(map.addBulletHoles(std::vector<BulletHole>(100)), Error); // 101 > 100
    EXPECT_EQ(map.pendingStamps(), 1u);
    EXPECT_THROW(map.step(0.0), Error);
    EXPECT_THROW(DecalMap(cl(), {.width = 8, .height = 8}, std::vector<float>(64, 2.0f)), Error);
}

TEST(DecalExplosion, ExpandsIntoCraterAndDebris) {
    const auto stamps = DecalMap::expand({.u = 0.9f, .v = 0.1f, .debris = 40, .seed = 3}, EdgeMode::Wrap);
    ASSERT_EQ(stamps.size(), 41u);
    EXPECT_EQ(stamps[0].radius, Explosion{}.radius);
    for (const BulletHole& s : stamps) {
        EXPECT_GE(s.u, 0.0f);
        EXPECT_LT(s.u, 1.0f);
        EXPECT_GE(s.v, 0.0f);
        EXPECT_LT(s.v, 1.0f);
    }
    // Same seed, same debris.
    const auto again = DecalMap::expand({.u = 0.9f, .v = 0.1f, .debris = 40, .seed = 3}, EdgeMode::Wrap);
    EXPECT_EQ(again[17].u, stamps[17].u);
    // On a clamped map debris that flies off the edge is dropped.
    EXPECT_LT(DecalMap::expand({.u = 0.99f, .v = 0.01f, .debris = 40, .seed = 3}, EdgeMode::Clamp).size(), 41u);
}

} // namespace
} // namespace hfx::test
