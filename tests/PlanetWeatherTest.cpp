// The gas giant's weather: storms are seeded only in the middle of the bands, the jets fade at
// the poles, a 10^4 time scale stays finite and bounded, a seeded vortex outlives twenty
// rotations, and the weather is the same in planet units on a finer grid (the device's).

#include "support/Fixtures.h"

#include "hfx/compute/shared/GasMath.h"
#include "hfx/core/Error.h"
#include "hfx/effects/GasPlanetEffect.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <numbers>
#include <utility>

namespace hfx::test {
namespace {

class PlanetWeather : public DeviceTest {};

TEST_F(PlanetWeather, StormsAreSeededOnlyWhereTheBandShearIsLowAndJetsFadeAtThePoles) {
    GasPlanetEffect planet(cl(), {.gas = {.width = 64, .height = 32, .jetSpeed = 14.0f, .jetBands = 4.5f,
                                          .jetPolar = 1.0f, .initialBands = 4.0f},
                                  .stormsPerSecond = 20.0f});
    for (int i = 0; i < 3; ++i) planet.update(1.0);
    ASSERT_GE(planet.seededStorms().size(), 40u);
    for (const glm::vec2& s : planet.seededStorms())
        EXPECT_LE(planet.relativeShear(s.y), 0.35f) << "a storm seeded at v = " << s.y;
    float peak = 0.0f;
    for (int i = 0; i <= 1000; ++i) peak = std::max(peak, std::abs(planet.jetProfile(i / 1000.0)));
    EXPECT_EQ(planet.jetProfile(0.0), 0.0f);
    EXPECT_LT(std::abs(planet.jetProfile(0.02)), 0.1f * peak) << "the jets fade towards the poles";
    EXPECT_NE(messageOf([&] { planet.setTimeScale(2e4f); }).find("timeScale"), std::string::npos);
    EXPECT_EQ(planet.timeScale(), 1.0f);
}

TEST_F(PlanetWeather, ASpinUpIsTheWeatherOfLivingThroughItWhateverTheTimeScale) {
    // 20 simulated seconds at once on a planet shown 10x faster, against five 4-second frames of
    // one shown in real time: the same substeps (8 of 0.5 s a frame), storms and all, so the
    // same gas to the bit.
    GasPlanetConfig config{.gas = {.width = 64, .height = 32, .vorticity = 0.35f, .jetSpeed = 14.0f, .jetBands = 4.5f,
                                   .jetRate = 0.2f, .jetPolar = 1.0f, .maxSpeed = 56.0f, .initialBands = 4.0f,
                                   .bandVariety = 1.0f, .dyeRate = 0.15f}};
    GasPlanetEffect lived(cl(), config);
    for (int i = 0; i < 5; ++i) lived.update(4.0);
    config.timeScale = 10.0f;
    GasPlanetEffect spun(cl(), config);
    spun.spinUp(20.0);
    EXPECT_DOUBLE_EQ(spun.time(), 20.0);
    EXPECT_EQ(spun.seededStorms().size(), lived.seededStorms().size());
    EXPECT_GE(spun.seededStorms().size(), 10u) << "0.6 storms a second";
    std::vector<float> u[2], v[2], dye[2];
    lived.gas().readState(u[0], v[0], dye[0]);
    spun.gas().readState(u[1], v[1], dye[1]);
    EXPECT_EQ(u[0], u[1]);
    EXPECT_EQ(v[0], v[1]);
    EXPECT_EQ(dye[0], dye[1]);
    EXPECT_NE(messageOf([&] { spun.spinUp(-1.0); }).find("spinUp"), std::string::npos);
    EXPECT_DOUBLE_EQ(spun.time(), 20.0);
}

TEST_F(PlanetWeather, ASpunUpPlanetDrawsItsWeatherBeforeAnyUpdate) {
    // The demo draws its first frame before its first update (an overlapped frame draws what the
    // last update left): after spinUp the textures must hold the gas spun up, not the bands as
    // the constructor drew them (what the demo's first planet frame showed before).
    GasPlanetEffect planet(cl(), {.gas = {.width = 64, .height = 32, .vorticity = 0.35f, .jetSpeed = 14.0f,
                                          .jetBands = 4.5f, .jetRate = 0.2f, .jetPolar = 1.0f, .maxSpeed = 56.0f,
                                          .initialBands = 4.0f, .bandVariety = 1.0f, .dyeRate = 0.15f},
                                  .stormsPerSecond = 2.0f,
                                  .surface = {.format = SurfaceFormat::Float32}}); // the heights to the bit
    auto drawn = [&] {
        const int w = planet.surfaceWidth(), h = planet.surfaceHeight();
        std::vector<float> texels(size_t(w) * h * 4), heights(size_t(w) * h);
        glGetTextureImage(planet.textures().surface(), 0, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(float)),
                          texels.data());
        for (size_t i = 0; i < heights.size(); ++i) heights[i] = texels[4 * i + 3];
        return heights;
    };
    auto largestDifference = [](const std::vector<float>& a, const std::vector<float>& b) {
        float d = 0.0f;
        for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
        return d;
    };
    const std::vector<float> before = drawn();
    planet.spinUp(30.0);
    const std::vector<float> after = drawn(), heights = planet.readHeights();
    ASSERT_EQ(after.size(), heights.size());
    std::printf("[spin-up] drawn heights: %.3f from the bands as they started, %.2e from readHeights()\n",
                double(largestDifference(after, before)), double(largestDifference(after, heights)));
    EXPECT_GT(largestDifference(after, before), 0.05f) << "the textures still hold the bands as they started";
    EXPECT_LT(largestDifference(after, heights), 1e-6f) << "the textures are not the heights readHeights() gives";
}

TEST_F(PlanetWeather, ThePolesDrawNoStarburstOnTheSphereNorThroughThePolarFilter) {
    // A texel's longitude spans cos(latitude) of what its latitude spans: near a pole, a flat
    // gas's eddies, round on the map, are drawn as wedges along the meridians that meet in a
    // starburst. Measured on the sphere (a zonal difference over cos(latitude) texels of arc), the
    // drawn heights' slope across the meridians over their slope along them, 75 to 85 degrees of
    // latitude, 30 s into the same weather: on the sphere's metric (GasConfig::sphere, the
    // planet's) no more across than along (measured: 0.78, the polar gas's rings about the pole);
    // on a flat gas, 3.1 times more across, and 1.16 through the polar filter
    // (GasPlanetConfig::polarSmoothing), which leaves the heights below 50 degrees the same to
    // the bit.
    GasPlanetConfig config;
    config.gas.width = 256;
    config.gas.height = 128;
    config.detail.scale = 2;
    ASSERT_TRUE(config.gas.sphere);
    ASSERT_EQ(config.polarSmoothing, 0.0f);
    GasPlanetEffect sphere(cl(), config);
    config.gas.sphere = false;
    config.gas.rotation = 0.0f; // a flat map cannot spin
    GasPlanetEffect flat(cl(), config);
    config.polarSmoothing = 0.75f;
    GasPlanetEffect filtered(cl(), config);
    for (GasPlanetEffect* planet : {&sphere, &flat, &filtered}) planet->spinUp(30.0);
    const std::vector<float> a = filtered.readHeights(), b = flat.readHeights();
    const int W = filtered.surfaceWidth(), H = filtered.surfaceHeight();
    ASSERT_EQ(a.size(), size_t(W) * H);
    auto anisotropy = [&](const std::vector<float>& h) {
        double across = 0.0, along = 0.0;
        for (int y = 0; y + 1 < H; ++y) {
            const double latitude = ((y + 1.0) / H - 0.5) * std::numbers::pi; // between rows y and y + 1
            if (std::abs(latitude) < 75.0 * std::numbers::pi / 180.0 || std::abs(latitude) > 85.0 * std::numbers::pi / 180.0)
                continue;
            const double c = std::cos(((y + 0.5) / H - 0.5) * std::numbers::pi);
            for (int x = 0; x < W; ++x) {
                const size_t k = size_t(y) * W + x;
                across += std::abs(h[size_t(y) * W + (x + 1) % W] - h[k]) / c;
                along += std::abs(h[k + W] - h[k]);
            }
        }
        return across / along;
    };
    int same = 0, low = 0;
    for (int y = 0; y < H; ++y) {
        if (std::abs((y + 0.5) / H - 0.5) * 180.0 >= 50.0) continue;
        ++low;
        same += std::equal(a.begin() + ptrdiff_t(y) * W, a.begin() + ptrdiff_t(y + 1) * W, b.begin() + ptrdiff_t(y) * W);
    }
    const double onSphere = anisotropy(sphere.readHeights()), withFilter = anisotropy(a), without = anisotropy(b);
    std::printf("[polar] 75-85 degrees: the heights' slope across the meridians / along them, %.2f on the sphere; "
                "on a flat gas %.2f, %.2f filtered; %d of %d rows below 50 degrees the same\n",
                onSphere, without, withFilter, same, low);
    EXPECT_GT(without, 2.0) << "a flat gas's caps would pass as well";
    EXPECT_LT(onSphere, 1.4);
    EXPECT_LT(withFilter, 1.4);
    EXPECT_EQ(same, low);
}

TEST_F(PlanetWeather, ATimeScaleOfTenThousandRunsAThousandStepsWithoutNaN) {
    GasPlanetEffect planet(cl(), {.gas = {.width = 64, .height = 32, .pressure = GasPressure::Jacobi,
                                          .pressureIterations = 20, .vorticity = 0.35f,
                                          .jetSpeed = 14.0f, .jetBands = 4.5f, .jetRate = 0.2f, .jetPolar = 1.0f,
                                          .maxSpeed = 56.0f, .initialBands = 6.0f},
                                  .timeScale = 1e4f});
    for (int i = 0; i < 1000; ++i) planet.update(1.0 / 30.0);
    EXPECT_NEAR(planet.time(), 1000.0 / 30.0 * 1e4, 1.0);
    std::vector<float> u, v, dye;
    planet.gas().readState(u, v, dye);
    for (size_t i = 0; i < u.size(); ++i) {
        ASSERT_TRUE(std::isfinite(u[i]) && std::isfinite(v[i])) << i;
        ASSERT_LE(std::abs(u[i]), 2.0f * 56.0f) << "bounded (the projection after the clamp adds a little)";
        ASSERT_TRUE(dye[i] >= 0.0f && dye[i] <= 1.0f) << i;
    }
    for (float h : planet.readHeights()) ASSERT_TRUE(h >= 0.0f && h <= 1.0f) << h;
}

/// The quietest latitude near the equator (v in [0.3, 0.7]): the middle of a band, where the
/// jets' shear is least.
float quietestLatitude(const GasPlanetEffect& planet) {
    double best = 0.5, quiet = 1e9;
    for (int i = 0; i <= 400; ++i) {
        const double v = 0.3 + 0.4 * i / 400.0;
        if (planet.relativeShear(v) < quiet) quiet = planet.relativeShear(v), best = v;
    }
    return float(best);
}

TEST_F(PlanetWeather, ASeededVortexIsStillThereAfterTwentyRotations) {
    constexpr int W = 128, H = 64;
    GasPlanetConfig config{.gas = {.width = W, .height = H, .pressure = GasPressure::Jacobi,
                                   .pressureIterations = 30, .vorticity = 0.35f,
                                   .jetSpeed = 14.0f, .jetBands = 4.5f, .jetRate = 0.2f, .jetPolar = 1.0f,
                                   .maxSpeed = 56.0f, .initialBands = 6.0f},
                           .stormsPerSecond = 0.0f, .stormRadius = 0.04f, .timeScale = 60.0f};
    GasPlanetEffect planet(cl(), config);
    planet.addStorm(0.5f, quietestLatitude(planet), true, 2.0f);
    const double rotation = 2.0 * std::numbers::pi / config.rotationSpeed;
    std::vector<float> u, v, dye;
    const std::vector<float>& table = planet.gas().metricTable();
    auto vortexRatio = [&] {
        planet.gas().readState(u, v, dye);
        const GasPlanetEffect::Storm& storm = planet.storms().at(0);
        const int ci = int(storm.u * W), cj = int(storm.v * H), reach = int(2.0f * storm.radius * W);
        // The storm's neighbourhood against its band's typical vorticity (all longitudes).
        double extremum = 0.0;
        std::vector<double> band;
        for (int j = std::max(1, cj - reach); j <= std::min(H - 2, cj + reach); ++j)
            for (int i = 0; i < W; ++i) {
                const double w = std::abs(hfx_gas_curl(u.data(), v.data(), table.data(), W, H, i, j));
                band.push_back(w);
                const int di = std::min(std::abs(i - ci), W - std::abs(i - ci));
                if (di <= reach) extremum = std::max(extremum, w);
            }
        std::nth_element(band.begin(), band.begin() + long(band.size() / 2), band.end());
        return extremum / std::max(band[band.size() / 2], 1e-6);
    };
    // The flow is chaotic: a change of 10^-7 in the forces moves one rotation's ratio by half
    // (4.13 against 2.65 at rotation 20), so the claim is held over the last five rotations' median.
    std::vector<double> last;
    for (int r = 1; r <= 20; ++r) {
        while (planet.time() < r * rotation) planet.update(1.0 / 30.0);
        if (r > 15) last.push_back(vortexRatio());
        if (r == 1 || r % 5 == 0) std::printf("rotation %d: vortex / band median %.2f\n", r, vortexRatio());
    }
    ASSERT_EQ(planet.storms().size(), 1u) << "its life is 40 rotations";
    std::nth_element(last.begin(), last.begin() + 2, last.end());
    std::printf("rotations 16-20: median ratio %.2f\n", last[2]);
    EXPECT_GT(last[2], 3.0) << "the vortex stands out of its band over rotations 16 to 20";
}

TEST_F(PlanetWeather, AStormKeepsItsColourAndRidesTheWindAtItsCentre) {
    // A storm seeded in a band's middle on the planet's sphere (a 128x64 gas), read at rotations 3
    // to 7. Each frame the gas's wind at its centre (GasField::velocityAt, read before the frame's
    // steps) carries it along its band: u / metricAt(v) cells a second. Its clouds keep its colour
    // (the feed) within 0.15 (median 0.08 on PoCL) where, unheld and unfed, the shear and the
    // dye's relaxation leave its band's (0.48 off).
    // This test once also asked that the core of the spin about the storm be centred inside its
    // oval (rho < 1, median of the five readings: 0.76 on PoCL, 1.01 on an H200). That measure
    // could not fail for a storm elsewhere: about points a quarter, a half and three quarters of
    // the way round its latitude, where no storm is, it gave medians of 1.01, 0.81 and 0.77 on
    // PoCL, the band's own eddies spinning there as hard (the oval's mean spin 0.86 an eighth of
    // a turn west of the storm against 0.77 about it). That the held vortex stands out of its
    // band is ASeededVortexIsStillThereAfterTwentyRotations's, and the hold's wind Gas's.
    constexpr int W = 128, H = 64;
    auto make = [&](float hold, float feed) {
        GasPlanetConfig config{.gas = {.width = W, .height = H, .sphere = true, .pressure = GasPressure::Jacobi,
                                       .pressureIterations = 30,
                                       .vorticity = 0.35f, .jetSpeed = 14.0f, .jetBands = 4.5f, .jetRate = 0.2f,
                                       .jetPolar = 1.0f, .maxSpeed = 56.0f, .initialBands = 6.0f, .dyeRate = 0.15f},
                               .stormsPerSecond = 0.0f, .stormRadius = 0.06f, .timeScale = 60.0f};
        config.stormHold = hold;
        config.stormFeed = feed;
        auto planet = std::make_unique<GasPlanetEffect>(cl(), config);
        planet->addStorm(0.5f, quietestLatitude(*planet), true);
        return planet;
    };
    const auto held = make(1.0f, 2.0f), loose = make(0.0f, 0.0f);
    const double rotation = 2.0 * std::numbers::pi / held->config().rotationSpeed;
    auto colourError = [&](GasPlanetEffect& planet) {
        std::vector<float> u, v, dye;
        planet.gas().readState(u, v, dye);
        const GasPlanetEffect::Storm& storm = planet.storms().at(0);
        return std::abs(dye[size_t(storm.v * H) * W + size_t(storm.u * W)] - storm.colour);
    };
    // One frame's move along the band against the wind at the storm's centre before it, in cells.
    auto ride = [&](GasPlanetEffect& planet) {
        const GasPlanetEffect::Storm before = planet.storms().at(0);
        const glm::vec2 wind = planet.gas().velocityAt({{float(before.u), float(before.v)}}).at(0);
        const double t0 = planet.time();
        planet.update(1.0 / 30.0);
        const GasPlanetEffect::Storm& after = planet.storms().at(0);
        const double moved = std::remainder(after.u - before.u, 1.0) * W;
        const double expected = double(wind.x) / planet.gas().metricAt(float(before.v)) * (planet.time() - t0);
        EXPECT_EQ(after.v, before.v) << "a storm stays on its latitude";
        return std::pair{moved, expected};
    };
    std::vector<double> heldErrors, looseErrors;
    for (int r = 3; r <= 7; ++r) {
        while (held->time() < r * rotation) held->update(1.0 / 30.0);
        while (loose->time() < r * rotation) loose->update(1.0 / 30.0);
        heldErrors.push_back(colourError(*held));
        looseErrors.push_back(colourError(*loose));
        const auto [moved, expected] = ride(*held);
        std::printf("[storm] rotation %d: it moved %.4f cells in a frame, its centre's wind %.4f; its colour %.2f "
                    "off held and fed, %.2f off without\n",
                    r, moved, expected, heldErrors.back(), looseErrors.back());
        EXPECT_GT(std::abs(expected), 0.01) << "rotation " << r << ": the test's premise, a wind at the storm";
        EXPECT_NEAR(moved, expected, 1e-3 * std::abs(expected) + 1e-5) << "rotation " << r;
    }
    auto median = [](std::vector<double> x) {
        std::nth_element(x.begin(), x.begin() + 2, x.end());
        return x[2];
    };
    EXPECT_LT(median(heldErrors), 0.15) << "the storm lost its colour";
    EXPECT_GT(median(looseErrors), 0.2) << "unfed, the storm kept its colour (the test's premise)";
    // Bad storm settings are refused by name.
    const std::pair<const char*, GasPlanetConfig> bad[] = {{"stormWind", {.stormWind = -1.0f}},
                                                           {"stormAspect", {.stormAspect = 0.5f}},
                                                           {"stormHold", {.stormHold = NAN}},
                                                           {"stormFeed", {.stormFeed = 1e3f}}};
    for (const auto& [field, config] : bad)
        EXPECT_NE(messageOf([&c = config] { c.validate(); }).find(field), std::string::npos) << field;
}

TEST_F(PlanetWeather, AStormsCloudsWindIntoArmsThatTurnWithIt) {
    // A storm on a 128x64 gas, 10 s later, with its arms (GasPlanetConfig::stormArms, 3) and
    // without: the same gas (the dye does not move it), so the dye's difference is the arms'.
    // On the oval's rings rho = 0.5, 0.7 and 0.9 about where the planet has the storm, that
    // difference's third angular harmonic is larger than what the band's own structure puts in
    // the dye there without arms (1.9x, 1.6x and 6.6x on PoCL). On the middle ring it peaks
    // within a third of their spacing of where the arms' law puts arm 0 (GasArms: the angle the
    // planet turned them by, at the gas's spin at the storm's centre, less the winding's lag
    // there; paler than the storm here): they turn with the storm (0.28 rad from it on PoCL;
    // the gas's own shear winds them further than the law, 0.96 rad ahead of it at rho 0.5 and
    // 0.60 behind at 0.9).
    constexpr int W = 128, H = 64;
    auto after = [&](int arms) {
        GasPlanetConfig config{.gas = {.width = W, .height = H, .pressure = GasPressure::Jacobi,
                                       .pressureIterations = 30, .vorticity = 0.35f,
                                       .jetSpeed = 14.0f, .jetBands = 4.5f, .jetRate = 0.2f, .jetPolar = 1.0f,
                                       .maxSpeed = 56.0f, .initialBands = 6.0f, .dyeRate = 0.15f},
                               .stormsPerSecond = 0.0f, .stormRadius = 0.1f};
        config.stormArms = arms;
        auto planet = std::make_unique<GasPlanetEffect>(cl(), config);
        planet->addStorm(0.5f, quietestLatitude(*planet), false, 2.0f);
        while (planet->time() < 10.0) planet->update(0.1);
        return planet;
    };
    const auto with = after(3), without = after(0);
    std::vector<float> u, v, armed, plain;
    with->gas().readState(u, v, armed);
    without->gas().readState(u, v, plain);
    const GasPlanetEffect::Storm& storm = with->storms().at(0);
    ASSERT_GT(storm.band, storm.colour) << "the test's premise: paler arms in a dark storm";
    const double x = storm.u * W, y = storm.v * H, a = storm.radius * W, b = a / with->config().stormAspect;
    const double spacing = 2.0 * std::numbers::pi / 3.0;
    // The third harmonic of a field on the ring rho (bilinear reads at 144 angles).
    auto harmonic = [&](const std::vector<float>& f, double rho) {
        auto at = [&](int i, int j) { return double(f[size_t(j) * W + size_t((i % W + W) % W)]); };
        std::complex<double> sum = 0.0;
        for (int k = 0; k < 144; ++k) {
            const double phi = 2.0 * std::numbers::pi * k / 144.0;
            const double fx = x + rho * a * std::cos(phi) - 0.5, fy = y + rho * b * std::sin(phi) - 0.5;
            const int i = int(std::floor(fx)), j = int(std::floor(fy));
            const double tx = fx - i, ty = fy - j;
            const double d = (1 - ty) * ((1 - tx) * at(i, j) + tx * at(i + 1, j)) +
                             ty * ((1 - tx) * at(i, j + 1) + tx * at(i + 1, j + 1));
            sum += d * std::polar(2.0 / 144.0, -3.0 * phi);
        }
        return sum;
    };
    std::vector<float> arms(armed.size());
    for (size_t k = 0; k < arms.size(); ++k) arms[k] = armed[k] - plain[k];
    for (const double rho : {0.5, 0.7, 0.9}) {
        const std::complex<double> drawn = harmonic(arms, rho);
        const double band = std::abs(harmonic(plain, rho));
        const double law = storm.turned - with->config().stormWinding * (1.0 - std::exp(-rho * rho));
        const double off = std::remainder(std::arg(drawn) / 3.0 - law, spacing);
        std::printf("[arms] rho %.1f: the arms' third harmonic %.3f, the band's own %.3f; the arms %.2f rad from "
                    "their law\n",
                    rho, std::abs(drawn), band, off);
        EXPECT_GT(std::abs(drawn), band) << "rho " << rho;
        if (rho == 0.7) {
            EXPECT_LT(std::abs(off), spacing / 3.0) << "the arms do not turn with the storm";
        }
    }
}

TEST_F(PlanetWeather, ThePlanetsSpinHoldsItsBandsWhichWithoutItBreakUp) {
    // The planet's jets, u = U sin(4.5 cycles over the latitudes), have inflection points: on a
    // still sphere they are unstable (Rayleigh), and within two minutes their eddies hold most of
    // the wind's energy and mix the bands. GasPlanetConfig's spin gives the gas the beta effect,
    // above the jets' curvature (Rayleigh-Kuo: 6.9 rad/s at the equator), and they hold. The
    // planet's gas at half its cells (as gridScale 0.5 scales it), 120 s in steps of 0.5 s, as the
    // spin-up takes them: the zonal mean's share of the wind's energy and of the dye's variance
    // (area-weighted). Measured on PoCL: 0.94 and 0.84 spinning, 0.23 and 0.31 still.
    const GasConfig planet = scaledGas(GasPlanetConfig{}.gas, 0.5f);
    ASSERT_GT(planet.rotation, 0.0f);
    for (const float rotation : {planet.rotation, 0.0f}) {
        GasConfig config = planet;
        config.rotation = rotation;
        GasField gas(cl(), config);
        for (int s = 0; s < 240; ++s) gas.step(0.5);
        std::vector<float> u, v, dye;
        gas.readState(u, v, dye);
        const int W = gas.width(), H = gas.height();
        double mean = 0.0;
        for (float d : dye) mean += d;
        mean /= double(dye.size());
        double zonalWind = 0.0, wind = 0.0, zonalDye = 0.0, allDye = 0.0;
        for (int j = 0; j < H; ++j) {
            const double m = gas.metricTable()[size_t(2 * j + 1)];
            double mu = 0.0, md = 0.0;
            for (int i = 0; i < W; ++i) {
                const size_t n = size_t(j) * W + i;
                mu += u[n] / W;
                md += dye[n] / W;
                wind += m * (double(u[n]) * u[n] + double(v[n]) * v[n]) / W;
                allDye += m * (dye[n] - mean) * (dye[n] - mean) / W;
            }
            zonalWind += m * mu * mu;
            zonalDye += m * (md - mean) * (md - mean);
        }
        std::printf("[spin] rotation %.0f: after 120 s the zonal means hold %.2f of the wind's energy, %.2f of the "
                    "dye's variance\n",
                    rotation, zonalWind / wind, zonalDye / allDye);
        if (rotation > 0.0f) {
            EXPECT_GT(zonalWind / wind, 0.85);
            EXPECT_GT(zonalDye / allDye, 0.7);
        } else {
            EXPECT_LT(zonalWind / wind, 0.5) << "the test's premise: the jets are unstable without the spin";
        }
    }
}

/// The planet's zonal wind and a storm's wind after `seconds` of gas, in planet units (map widths
/// per second): the RMS of the zonal-mean east wind over the latitudes, and the fastest wind
/// relative to its latitude's mean within two storm radii of a storm added at the start.
struct Weather {
    double zonalWind, stormWind;
    int width;
};
Weather weatherOf(ClContext& cl, const GasPlanetConfig& config, double seconds) {
    GasPlanetEffect planet(cl, config);
    planet.addStorm(0.5f, 0.5f, true, 2.0f);
    while (planet.time() < seconds) planet.update(1.0 / 30.0);
    std::vector<float> u, v, dye;
    planet.gas().readState(u, v, dye);
    const int W = planet.gas().width(), H = planet.gas().height();
    std::vector<double> mean(size_t(H), 0.0);
    double sum = 0.0;
    for (int j = 0; j < H; ++j) {
        for (int i = 0; i < W; ++i) mean[size_t(j)] += u[size_t(j) * W + i] / W;
        sum += (mean[size_t(j)] / W) * (mean[size_t(j)] / W); // cells per second -> widths per second
    }
    const GasPlanetEffect::Storm& storm = planet.storms().at(0);
    const int ci = int(storm.u * W), cj = int(storm.v * H), reach = int(2.0f * storm.radius * W);
    double wind = 0.0;
    for (int j = std::max(0, cj - reach); j <= std::min(H - 1, cj + reach); ++j)
        for (int di = -reach; di <= reach; ++di) {
            const size_t at = size_t(j) * W + size_t(((ci + di) % W + W) % W);
            wind = std::max(wind, std::hypot(u[at] - mean[size_t(j)], double(v[at])) / W);
        }
    return {std::sqrt(sum / H), wind, W};
}

TEST_F(PlanetWeather, AFinerGridKeepsTheWeatherInPlanetUnits) {
    // The same planet on its reference grid (64x32), on twice the cells through gridScale (what a
    // GPU gets), and on twice the cells with the rates left in cells per second (what a finer
    // grid did before gridScale). A minute of gas at 30x: the jets have relaxed (rate 0.2 per
    // second) and a storm has spun up. The gas is viscous (2 cells^2 per second on the reference
    // grid, scaled with the cells' square), so its jets are laminar: inviscid, they are
    // shear-unstable on grids this coarse (4.5 bands on 32 or 64 rows) and their zonal mean is
    // chaos, 5-20% of its target and a different share on each grid, which no scaling keeps.
    // Measured on llvmpipe + PoCL: scaled, the zonal wind 1.3% and the storm's 1.8% off the
    // reference's; unscaled, 7.5% and 14%, outside the 5% and 10% the scaled grid meets.
    const GasPlanetConfig reference{.gas = {.width = 64, .height = 32, .viscosity = 2.0f, .pressure = GasPressure::Jacobi,
                                            .pressureIterations = 20,
                                            .vorticity = 0.35f, .jetSpeed = 14.0f, .jetBands = 4.5f, .jetRate = 0.2f,
                                            .jetPolar = 1.0f, .maxSpeed = 56.0f, .initialBands = 6.0f},
                                    .stormsPerSecond = 0.0f, .stormRadius = 0.05f, .timeScale = 30.0f, .poleCap = 0.0f,
                                    .detail = {.amount = 0.0f}};
    GasPlanetConfig scaled = reference;
    scaled.gridScale = 2.0f;
    GasPlanetConfig finer = reference;
    finer.gas.width = 128;
    finer.gas.height = 64;
    const Weather a = weatherOf(cl(), reference, 60.0), b = weatherOf(cl(), scaled, 60.0), c = weatherOf(cl(), finer, 60.0);
    std::printf("[grid] zonal wind and storm wind (widths/s): %d wide: %.4f, %.4f; %d scaled: %.4f, %.4f; %d "
                "unscaled: %.4f, %.4f\n",
                a.width, a.zonalWind, a.stormWind, b.width, b.zonalWind, b.stormWind, c.width, c.zonalWind, c.stormWind);
    ASSERT_EQ(b.width, 128);
    EXPECT_NEAR(b.zonalWind / a.zonalWind, 1.0, 0.05) << "the jets' speed changed with the grid";
    EXPECT_NEAR(b.stormWind / a.stormWind, 1.0, 0.1) << "the storm's wind changed with the grid";
    EXPECT_TRUE(std::abs(c.zonalWind / a.zonalWind - 1.0) > 0.05 || std::abs(c.stormWind / a.stormWind - 1.0) > 0.1)
        << "unscaled, a finer grid should miss what the scaled one meets (the test's premise)";
    EXPECT_THROW(GasPlanetEffect(cl(), GasPlanetConfig{.gridScale = 8.0f}), Error);
    EXPECT_THROW(GasPlanetEffect(cl(), GasPlanetConfig{.gridScale = -1.0f}), Error);
}

} // namespace
} // namespace hfx::test
