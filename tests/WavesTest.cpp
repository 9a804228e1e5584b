// The waves kernel against the plain C++ reference of the same formula (WavesMath.h) and,
// for a single plain sine, against the closed form.

#include "support/Fixtures.h"
#include "support/References.h"

#include "hfx/compute/WaveField.h"
#include "hfx/compute/shared/WavesMath.h"
#include "hfx/core/Error.h"

#include <cmath>
#include <numbers>

namespace hfx::test {
namespace {

class Waves : public ClTest {
protected:
    std::vector<float> read(const WaveField& field) {
        std::vector<float> out(size_t(field.size()) * field.size());
        cl().queue().enqueueReadBuffer(field.buffer(), CL_TRUE, 0, out.size() * sizeof(float),
                                       out.data());
        return out;
    }
};

TEST_F(Waves, KernelMatchesCppReference) {
    const WaveConfig config{.size = 96, .waveCount = 16, .steepness = 0.25f, .seed = 7};
    WaveField field(cl(), config);
    for (double t : {0.0, 1.25, 3600.5}) { // an hour in: phases stay exact
        field.setTime(t);
        const auto gpu = read(field);
        const auto cpu = wavesReference(config, t);
        double maxDiff = 0;
        float lo = 1, hi = 0;
        for (size_t i = 0; i < gpu.size(); ++i) {
            maxDiff = std::max(maxDiff, double(std::abs(gpu[i] - cpu[i])));
            lo = std::min(lo, gpu[i]);
            hi = std::max(hi, gpu[i]);
        }
        // Float rounding of the tabulated angles and the sum of 16 terms against double.
        EXPECT_LT(maxDiff, 1e-5) << "t = " << t;
        EXPECT_GE(lo, 0.0f);
        EXPECT_LE(hi, 1.0f);
        EXPECT_GT(hi - lo, 0.2f) << "field is nearly flat at t = " << t;
    }
}

TEST_F(Waves, SingleSineMovesAtThePhaseSpeed) {
    // One plain sine (steepness 0): h = 0.5 + 0.5 sin(2 pi (m u + n v) + phi0 - omega t),
    // omega = sqrt(g k) with k = 2 pi |(m, n)| / patch.
    const WaveConfig config{.size = 64, .waveCount = 1, .patchMeters = 50.0f, .spread = 0.0f,
                            .minCycles = 3, .maxCycles = 3, .steepness = 0.0f, .seed = 3};
    WaveField field(cl(), config);
    const Wave w = field.waves().at(0);
    const double k = 2 * std::numbers::pi * std::hypot(w.m, w.n) / config.patchMeters;
    EXPECT_NEAR(w.omega, std::sqrt(9.81 * k), 1e-5);
    for (double t : {0.0, 0.7, 12.3}) {
        field.setTime(t);
        const auto gpu = read(field);
        double maxDiff = 0;
        for (int y = 0; y < config.size; ++y)
            for (int x = 0; x < config.size; ++x) {
                const double u = (x + 0.5) / config.size, v = (y + 0.5) / config.size;
                const double truth =
                    0.5 + 0.5 * std::sin(2 * std::numbers::pi * (w.m * u + w.n * v) + w.phase - w.omega * t);
                maxDiff = std::max(maxDiff, std::abs(gpu[y * config.size + x] - truth));
            }
        EXPECT_LT(maxDiff, 2e-6) << "t = " << t;
    }
}

TEST_F(Waves, FieldTilesAndChangesOverTime) {
    const WaveConfig config{.size = 64, .waveCount = 12};
    WaveField field(cl(), config);
    const auto first = read(field);
    // Tiling: every wave has whole cycles across the patch, so stepping across the edge (last
    // column to first, last row to first) changes the field no more than any interior step.
    for (const Wave& w : field.waves()) {
        EXPECT_EQ(w.m, std::round(w.m));
        EXPECT_EQ(w.n, std::round(w.n));
    }
    const int N = config.size;
    double interior = 0, seam = 0;
    for (int a = 0; a < N; ++a) {
        for (int b = 0; b + 1 < N; ++b) {
            interior = std::max(interior, double(std::abs(first[a * N + b + 1] - first[a * N + b])));
            interior = std::max(interior, double(std::abs(first[(b + 1) * N + a] - first[b * N + a])));
        }
        seam = std::max(seam, double(std::abs(first[a * N] - first[a * N + N - 1])));
        seam = std::max(seam, double(std::abs(first[a] - first[(N - 1) * N + a])));
    }
    EXPECT_LE(seam, interior * 1.05) << "the patch has a seam at its edges";
    field.step(0.1);
    const auto second = read(field);
    double change = 0;
    for (size_t i = 0; i < first.size(); ++i) change = std::max(change, double(std::abs(first[i] - second[i])));
    EXPECT_GT(change, 0.01) << "the field did not move in 0.1 s";
}

TEST_F(Waves, BadConfigurationNamesTheField) {
    auto message = [&](const WaveConfig& c) {
        try {
            WaveField field(cl(), c);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message({.size = 0}).find("WaveConfig.size"), std::string::npos);
    EXPECT_NE(message({.waveCount = 0}).find("WaveConfig.waveCount"), std::string::npos);
    EXPECT_NE(message({.steepness = 0.3f}).find("WaveConfig.steepness"), std::string::npos);
    EXPECT_NE(message({.patchMeters = NAN}).find("WaveConfig.patchMeters"), std::string::npos);
    WaveField field(cl(), {.size = 16, .maxCycles = 8});
    EXPECT_THROW(field.step(0.0), Error);
    EXPECT_THROW(field.step(-1.0), Error);
    EXPECT_THROW(field.step(INFINITY), Error);
    EXPECT_EQ(field.time(), 0.0); // a refused step changes nothing
}

} // namespace
} // namespace hfx::test
