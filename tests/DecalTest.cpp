// Decal stamping against its analytic profile, a plain CPU reference (no binning), the [0,1]
// promise under thousands of overlapping stamps, wrapping, healing and refusals.

#include "support/Fixtures.h"
#include "support/References.h"

#include "hfx/compute/DamageLog.h"
#include "hfx/compute/DecalMap.h"
#include "hfx/compute/shared/DecalMath.h"
#include "hfx/core/Error.h"

#include <algorithm>
#include <cmath>
#include <numbers>
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
    std::vector<std::uint8_t> bytes(const cl::Buffer& buffer, size_t count) {
        std::vector<std::uint8_t> out(count);
        cl().queue().enqueueReadBuffer(buffer, CL_TRUE, 0, count, out.data());
        return out;
    }
    /// FNV-1a over the height, albedo and channel maps of `map`.
    std::uint64_t hashMaps(const DecalMap& map) {
        const size_t n = size_t(map.width()) * map.height();
        std::uint64_t h = 1469598103934665603ull;
        auto mix = [&](const void* data, size_t size) {
            for (size_t i = 0; i < size; ++i) h = (h ^ static_cast<const std::uint8_t*>(data)[i]) * 1099511628211ull;
        };
        const std::vector<float> heights = read(map.buffer(), n);
        mix(heights.data(), heights.size() * sizeof(float));
        const std::vector<std::uint8_t> albedo = bytes(map.albedo(), 4 * n), channels = bytes(map.channels(), 4 * n);
        mix(albedo.data(), albedo.size());
        mix(channels.data(), channels.size());
        return h;
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

TEST_F(Decals, MarksMatchTheSharedMathAndBurnTheAlbedoTowardsSoot) {
    constexpr int N = 96;
    DecalConfig config{.width = N, .height = N, .edges = EdgeMode::Clamp};
    std::vector<std::uint8_t> base(4 * N * N);
    for (size_t i = 0; i < base.size(); ++i) base[i] = std::uint8_t(40 + (i * 37) % 200);
    DecalMap map(cl(), config, {}, base);
    const BulletHole hole{.u = 0.45f, .v = 0.5f, .radius = 0.08f, .scorch = 0.8f, .roughness = 0.7f, .occlusion = 0.5f,
                          .scorchReach = 2.0f, .phase = 1.3f, .glow = 0.9f};
    map.addBulletHole(hole);
    map.rebuild();
    const auto albedo = bytes(map.albedo(), 4 * N * N), channels = bytes(map.channels(), 4 * N * N);
    int worst = 0, scorched = 0, glowing = 0;
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            const float r = hole.radius * N;
            float scorch, rough, occlusion;
            float w[4];
            hfx_decal_wobble(hole.phase, w);
            hfx_decal_marks(((x + 0.5f) - hole.u * N) / r, ((y + 0.5f) - hole.v * N) / r, hole.scorch, hole.roughness,
                            hole.occlusion, hole.scorchReach, w[0], w[1], w[2], w[3], &scorch, &rough, &occlusion);
            const size_t i = 4 * (size_t(y) * N + x);
            auto byte = [](float v) { return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
            const float hx = ((x + 0.5f) - hole.u * N) / r, hy = ((y + 0.5f) - hole.v * N) / r;
            const float glow = hfx_decal_heat(hx, hy, hole.glow) * hfx_decal_crust(hx, hy, hole.glow, 1.0f / r, w[0], w[1]);
            worst = std::max({worst, std::abs(channels[i] - byte(rough)), std::abs(channels[i + 1] - byte(occlusion)),
                              std::abs(channels[i + 2] - byte(scorch)), std::abs(channels[i + 3] - byte(glow))});
            glowing += channels[i + 3] > 0;
            for (int c = 0; c < 3; ++c) {
                const float expected = base[i + c] + scorch * (255.0f * config.soot[size_t(c)] - base[i + c]);
                worst = std::max(worst, std::abs(albedo[i + c] - int(std::lround(expected))));
            }
            EXPECT_EQ(albedo[i + 3], base[i + 3]);
            scorched += scorch > 0.5f;
        }
    EXPECT_LE(worst, 1) << "steps of 1/255 from the shared math";
    EXPECT_GT(scorched, 300) << "the burn covers about pi (1.4 radii)^2";
    // The heat fills the bowl: pi (0.08 N)^2 = 185 texels, the last of them under half a step.
    EXPECT_GT(glowing, 150);
    EXPECT_LT(glowing, 190) << "the heat stays in the bowl";
}

TEST_F(Decals, AFreshCratersHeatCracksIntoPlatesThatCoolFirst) {
    // A crater 30 texels across: its heat over the bowl's profile, strength (1 - r^2)^2, is 1 on
    // the cracks and the crust's 0.6 strength on the plates. Inside 0.8 radii the plates are most
    // of the floor, a dozen of them (0.4 radii across: pi 0.8^2 / 0.4^2 = 12.6 cells), parted by
    // cracks; a crater half as hot has plates half as bright against its cracks.
    constexpr int N = 96;
    auto heat = [&](float glow) {
        DecalMap map(cl(), {.width = N, .height = N, .edges = EdgeMode::Clamp});
        map.addBulletHole({.u = 0.5f, .v = 0.5f, .radius = 15.0f / N, .phase = 0.7f, .glow = glow});
        map.rebuild();
        const auto channels = bytes(map.channels(), 4 * N * N);
        std::vector<float> share(N * N, -1.0f); // heat / the bowl's profile, -1 outside 0.8 radii
        for (int y = 0; y < N; ++y)
            for (int x = 0; x < N; ++x) {
                const float dx = (x + 0.5f - 0.5f * N) / 15.0f, dy = (y + 0.5f - 0.5f * N) / 15.0f;
                const float r2 = dx * dx + dy * dy;
                if (r2 < 0.64f) share[size_t(y * N + x)] = channels[4 * size_t(y * N + x) + 3] / 255.0f /
                                                           (glow * (1.0f - r2) * (1.0f - r2));
            }
        return share;
    };
    const std::vector<float> hot = heat(0.8f), cool = heat(0.4f);
    int floor = 0, cracks = 0, plateTexels = 0;
    for (float s : hot) {
        if (s < 0.0f) continue;
        ++floor;
        cracks += s > 0.9f;
        plateTexels += s < 0.5f;
    }
    // The plates: connected texels of the plate, 4-neighbours, each a dozen texels or more.
    std::vector<int> label(hot.size(), 0);
    int plates = 0;
    for (size_t start = 0; start < hot.size(); ++start) {
        if (label[start] || hot[start] < 0.0f || hot[start] >= 0.5f) continue;
        std::vector<size_t> stack{start};
        label[start] = -1;
        int size = 0;
        while (!stack.empty()) {
            const size_t i = stack.back();
            stack.pop_back();
            ++size;
            const int x = int(i % N), y = int(i / N);
            for (const auto& [nx, ny] : {std::pair{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}}) {
                const size_t j = size_t(ny * N + nx);
                if (nx < 0 || ny < 0 || nx >= N || ny >= N || label[j] || hot[j] < 0.0f || hot[j] >= 0.5f) continue;
                label[j] = -1;
                stack.push_back(j);
            }
        }
        plates += size >= 12;
    }
    double hotPlate = 0.0, coolPlate = 0.0;
    int both = 0;
    for (size_t i = 0; i < hot.size(); ++i)
        if (hot[i] >= 0.0f && hot[i] < 0.5f && cool[i] >= 0.0f) {
            hotPlate += hot[i];
            coolPlate += cool[i];
            ++both;
        }
    hotPlate /= both;
    coolPlate /= both;
    std::printf("floor %d texels: cracks %.1f%%, plates %.1f%% in %d plates; a plate's share of the heat %.3f hot, "
                "%.3f at half the heat\n",
                floor, 100.0 * cracks / floor, 100.0 * plateTexels / floor, plates, hotPlate, coolPlate);
    EXPECT_GT(cracks, floor / 12) << "too few cracks";
    EXPECT_LT(cracks, floor / 3) << "the cracks are no narrower than the plates";
    EXPECT_GT(plateTexels, floor / 2);
    EXPECT_GE(plates, 8);
    EXPECT_LE(plates, 20);
    EXPECT_NEAR(hotPlate, 0.48, 0.03) << "the crust at 0.6 of the heat of 0.8";
    EXPECT_NEAR(coolPlate, 0.24, 0.03) << "the crust at 0.6 of the heat of 0.4";
}

// A log fed 10,000 impacts (merging, evicting, healing as the clock runs), its map rebuilt as it
// goes; saved and loaded into a fresh map, it rebuilds the same heights, albedo and channels.
TEST_F(Decals, AReplayedDamageLogRebuildsTheSameMapsBitForBit) {
    constexpr int N = 128;
    std::vector<float> base(N * N);
    for (size_t i = 0; i < base.size(); ++i) base[i] = 0.7f + 0.2f * std::sin(float(i) * 0.11f);
    DamageLogConfig logConfig{.budget = 256, .mergeRadius = 0.01f};
    logConfig.look.scorch = {.start = 1.0, .duration = 20.0, .end = 0.3f};
    DamageLog live(logConfig);
    DecalMap liveMap(cl(), {.width = N, .height = N}, base);
    std::mt19937 random(5);
    std::uniform_real_distribution<float> unit(0.0f, 0.999f);
    for (int i = 0; i < 10000; ++i) {
        live.add({.u = unit(random), .v = unit(random), .radius = 0.01f + 0.02f * unit(random),
                  .kind = i % 50 == 0 ? ImpactKind::Explosion : ImpactKind::Bullet, .seed = std::uint64_t(i)});
        live.advance(0.005);
        if (i % 1000 == 999) {
            liveMap.addBulletHoles(live.stamps());
            liveMap.rebuild();
        }
    }
    EXPECT_EQ(live.size(), 256);
    EXPECT_GT(live.merged(), 0u);
    const std::uint64_t liveHash = hashMaps(liveMap);
    const std::string path = outputPath("replay-damage.log");
    live.save(path);

    const DamageLog loaded = DamageLog::load(path, logConfig);
    DecalMap replayed(cl(), {.width = N, .height = N}, base);
    replayed.addBulletHoles(loaded.stamps());
    replayed.rebuild();
    EXPECT_EQ(hashMaps(replayed), liveHash);
    // And the hash sees a change: one more impact moves it.
    DamageLog more = loaded;
    more.add({.u = 0.5f, .v = 0.5f, .radius = 0.05f});
    replayed.addBulletHoles(more.stamps());
    replayed.rebuild();
    EXPECT_NE(hashMaps(replayed), liveHash);
}

TEST(DecalMarks, ABurnIsDarkestAtItsCraterAndFadesOutInRays) {
    // Along every ray from an impact the soot is full on the crater's floor and fades from the lip
    // out to its outline (where it falls below a twentieth), lower at every step, and by a tenth a
    // third of the way there: no flat plate of full soot past the lip with a rim round it, as
    // the burn had until 2026-11-29. It ends inside the reach its stamp is binned by (no cut along
    // a tile's edge), and its outline bulges into a blast's rays, 12 or more round the circle,
    // in no k-fold pattern: turned by a k-th of a turn (k = 2 to 8) it correlates with itself
    // under 0.5. (Until 2026-11-30 one lobe order, 5, held 0.18 of the 0.4 of the outline's
    // swing, and a bullet's soot, too small for the finer orders to show, read as a five-pointed
    // star: turned by a fifth, 0.65.)
    const DamageLook look;
    const std::vector<BulletHole> explosion = DecalMap::expand(look.explosion, EdgeMode::Wrap);
    double mostFold = -1.0;
    int fewestRays = 1 << 30;
    for (const BulletHole& mark : {look.bullet, explosion[0], explosion[1]})
        for (const float phase : {0.0f, 0.9f, 2.3f, 4.1f, 5.9f}) {
            float w[4];
            hfx_decal_wobble(phase, w);
            const float reach = hfx_decal_reach(mark.rimWidth, mark.scorch, mark.roughness, mark.scorchReach);
            auto scorchAt = [&](float r, float a) {
                float scorch, rough, occlusion;
                hfx_decal_marks(r * std::cos(a), r * std::sin(a), 1.0f, mark.roughness, mark.occlusion,
                                mark.scorchReach, w[0], w[1], w[2], w[3], &scorch, &rough, &occlusion);
                return scorch;
            };
            constexpr int kAngles = 720;
            constexpr float kStep = 0.02f;
            std::vector<float> outline(kAngles);
            float palestFloor = 1.0f, darkestThird = 0.0f, lastSoot = 0.0f;
            int flat = 0;
            for (int k = 0; k < kAngles; ++k) {
                const float a = 2.0f * std::numbers::pi_v<float> * float(k) / kAngles;
                palestFloor = std::min(palestFloor, scorchAt(0.5f, a));
                for (float r = 1.0f, here = scorchAt(r, a); here > 0.0f; r += kStep) {
                    const float next = scorchAt(r + kStep, a);
                    flat += next >= here;
                    if (here >= 0.05f) outline[size_t(k)] = r + kStep;
                    here = next;
                }
                darkestThird = std::max(darkestThird, scorchAt(1.0f + (outline[size_t(k)] - 1.0f) / 3.0f, a));
                lastSoot = std::max(lastSoot, scorchAt(reach - 0.01f, a));
            }
            int rays = 0;
            for (int k = 0; k < kAngles; ++k)
                rays += outline[size_t(k)] > outline[size_t((k + kAngles - 1) % kAngles)] &&
                        outline[size_t(k)] >= outline[size_t((k + 1) % kAngles)];
            const std::string where = str("scorch reach ", mark.scorchReach, ", phase ", phase);
            double mean = 0.0, variance = 0.0;
            for (const float o : outline) mean += o / double(kAngles);
            for (const float o : outline) variance += (o - mean) * (o - mean);
            for (int k = 2; k <= 8; ++k) {
                double turned = 0.0;
                for (int i = 0; i < kAngles; ++i)
                    turned += (outline[size_t(i)] - mean) * (outline[size_t((i + kAngles / k) % kAngles)] - mean);
                EXPECT_LT(turned / variance, 0.5) << where << ": the outline is " << k << "-fold";
                mostFold = std::max(mostFold, turned / variance);
            }
            EXPECT_GT(palestFloor, 0.95f) << where << ": the crater's floor is burnt black";
            EXPECT_LT(darkestThird, 0.9f) << where << ": full soot past the lip";
            EXPECT_EQ(flat, 0) << where << ": steps where the soot did not fade outwards";
            EXPECT_LT(lastSoot, 1e-3f) << where << ": the soot is cut at the binned reach";
            EXPECT_GE(rays, 12) << where;
            fewestRays = std::min(fewestRays, rays);
        }
    std::printf("[burn] the outlines: at least %d rays; turned by a k-th of a turn, at most %.2f correlated\n",
                fewestRays, mostFold);
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
