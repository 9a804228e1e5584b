// The FFT ocean against closed forms: a direct DFT of its spectrum; one mode is the trochoidal
// (Gerstner) wave, positions, normal and Jacobian; the cascades' variances add up to the
// spectrum's (Parseval) and a fully developed sea has its significant wave height; time is a
// pure input; foam appears exactly where J < threshold and halves in its half-life; the
// patch tiles and the animation loops.

#include "support/Fixtures.h"

#include "hfx/compute/OceanField.h"
#include "hfx/core/Error.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace hfx::test {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

class Ocean : public ClTest {
protected:
    std::vector<float> read(const cl::Buffer& b, size_t n) {
        std::vector<float> out(n);
        cl().queue().enqueueReadBuffer(b, CL_TRUE, 0, n * sizeof(float), out.data());
        return out;
    }
    /// h, Dx, Dy of a cascade on the Lagrangian grid, metres.
    std::vector<float> lagrangian(const OceanField& o, int c = 0) {
        return read(o.cascade(c).lagrangian, 3 * size_t(o.config().size) * o.config().size);
    }
    std::vector<float> plane(const cl::Buffer& b, const OceanField& o) {
        return read(b, size_t(o.config().size) * o.config().size);
    }
};

/// One cascade, deep water, a JONSWAP wind sea: the default for the tests that need a sea.
OceanConfig oneCascade(int size, float patch, float choppiness = 1.0f) {
    return {.size = size, .cascades = 1, .patchMeters = patch, .choppiness = choppiness};
}

// The device transforms only the kx >= 0 half of the spectrum, trusting h(-k) = conj(h(k)); the
// direct DFT sums every mode, so it checks that symmetry (its imaginary part must vanish) and the
// half transform together, for the heights and both displacements.
TEST_F(Ocean, FftMatchesDirectDftForHeightAndDisplacement) {
    constexpr int N = 16;
    OceanConfig config = oneCascade(N, 20.0f);
    config.sea.wind.windSpeed = 3.0f; // a short peak, so the 16-texel patch holds waves
    OceanField ocean(cl(), config);
    ocean.setTime(3.7);
    const auto fields = lagrangian(ocean);
    const OceanCascade& c = ocean.cascade(0);
    const double t = std::fmod(3.7, double(config.repeatSeconds));
    double maxDiff = 0, maxValue = 0, maxImag = 0;
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            std::complex<double> sum[3];
            for (int ky = 0; ky < N; ++ky)
                for (int kx = 0; kx < N; ++kx) {
                    const int k = ky * N + kx, mk = ((N - ky) % N) * N + (N - kx) % N;
                    const double phase = -double(c.omega[k]) * t;
                    const std::complex<double> mode = std::complex<double>(c.h0[k]) * std::polar(1.0, phase) +
                                                      std::conj(std::complex<double>(c.h0[mk])) * std::polar(1.0, -phase);
                    double wx, wy;
                    OceanField::waveVector(kx, ky, N, c.patchMeters, wx, wy);
                    const double len = std::hypot(wx, wy);
                    const std::complex<double> i(0.0, 1.0), e = std::polar(1.0, kTwoPi * (double(kx) * x + double(ky) * y) / N);
                    sum[0] += mode * e;
                    if (len > 0) {
                        sum[1] += i * (wx / len) * mode * e;
                        sum[2] += i * (wy / len) * mode * e;
                    }
                }
            for (int f = 0; f < 3; ++f) {
                maxDiff = std::max(maxDiff, std::abs(sum[f].real() - double(fields[size_t(f) * N * N + y * N + x])));
                maxImag = std::max(maxImag, std::abs(sum[f].imag()));
                maxValue = std::max(maxValue, std::abs(sum[f]));
            }
        }
    ASSERT_GT(maxValue, 0.0);
    EXPECT_LT(maxDiff, 1e-5 * maxValue);
    EXPECT_LT(maxImag, 1e-9 * maxValue) << "a field is not real: the spectrum is not Hermitian";
}

/// Every mode zero but one, h0 at index (mx, my): h = A cos(k.x0 - w t + phi) with A = 2 |h0|.
std::vector<std::complex<float>> singleMode(int N, int mx, int my, float amplitude) {
    std::vector<std::complex<float>> h0(size_t(N) * N, 0.0f);
    h0[size_t(my) * N + size_t(mx)] = {amplitude / 2.0f, 0.0f};
    return h0;
}

TEST_F(Ocean, OneModeIsTheGerstnerWave) {
    // The trochoid: x = x0 - lambda k^ A sin(theta), z = A cos(theta), J = 1 - lambda k A cos(theta),
    // with theta = k.x0 - w t. Two cycles along x and one along y over 256 texels, lambda k A = 0.6.
    constexpr int N = 256;
    constexpr float L = 200.0f, lambda = 0.8f;
    OceanField ocean(cl(), oneCascade(N, L, lambda));
    const double kx = kTwoPi * 2 / L, ky = kTwoPi * 1 / L, k = std::hypot(kx, ky);
    const double A = 0.75 / (lambda * k);
    ocean.setAmplitudes(0, singleMode(N, 2, 1, float(A)));
    ocean.setTime(2.5);
    const double w = ocean.cascade(0).omega[size_t(1) * N + 2], t = 2.5;
    const auto f = lagrangian(ocean);
    const auto J = plane(ocean.cascade(0).jacobian, ocean);
    const double dx = L / N;
    double position = 0, height = 0, jacobian = 0, normal = 0;
    auto at = [&](int field, int i, int j) { return double(f[size_t(field) * N * N + size_t((j + N) % N) * N + (i + N) % N]); };
    for (int j = 0; j < N; j += 3)
        for (int i = 0; i < N; i += 3) {
            const double theta = kx * i * dx + ky * j * dx - w * t;
            // Positions: the displacement and the height.
            position = std::max({position, std::abs(at(1, i, j) - (-(kx / k) * A * std::sin(theta))),
                                 std::abs(at(2, i, j) - (-(ky / k) * A * std::sin(theta)))});
            height = std::max(height, std::abs(at(0, i, j) - A * std::cos(theta)));
            jacobian = std::max(jacobian, std::abs(J[size_t(j) * N + i] - (1.0 - lambda * k * A * std::cos(theta))));
            // The normal of the displaced surface, from its tangents along x0 and y0 (fourth-order
            // differences of the device's fields), against the trochoid's.
            auto d = [&](int field, int di, int dj) {
                return (8.0 * (at(field, i + di, j + dj) - at(field, i - di, j - dj)) -
                        (at(field, i + 2 * di, j + 2 * dj) - at(field, i - 2 * di, j - 2 * dj))) / (12.0 * dx);
            };
            const glm::dvec3 tx(1.0 + lambda * d(1, 1, 0), lambda * d(2, 1, 0), d(0, 1, 0));
            const glm::dvec3 ty(lambda * d(1, 0, 1), 1.0 + lambda * d(2, 0, 1), d(0, 0, 1));
            const glm::dvec3 n = glm::normalize(glm::cross(tx, ty));
            // Analytic: along k the profile (x, z)(theta) has slope dz/dx = -k A sin / J; across it, flat.
            const double Jt = 1.0 - lambda * k * A * std::cos(theta), s = -k * A * std::sin(theta) / Jt;
            const glm::dvec3 expected = glm::normalize(glm::dvec3(-s * kx / k, -s * ky / k, 1.0));
            normal = std::max(normal, glm::length(n - expected));
        }
    EXPECT_LT(position, 1e-4 * A) << "metres, of amplitude " << A;
    EXPECT_LT(height, 1e-4 * A);
    EXPECT_LT(jacobian, 1e-4) << "J = 1 - lambda k A cos(theta)";
    EXPECT_LT(normal, 1e-4) << "radians";

    // The Eulerian field the renderer traces: the trochoid's height over the undisplaced grid,
    // found by Newton steps on the bilinearly sampled fields: within 1e-3 of the amplitude (the
    // bilinear interpolation of a 100-texel wave).
    const auto eulerian = plane(ocean.cascade(0).meters, ocean);
    double worst = 0;
    for (int j = 0; j < N; j += 5)
        for (int i = 0; i < N; i += 5) {
            // Solve x = x0 - lambda k^ A sin(theta(x0)) along k in double (Newton).
            const double s = (kx * i * dx + ky * j * dx) / k; // position along k
            double s0 = s;
            for (int it = 0; it < 40; ++it) {
                const double th = k * s0 - w * t;
                s0 -= (s0 - lambda * A * std::sin(th) - s) / (1.0 - lambda * k * A * std::cos(th));
            }
            worst = std::max(worst, std::abs(eulerian[size_t(j) * N + i] - A * std::cos(k * s0 - w * t)));
        }
    EXPECT_LT(worst, 1e-3 * A);
}

TEST_F(Ocean, CascadesShareTheSpectrumWithoutOverlapAndTheirVariancesAddUp) {
    struct Case {
        const char* name;
        SeaState sea;
    };
    SeaState swell{.wind = {.shape = SpectrumShape::PiersonMoskowitz, .windSpeed = 18.0f}};
    swell.swell.energy = 0.5f;
    for (const Case& c : {Case{"jonswap 10 m/s", {.wind = {.windSpeed = 10.0f}}},
                          Case{"pm 18 m/s + swell", swell},
                          Case{"tma 8 m/s, 15 m deep", {.wind = {.shape = SpectrumShape::Tma, .windSpeed = 8.0f, .spreading = Spreading::Hasselmann}, .depthMeters = 15.0f}}}) {
        OceanField ocean(cl(), {.size = 256, .cascades = 4, .sea = c.sea});
        double sum = 0;
        for (int i = 0; i < ocean.cascadeCount(); ++i) {
            const OceanCascade& k = ocean.cascade(i);
            sum += double(k.sigma) * k.sigma;
            if (i > 0) {
                EXPECT_EQ(k.kMin, ocean.cascade(i - 1).kMax) << c.name << ": bands overlap or leave a gap";
                EXPECT_GT(std::remainder(ocean.cascade(i - 1).patchMeters / k.patchMeters, 1.0), 0.1)
                    << "lengths in a whole ratio repeat together";
            }
        }
        const double truth = c.sea.variance(1e-6, ocean.cascade(ocean.cascadeCount() - 1).kMax);
        EXPECT_NEAR(sum, truth, 0.01 * truth) << c.name << ": Parseval";
    }
}

TEST_F(Ocean, FullyDevelopedPiersonMoskowitzSeaHasItsSignificantWaveHeight) {
    for (float u10 : {6.0f, 12.0f}) {
        OceanField ocean(cl(), {.size = 256, .cascades = 4, .sea = {.wind = {.shape = SpectrumShape::PiersonMoskowitz, .windSpeed = u10}}});
        const double u = 1.026 * u10, hs = 4.0 * ocean.sigmaMeters();
        EXPECT_NEAR(hs, 0.21 * u * u / kGravity, 0.05 * 0.21 * u * u / kGravity) << u10 << " m/s";
    }
}

TEST_F(Ocean, TimeIsAPureInputTheFieldIsBitForBitTheSame) {
    OceanConfig config{.size = 64, .cascades = 1, .seed = 42};
    OceanField a(cl(), config), b(cl(), config), jump(cl(), config);
    for (int i = 0; i < 17; ++i) {
        a.step(1.0 / 30.0);
        b.step(1.0 / 30.0);
    }
    jump.setTime(a.time());
    auto fields = [&](const OceanField& o) {
        std::vector<float> all = lagrangian(o);
        const auto h = plane(o.cascade(0).height, o);
        all.insert(all.end(), h.begin(), h.end());
        return all;
    };
    EXPECT_EQ(fields(a), fields(b)) << "two runs";
    EXPECT_EQ(fields(a), fields(jump)) << "a jump straight to t";
    OceanConfig other = config;
    other.seed = 43;
    OceanField c(cl(), other);
    c.setTime(a.time());
    EXPECT_NE(fields(a), fields(c)) << "another seed, the same sea";
}

TEST_F(Ocean, FoamAppearsWhereJFallsBelowTheThresholdAndHalvesInItsHalfLife) {
    // One mode at lambda k A = 0.8 with threshold 0.5: J < 0.5 where cos(theta) > 0.625, a
    // fraction acos(0.625) / pi of the phase. The mode runs 3 cycles along x and 2 along y, so
    // the Lagrangian grid samples the phase evenly. What is injected is young; the young part
    // halves in its own half-life (a third of the foam's here) and never exceeds the foam.
    constexpr int N = 256;
    constexpr float L = 256.0f, lambda = 1.0f;
    OceanConfig config = oneCascade(N, L, lambda);
    config.foam = {
        .threshold = 0.5f, .injection = 1.0f, .halfLife = 1.5f, .youngHalfLife = 0.5f, .drift = 0.0f};
    OceanField ocean(cl(), config);
    const double k = kTwoPi * std::hypot(3.0, 2.0) / L, A = 0.8 / (lambda * k);
    ocean.setAmplitudes(0, singleMode(N, 3, 2, float(A)));
    ocean.setTime(0.0); // the foam restarts clear
    ocean.step(0.02);
    auto foam = [&] { return plane(ocean.foam(0), ocean); };
    const auto injected = foam();
    const double covered = double(std::count_if(injected.begin(), injected.end(), [](float f) { return f > 0.0f; })) / (N * N);
    const double analytic = std::acos(0.625) / std::numbers::pi;
    EXPECT_NEAR(covered, analytic, 0.01 * analytic);
    auto young = [&] { return plane(ocean.youngFoam(0), ocean); };
    EXPECT_EQ(young(), injected) << "all of a first step's foam is young";

    // Foam everywhere the crest passed, then no more waves: nothing is injected, the foam only
    // decays (no drift here). One half-life in 30 steps.
    for (int i = 0; i < 40; ++i) ocean.step(0.05);
    ocean.setAmplitudes(0, std::vector<std::complex<float>>(size_t(N) * N, 0.0f));
    auto total = [&](const std::vector<float>& field) {
        double s = 0;
        for (float f : field) s += f;
        return s;
    };
    const double start = total(foam()), youngStart = total(young());
    ASSERT_GT(start, 100.0);
    ASSERT_GT(youngStart, 10.0);
    for (int i = 0; i < 30; ++i) ocean.step(1.5 / 30.0);
    const auto aged = foam(), agedYoung = young();
    EXPECT_NEAR(total(aged) / start, 0.5, 0.02 * 0.5) << "after one half-life";
    EXPECT_NEAR(total(agedYoung) / youngStart, 0.125, 0.02 * 0.125)
        << "after three of the young foam's";
    for (size_t i = 0; i < aged.size(); ++i) ASSERT_LE(agedYoung[i], aged[i]) << "texel " << i;
}

TEST_F(Ocean, SettledFoamIsTheHistoryTheSeaWouldHaveAndTheFieldsStayAsTheyWere) {
    // settleFoam(5) at t = 10 is the same foam, bit for bit, as a sea set to t = 5 and stepped
    // there in quarter seconds; its fields are those of t = 10 itself (a function of t alone).
    const OceanConfig config{.size = 256, .cascades = 2, .sea = {.wind = {.windSpeed = 18.0f}}};
    OceanField settled(cl(), config), stepped(cl(), config), plain(cl(), config);
    settled.setTime(10.0);
    settled.settleFoam(5.0);
    stepped.setTime(5.0);
    for (int i = 0; i < 20; ++i) stepped.step(0.25);
    plain.setTime(10.0);
    EXPECT_EQ(settled.time(), 10.0);
    for (int c = 0; c < 2; ++c) {
        const auto foam = plane(settled.foam(c), settled);
        EXPECT_EQ(foam, plane(stepped.foam(c), stepped)) << "cascade " << c;
        EXPECT_GT(*std::max_element(foam.begin(), foam.end()), 0.5f) << "a storm's foam, cascade " << c;
        EXPECT_EQ(plane(settled.cascade(c).height, settled), plane(plain.cascade(c).height, plain)) << "cascade " << c;
    }
    EXPECT_THROW(settled.settleFoam(-1.0), Error);
    EXPECT_THROW(settled.settleFoam(5.0, 0.0), Error);
}

TEST_F(Ocean, AutomaticFoamCoversWhatMonahansLawGives) {
    // J - 1 is nearly Gaussian on a sea of many modes, so thresholds set from its spectral
    // variance leave Monahan's whitecap fraction W(U10) below them: measured over the cascades,
    // one step after a clear start (the injected area), within a quarter of W.
    for (float u10 : {10.0f, 16.0f}) {
        OceanField ocean(cl(), {.size = 256, .cascades = 3, .sea = {.wind = {.windSpeed = u10}}});
        ocean.setTime(1.0);
        ocean.step(0.01);
        double covered = 0;
        for (int c = 0; c < ocean.cascadeCount(); ++c) {
            const auto f = plane(ocean.foam(c), ocean);
            covered += double(std::count_if(f.begin(), f.end(), [](float x) { return x > 0.0f; })) / f.size();
        }
        const double w = OceanField::whitecapCoverage(u10);
        EXPECT_NEAR(covered, w, 0.25 * w) << u10 << " m/s";
    }
    EXPECT_NEAR(OceanField::whitecapCoverage(10.0), 3.84e-6 * std::pow(10.0, 3.41), 1e-12);
}

TEST_F(Ocean, SingleWaveMovesAtThePhaseSpeed) {
    // One mode along +x, n = 4 cycles over the patch: the height 2 a cos(k x - w t) travels
    // along +x at w / k, with w = sqrt(g k) rounded down to a multiple of 2 pi / T.
    constexpr int N = 64;
    OceanConfig config = oneCascade(N, 64.0f, 0.0f);
    config.repeatSeconds = 1000.0f;
    OceanField ocean(cl(), config);
    ocean.setAmplitudes(0, singleMode(N, 4, 0, 1.0f));
    const double k = kTwoPi * 4 / 64.0;
    const double omega = ocean.cascade(0).omega[4];
    EXPECT_NEAR(omega, std::sqrt(9.81 * k), kTwoPi / config.repeatSeconds); // quantised down
    auto crestPhase = [&] {
        const auto f = plane(ocean.cascade(0).meters, ocean);
        double c = 0, s = 0;
        for (int x = 0; x < N; ++x) {
            c += f[x] * std::cos(kTwoPi * 4 * x / N);
            s += f[x] * std::sin(kTwoPi * 4 * x / N);
        }
        return std::atan2(s, c); // the crest's phase k x_crest, = w t for cos(k x - w t)
    };
    ocean.setTime(0.0);
    const double p0 = crestPhase();
    ocean.setTime(0.2);
    const double dPhase = std::remainder(crestPhase() - p0, kTwoPi);
    EXPECT_GT(dPhase, 0.0) << "the wave travels against its wave vector";
    EXPECT_NEAR(dPhase / k / 0.2, omega / k, 1e-3 * omega / k);
    EXPECT_NEAR(omega / k, std::sqrt(9.81 / k), 0.01 * std::sqrt(9.81 / k));
}

TEST_F(Ocean, EulerianFieldTilesAndTheAnimationLoops) {
    OceanConfig config{.size = 128, .cascades = 2, .cascadeRatio = 2.6f, .repeatSeconds = 50.0f};
    config.sea.wind.windSpeed = 14.0f;
    OceanField ocean(cl(), config);
    for (int c = 0; c < ocean.cascadeCount(); ++c) {
        const auto h = plane(ocean.cascade(c).height, ocean);
        const int N = 128;
        double interior = 0, seam = 0;
        for (int a = 0; a < N; ++a) {
            for (int b = 0; b + 1 < N; ++b) {
                interior = std::max(interior, double(std::abs(h[a * N + b + 1] - h[a * N + b])));
                interior = std::max(interior, double(std::abs(h[(b + 1) * N + a] - h[b * N + a])));
            }
            seam = std::max(seam, double(std::abs(h[a * N] - h[a * N + N - 1])));
            seam = std::max(seam, double(std::abs(h[a] - h[(N - 1) * N + a])));
        }
        EXPECT_LE(seam, interior * 1.05) << "cascade " << c;
    }
    ocean.setTime(3.0);
    const auto a = plane(ocean.cascade(0).meters, ocean);
    ocean.setTime(53.0);
    const auto b = plane(ocean.cascade(0).meters, ocean);
    ocean.setTime(4.0);
    const auto c = plane(ocean.cascade(0).meters, ocean);
    double same = 0, moved = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        same = std::max(same, double(std::abs(a[i] - b[i])));
        moved = std::max(moved, double(std::abs(a[i] - c[i])));
    }
    EXPECT_LT(same, 1e-4 * ocean.sigmaMeters());
    EXPECT_GT(moved, 0.01 * ocean.sigmaMeters());
}

// A wind change blends the spectra (hfx_ocean_blend: energy mixed linearly, each k's phase
// kept): mid-blend the field is that of the blended amplitudes and its variance the mean of the
// two seas', with no dip; at the end it is the new sea. A sea that turns 90 degrees over 10 s
// changes no faster per frame than a steady sea does by itself (its waves moving), where an
// immediate change jumps.
TEST_F(Ocean, WindChangesBlendWithoutAJump) {
    OceanConfig before = oneCascade(64, 200.0f, 1.0f);
    before.sea.wind.windSpeed = 12.0f;
    OceanConfig after = before;
    after.sea.wind.direction = float(std::numbers::pi / 2);
    const double dt = 1.0 / 30.0;
    auto heights = [&](const OceanField& o) {
        auto l = lagrangian(o);
        l.resize(size_t(64) * 64);
        return l;
    };
    auto maxDiff = [](const std::vector<float>& a, const std::vector<float>& b) {
        double m = 0;
        for (size_t i = 0; i < a.size(); ++i) m = std::max(m, double(std::abs(a[i] - b[i])));
        return m;
    };
    // How much a steady sea changes in a frame, either wind.
    double steady = 0;
    for (const OceanConfig& c : {before, after}) {
        OceanField o(cl(), c);
        o.setTime(1.0);
        for (int i = 0; i < 30; ++i) {
            const auto a = heights(o);
            o.step(dt);
            steady = std::max(steady, maxDiff(a, heights(o)));
        }
    }

    OceanField turning(cl(), before);
    turning.setTime(1.0);
    turning.setWind(after.sea.wind.windSpeed, after.sea.wind.direction, 10.0);
    double worst = 0;
    auto last = heights(turning);
    for (int i = 0; i < 150; ++i) { // to t = 6: s = smoothstep(0.5) = 0.5
        turning.step(dt);
        auto now = heights(turning);
        worst = std::max(worst, maxDiff(last, now));
        last = std::move(now);
    }
    EXPECT_NEAR(turning.windBlend().at(turning.time()), 0.5, 1e-6);
    OceanField from(cl(), before), to(cl(), after), mixed(cl(), before);
    std::vector<std::complex<float>> half(to.cascade(0).h0.size());
    for (size_t k = 0; k < half.size(); ++k) {
        const std::complex<float> a = from.cascade(0).h0[k], b = to.cascade(0).h0[k];
        const double energy = 0.5 * (std::norm(a) + std::norm(b));
        const std::complex<float> m = 0.5f * (a + b);
        half[k] = std::abs(m) > 0.0f ? m * float(std::sqrt(energy) / std::abs(m)) : 0.0f;
    }
    mixed.setAmplitudes(0, half);
    for (OceanField* o : {&from, &to, &mixed}) o->setTime(turning.time());
    const double sigma = to.sigmaMeters();
    EXPECT_LT(maxDiff(last, heights(mixed)), 1e-3 * sigma) << "mid-blend is the sea of the blended spectrum";
    const double meanVariance = 0.5 * (std::pow(from.sigmaMeters(), 2) + std::pow(to.sigmaMeters(), 2));
    EXPECT_NEAR(turning.sigmaMeters(), std::sqrt(meanVariance), 1e-4 * sigma) << "the sea keeps its height";
    double sum = 0, sum2 = 0;
    for (float v : last) sum += v, sum2 += double(v) * v;
    const double mean = sum / double(last.size()), realised = std::sqrt(sum2 / double(last.size()) - mean * mean);
    EXPECT_NEAR(realised, turning.sigmaMeters(), 0.1 * sigma) << "and the field shows it";
    for (int i = 0; i < 160; ++i) {
        turning.step(dt);
        auto now = heights(turning);
        worst = std::max(worst, maxDiff(last, now));
        last = std::move(now);
    }
    EXPECT_LE(worst, 1.5 * steady) << "a frame of the blend changes the sea at most 1.5 times a steady frame";
    to.setTime(turning.time());
    EXPECT_LT(maxDiff(last, heights(to)), 1e-3 * sigma) << "after the blend it is the new sea";

    OceanField cut(cl(), before);
    cut.setTime(1.0);
    const auto a = heights(cut);
    cut.setWind(after.sea.wind.windSpeed, after.sea.wind.direction);
    EXPECT_GT(maxDiff(a, heights(cut)), 5.0 * steady) << "an immediate change is a jump";
    EXPECT_THROW(cut.setWind(10.0f, 0.0f, -1.0), Error);
    EXPECT_THROW(cut.setWind(10.0f, 0.0f, std::nan("")), Error);
}

TEST_F(Ocean, BadConfigurationIsRefusedByName) {
    EXPECT_NE(messageOf([&] { OceanField(cl(), {.size = 100}); }).find("size"), std::string::npos);
    EXPECT_NE(messageOf([&] { OceanField(cl(), {.cascades = 5}); }).find("cascades"), std::string::npos);
    EXPECT_NE(messageOf([&] { OceanField(cl(), {.size = 64, .cascades = 2}); }).find("cascadeRatio"), std::string::npos);
    EXPECT_NE(messageOf([&] { OceanField(cl(), {.sea = {.wind = {.windSpeed = 0.0f}}}); }).find("windSpeed"), std::string::npos);
    EXPECT_NE(messageOf([&] { OceanField(cl(), {.choppiness = -1.0f}); }).find("choppiness"), std::string::npos);
    EXPECT_NE(messageOf([&] { OceanField(cl(), {.foam = {.halfLife = 0.0f}}); }).find("halfLife"), std::string::npos);
    const std::string young =
        messageOf([&] { OceanField(cl(), {.foam = {.youngHalfLife = -1.0f}}); });
    EXPECT_NE(young.find("youngHalfLife"), std::string::npos);
    OceanField ocean(cl(), {.size = 16, .cascades = 1});
    EXPECT_THROW(ocean.setAmplitudes(0, std::vector<std::complex<float>>(5)), Error);
    EXPECT_THROW(ocean.setAmplitudes(1, std::vector<std::complex<float>>(256)), Error);
    EXPECT_THROW(ocean.step(-0.1), Error);
    EXPECT_THROW(ocean.setWind(-3.0f, 0.0f), Error);
}

} // namespace
} // namespace hfx::test
