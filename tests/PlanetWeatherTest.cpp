// The gas giant's weather: storms are seeded only in the middle of the bands, the jets fade at
// the poles, and a 10^4 time scale stays finite and bounded.

#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/effects/GasPlanetEffect.h"

#include <algorithm>
#include <cmath>

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

TEST_F(PlanetWeather, ATimeScaleOfTenThousandRunsAThousandStepsWithoutNaN) {
    GasPlanetEffect planet(cl(), {.gas = {.width = 64, .height = 32, .pressureIterations = 20, .vorticity = 0.35f,
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

} // namespace
} // namespace hfx::test
