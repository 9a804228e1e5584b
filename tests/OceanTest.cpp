// The FFT ocean against a direct DFT, its Hermitian symmetry, tiling, and the phase speed that
// the dispersion relation gives.

#include "support/Fixtures.h"

#include "hfx/compute/OceanField.h"
#include "hfx/core/Error.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace hfx::test {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

class Ocean : public ClTest {
protected:
    std::vector<float> readField(const OceanField& ocean) {
        std::vector<float> out(size_t(ocean.width()) * ocean.height());
        cl().queue().enqueueReadBuffer(ocean.rawHeight(), CL_TRUE, 0, out.size() * sizeof(float), out.data());
        return out;
    }
    std::vector<float> readHeight(const OceanField& ocean) {
        std::vector<float> out(size_t(ocean.width()) * ocean.height());
        cl().queue().enqueueReadBuffer(ocean.buffer(), CL_TRUE, 0, out.size() * sizeof(float), out.data());
        return out;
    }
};

TEST_F(Ocean, HeightsFillTheUnitRangeWithoutClipping) {
    for (OceanSpectrum spectrum : {OceanSpectrum::Phillips, OceanSpectrum::Jonswap}) {
        OceanField ocean(cl(), {.size = 128, .spectrum = spectrum});
        ocean.setTime(17.3);
        const auto field = readField(ocean);
        const auto [lo, hi] = std::minmax_element(field.begin(), field.end());
        ASSERT_GT(*hi - *lo, 0.0f) << "spectrum " << int(spectrum);
        // About 99.99% of a Gaussian sea lies within 4 sigma, so the stored heights fill [0,1]
        // without clipping much.
        const auto h = readHeight(ocean);
        size_t clipped = 0;
        for (float x : h) clipped += x == 0.0f || x == 1.0f;
        EXPECT_LT(clipped, h.size() / 1000);
    }
}

// The device transforms only the kx >= 0 half of the spectrum, trusting h(-k) = conj(h(k)); the
// direct DFT sums every mode, so it checks that symmetry (its imaginary part must vanish) and the
// half transform together.
TEST_F(Ocean, FftMatchesDirectDft) {
    constexpr int N = 16;
    OceanField ocean(cl(), {.size = N, .patchMeters = 20.0f});
    ocean.setTime(3.7);
    const auto field = readField(ocean);
    const auto& h0 = ocean.amplitudes();
    const auto& omega = ocean.frequencies();
    const double t = std::fmod(3.7, double(ocean.config().repeatSeconds));
    double maxDiff = 0, maxValue = 0, maxImag = 0;
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            std::complex<double> sum = 0;
            for (int ky = 0; ky < N; ++ky)
                for (int kx = 0; kx < N; ++kx) {
                    const int k = ky * N + kx, mk = ((N - ky) % N) * N + (N - kx) % N;
                    const double phase = -double(omega[k]) * t;
                    const std::complex<double> mode = std::complex<double>(h0[k]) * std::polar(1.0, phase) +
                                                      std::conj(std::complex<double>(h0[mk])) * std::polar(1.0, -phase);
                    sum += mode * std::polar(1.0, kTwoPi * (double(kx) * x + double(ky) * y) / N);
                }
            maxDiff = std::max(maxDiff, std::abs(sum.real() - double(field[y * N + x])));
            maxImag = std::max(maxImag, std::abs(sum.imag()));
            maxValue = std::max(maxValue, std::abs(sum));
        }
    EXPECT_LT(maxDiff, 1e-5 * maxValue);
    EXPECT_LT(maxImag, 1e-9 * maxValue) << "the spectrum is not Hermitian: the height would not be real";
}

TEST_F(Ocean, SingleWaveMovesAtThePhaseSpeed) {
    // One mode along +x, n = 4 cycles over the patch: the height 2 a cos(k x - w t) travels
    // along +x at w / k, with w = sqrt(g k) rounded down to a multiple of 2 pi / T.
    constexpr int N = 64;
    const OceanConfig config{.size = N, .patchMeters = 64.0f, .repeatSeconds = 1000.0f};
    OceanField ocean(cl(), config);
    std::vector<std::complex<float>> h0(N * N, 0.0f);
    h0[4] = {0.5f, 0.0f};
    ocean.setAmplitudes(h0);
    const double k = kTwoPi * 4 / config.patchMeters;
    const double omega = ocean.frequencies()[4];
    EXPECT_NEAR(omega, std::sqrt(9.81 * k), kTwoPi / config.repeatSeconds); // quantised down
    auto crestPhase = [&] {
        // Phase of the n = 4 Fourier component along a row: atan2 of the projections.
        const auto f = readField(ocean);
        double c = 0, s = 0;
        for (int x = 0; x < N; ++x) {
            c += f[x] * std::cos(kTwoPi * 4 * x / N);
            s += f[x] * std::sin(kTwoPi * 4 * x / N);
        }
        return std::atan2(s, c); // the crest's phase k x_crest, = w t for cos(k x - w t)
    };
    ocean.setTime(0.0);
    const double p0 = crestPhase();
    const double dt = 0.2;
    ocean.setTime(dt);
    const double p1 = crestPhase();
    const double dPhase = std::remainder(p1 - p0, kTwoPi);
    EXPECT_GT(dPhase, 0.0) << "the wave travels against its wave vector";
    const double speed = dPhase / k / dt; // the crest moved dPhase / k metres in dt
    EXPECT_NEAR(speed, omega / k, 1e-3 * omega / k);
    EXPECT_NEAR(omega / k, std::sqrt(9.81 / k), 0.01 * std::sqrt(9.81 / k));
}

TEST_F(Ocean, PatchTiles) {
    constexpr int N = 128;
    OceanField ocean(cl(), {.size = N});
    const auto h = readHeight(ocean);
    double interior = 0, seam = 0;
    for (int a = 0; a < N; ++a) {
        for (int b = 0; b + 1 < N; ++b) {
            interior = std::max(interior, double(std::abs(h[a * N + b + 1] - h[a * N + b])));
            interior = std::max(interior, double(std::abs(h[(b + 1) * N + a] - h[b * N + a])));
        }
        seam = std::max(seam, double(std::abs(h[a * N] - h[a * N + N - 1])));
        seam = std::max(seam, double(std::abs(h[a] - h[(N - 1) * N + a])));
    }
    EXPECT_LE(seam, interior * 1.05);
}

TEST_F(Ocean, AnimationLoopsAtTheRepeatPeriod) {
    OceanField ocean(cl(), {.size = 32, .repeatSeconds = 50.0f});
    ocean.setTime(3.0);
    const auto a = readHeight(ocean);
    ocean.setTime(53.0);
    const auto b = readHeight(ocean);
    ocean.setTime(4.0);
    const auto c = readHeight(ocean);
    double same = 0, moved = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        same = std::max(same, double(std::abs(a[i] - b[i])));
        moved = std::max(moved, double(std::abs(a[i] - c[i])));
    }
    EXPECT_LT(same, 1e-5);
    EXPECT_GT(moved, 0.01);
}

TEST_F(Ocean, BadConfigurationIsRefused) {
    EXPECT_THROW(OceanField(cl(), {.size = 100}), Error);
    EXPECT_THROW(OceanField(cl(), {.windSpeed = 0.0f}), Error);
    EXPECT_THROW(OceanField(cl(), {.fetchKm = -1.0f}), Error);
    OceanField ocean(cl(), {.size = 16});
    EXPECT_THROW(ocean.setAmplitudes(std::vector<std::complex<float>>(5)), Error);
    EXPECT_THROW(ocean.step(-0.1), Error);
}

} // namespace
} // namespace hfx::test
