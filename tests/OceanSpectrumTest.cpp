// The sea's spectra against their closed forms: every spreading integrates to 1, a fully
// developed Pierson-Moskowitz sea has the significant wave height the literature gives, JONSWAP
// peaks where its fetch law says, and shallow water (TMA) holds less energy than deep.

#include "support/Fixtures.h"

#include "hfx/compute/OceanSpectrum.h"
#include "hfx/core/Error.h"

#include <cmath>
#include <numbers>

namespace hfx::test {
namespace {

constexpr double kPi = std::numbers::pi;

double integrateOverAngle(const WaveSpectrum& s, double omega) {
    constexpr int n = 20000; // Simpson's rule; narrow spreadings (s = 200) are resolved
    const double h = 2.0 * kPi / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i)
        sum += s.spread(omega, -kPi + h * i) * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
    return sum * h / 3.0;
}

TEST(OceanSpectrum, EverySpreadingIntegratesToOne) {
    for (Spreading spreading : {Spreading::Cos2s, Spreading::Hasselmann, Spreading::DonelanBanner})
        for (float exponent : {0.5f, 2.0f, 10.0f, 200.0f}) {
            const WaveSpectrum s{.windSpeed = 12.0f, .spreading = spreading, .spreadExponent = exponent};
            for (double ratio : {0.3, 0.6, 0.95, 1.0, 1.3, 1.6, 3.0, 8.0}) {
                const double omega = ratio * s.peakFrequency();
                EXPECT_NEAR(integrateOverAngle(s, omega), 1.0, 1e-3)
                    << spreadingName(spreading) << " s " << exponent << " at " << ratio << " wp";
            }
        }
    // And they point where the waves go: most energy within 45 degrees of the direction.
    const WaveSpectrum s{.windSpeed = 12.0f};
    EXPECT_GT(s.spread(s.peakFrequency(), 0.0), 5.0 * s.spread(s.peakFrequency(), kPi / 2));
}

TEST(OceanSpectrum, FullyDevelopedPiersonMoskowitzSeaHasItsSignificantWaveHeight) {
    for (float u10 : {5.0f, 10.0f, 20.0f}) {
        SeaState sea{.wind = {.shape = SpectrumShape::PiersonMoskowitz, .windSpeed = u10}};
        const double m0 = sea.variance(1e-4, 100.0);
        const double u = 1.026 * u10; // the spectrum's wind is U19.5
        EXPECT_NEAR(4.0 * std::sqrt(m0), 0.21 * u * u / kGravity, 0.05 * 0.21 * u * u / kGravity) << u10 << " m/s";
    }
}

TEST(OceanSpectrum, JonswapPeaksWhereItsFetchLawSaysAndGrowsWithFetch) {
    const WaveSpectrum s{.shape = SpectrumShape::Jonswap, .windSpeed = 10.0f, .fetchKm = 50.0f};
    double best = 0.0, at = 0.0;
    for (double w = 0.2; w < 4.0; w += 1e-4)
        if (s.frequencySpectrum(w) > best) best = s.frequencySpectrum(w), at = w;
    const double wp = 22.0 * std::cbrt(kGravity * kGravity / (10.0 * 50000.0)); // Hasselmann et al. 1973
    EXPECT_NEAR(at, wp, 2e-3 * wp);
    auto hs = [](float fetch) {
        return 4.0 * std::sqrt(SeaState{.wind = {.windSpeed = 10.0f, .fetchKm = fetch}}.variance(1e-4, 100.0));
    };
    EXPECT_LT(hs(10.0f), hs(100.0f));
    // Beyond a fully developed fetch the sea grows no more; without the peak enhancement it is
    // then Pierson-Moskowitz's sea (the same peak, alpha 0.0089 for 0.0081).
    EXPECT_NEAR(hs(5000.0f), hs(50000.0f), 1e-9);
    const double pm = 4.0 * std::sqrt(SeaState{.wind = {.shape = SpectrumShape::PiersonMoskowitz, .windSpeed = 10.0f}}.variance(1e-4, 100.0));
    const double plain = 4.0 * std::sqrt(
        SeaState{.wind = {.windSpeed = 10.0f, .fetchKm = 50000.0f, .peakEnhancement = 1.0f}}.variance(1e-4, 100.0));
    EXPECT_NEAR(plain, pm, 0.06 * pm);
}

TEST(OceanSpectrum, ShallowWaterHoldsLessAndDispersesSlower) {
    const SeaState deep{.wind = {.shape = SpectrumShape::Tma, .windSpeed = 15.0f}};
    SeaState shallow = deep;
    shallow.depthMeters = 5.0f;
    EXPECT_LT(shallow.variance(1e-4, 100.0), 0.8 * deep.variance(1e-4, 100.0));
    // Deep water: w^2 = g k; at k d >> 1 the depth does not matter; shallow: w = k sqrt(g d).
    EXPECT_DOUBLE_EQ(dispersion(0.5, 0.0), std::sqrt(kGravity * 0.5));
    EXPECT_NEAR(dispersion(0.5, 200.0), std::sqrt(kGravity * 0.5), 1e-9);
    EXPECT_NEAR(dispersion(0.001, 2.0), 0.001 * std::sqrt(kGravity * 2.0), 1e-5 * 0.001 * std::sqrt(kGravity * 2.0));
    // The slope is the group velocity: half the phase speed in deep water.
    EXPECT_NEAR(dispersionSlope(0.5, 0.0), 0.5 * dispersion(0.5, 0.0) / 0.5, 1e-12);
    const double h = 1e-6;
    EXPECT_NEAR(dispersionSlope(0.3, 4.0), (dispersion(0.3 + h, 4.0) - dispersion(0.3 - h, 4.0)) / (2 * h), 1e-6);
}

TEST(OceanSpectrum, NamesAndBadValues) {
    EXPECT_EQ(parseSpectrumShape("tma"), SpectrumShape::Tma);
    EXPECT_EQ(parseSpreading("donelan-banner"), Spreading::DonelanBanner);
    EXPECT_NE(messageOf([] { parseSpectrumShape("bretschneider"); }).find("pierson-moskowitz"), std::string::npos);
    EXPECT_NE(messageOf([] { SeaState{.wind = {.windSpeed = -1.0f}}.validate(); }).find("wind.windSpeed"), std::string::npos);
    EXPECT_NE(messageOf([] { SeaState{.depthMeters = std::nanf("")}.validate(); }).find("depthMeters"), std::string::npos);
    EXPECT_EQ(beaufortWindSpeed(7), 15.5f);
    EXPECT_THROW(beaufortWindSpeed(13), Error);
}

} // namespace
} // namespace hfx::test
