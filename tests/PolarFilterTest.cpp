// The polar filter of a longitude-latitude field (PolarFilter): the kernels against the filter
// in double precision on the host, each row's mean kept, the rows whose box is a texel or less
// copied bit for bit, a zonal wave damped as a box of the row's width damps it, the rows at the
// poles flattened to their mean, and bad sizes and smoothings refused by name.

#include "support/Fixtures.h"

#include "hfx/compute/PolarFilter.h"
#include "hfx/core/Random.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace hfx::test {
namespace {

class Polar : public ClTest {
protected:
    std::vector<float> filter(const std::vector<float>& field, int width, int height, float smoothing) {
        PolarFilter polar(cl(), width, height, smoothing);
        return filter(polar, field);
    }
    std::vector<float> filter(PolarFilter& polar, const std::vector<float>& field) {
        cl::Buffer in(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, field.size() * sizeof(float),
                      const_cast<float*>(field.data()));
        polar.run(in);
        std::vector<float> out(field.size());
        cl().queue().enqueueReadBuffer(polar.output(), CL_TRUE, 0, out.size() * sizeof(float), out.data());
        return out;
    }
};

TEST_F(Polar, TheKernelsMatchTheHostFilterKeepEachRowsMeanAndCopyTheRowsTheyLeave) {
    constexpr int W = 256, H = 128;
    SplitMix64 random(7);
    std::vector<float> field(size_t(W) * H);
    for (float& h : field) h = float(random.next());
    for (const float smoothing : {0.75f, 6.0f}) {
        const std::vector<float> out = filter(field, W, H, smoothing),
                                 expected = PolarFilter::reference(field, W, H, smoothing);
        double largest = 0.0, meanDrift = 0.0;
        int copied = 0, filtered = 0;
        for (int y = 0; y < H; ++y) {
            const float w = PolarFilter::rowWidth(y, W, H, smoothing);
            double before = 0.0, after = 0.0;
            for (int x = 0; x < W; ++x) {
                const size_t k = size_t(y) * W + x;
                largest = std::max(largest, double(std::abs(out[k] - expected[k])));
                before += field[k];
                after += out[k];
                if (w <= 1.0f) {
                    ASSERT_EQ(out[k], field[k]) << "row " << y << " (box " << w << " texels) changed";
                }
            }
            meanDrift = std::max(meanDrift, std::abs(after - before) / W);
            (w <= 1.0f ? copied : filtered) += 1;
        }
        std::printf("[polar] smoothing %.2f: %d rows filtered, %d copied; the kernels %.2e from the host's, row means "
                    "kept within %.2e\n",
                    double(smoothing), filtered, copied, largest, meanDrift);
        EXPECT_LT(largest, 2e-5) << smoothing;
        EXPECT_LT(meanDrift, 2e-5) << smoothing;
        EXPECT_GT(copied, H / 3) << "the low latitudes are filtered";
        EXPECT_GT(filtered, H / 8) << "the polar rows are not filtered";
    }
}

TEST_F(Polar, AZonalWaveIsDampedAsTheRowsBoxDampsItAndThePolarRowsFlatten) {
    // A wave of m cycles round each row: a box of w texels passes sinc(pi m w / W) of it (and the
    // texels' own steps a factor sinc(pi m / W), under 0.2% here), keeping its phase; a row whose
    // box spans it whole is its mean. Were the box twice as wide, the wave at 70 degrees would
    // keep 0.79 of itself instead of 0.95.
    constexpr int W = 512, H = 256, m = 6;
    constexpr float smoothing = 3.0f;
    std::vector<float> field(size_t(W) * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            field[size_t(y) * W + x] = 0.5f + 0.4f * float(std::sin(2.0 * std::numbers::pi * m * (x + 0.5) / W + y));
    const std::vector<float> out = filter(field, W, H, smoothing);
    auto sinc = [](double t) { return t == 0.0 ? 1.0 : std::sin(t) / t; };
    int checked = 0, flat = 0;
    for (int y = 0; y < H; ++y) {
        const double w = PolarFilter::rowWidth(y, W, H, smoothing);
        // The row's response: its projection on the input's wave.
        double along = 0.0, norm = 0.0, largest = 0.0;
        for (int x = 0; x < W; ++x) {
            const size_t k = size_t(y) * W + x;
            along += (out[k] - 0.5) * (field[k] - 0.5);
            norm += (field[k] - 0.5) * (field[k] - 0.5);
            largest = std::max(largest, std::abs(out[k] - 0.5));
        }
        if (w >= W) {
            EXPECT_LT(largest, 1e-5) << "row " << y << " spans its box whole and is not flat";
            ++flat;
            continue;
        }
        const double gain = along / norm, expected = sinc(std::numbers::pi * m * w / W);
        if (w > 1.0) ++checked;
        const double latitude = ((y + 0.5) / H - 0.5) * 180.0;
        if (y % 16 == 0 || std::abs(std::abs(latitude) - 70.0) < 0.4)
            std::printf("[polar] latitude %6.1f: box %7.2f texels, the wave kept %.4f (a box: %.4f)\n", latitude, w, gain,
                        expected);
        EXPECT_NEAR(gain, expected, 0.006) << "row " << y << ", box " << w;
    }
    EXPECT_GT(checked, 60);
    EXPECT_GE(flat, 2) << "no row at a pole spans its box whole";
}

TEST_F(Polar, GivenRowWidthsTheKernelsMatchTheHostFilter) {
    // The widths a sphere's gas filters its dye with (gasPolarWidths' law, 1 / cos(latitude) - 1
    // cells), given row by row: the kernels as the host's filter, the rows of a box of at most a
    // texel copied.
    constexpr int W = 128, H = 64;
    std::vector<float> widths(H);
    for (int y = 0; y < H; ++y)
        widths[size_t(y)] = float(std::min(1.0 / std::cos(((y + 0.5) / H - 0.5) * std::numbers::pi) - 1.0, double(W)));
    SplitMix64 random(3);
    std::vector<float> field(size_t(W) * H);
    for (float& h : field) h = float(random.next());
    PolarFilter polar(cl(), W, H, widths);
    EXPECT_EQ(polar.smoothing(), 0.0f);
    const std::vector<float> out = filter(polar, field), expected = PolarFilter::reference(field, W, H, widths);
    double largest = 0.0;
    for (size_t k = 0; k < out.size(); ++k) largest = std::max(largest, double(std::abs(out[k] - expected[k])));
    EXPECT_LT(largest, 2e-5);
    for (int x = 0; x < W; ++x) ASSERT_EQ(out[size_t(H / 2) * W + x], field[size_t(H / 2) * W + x]);
    EXPECT_NE(out[size_t(W) + 5], field[size_t(W) + 5]) << "the second row (a box of 39 texels) came through";
    // Into a buffer of the caller's (as a gas filters its dye): the same values; not into the field.
    cl::Buffer in(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, field.size() * sizeof(float), field.data());
    cl::Buffer mine(cl().context(), CL_MEM_READ_WRITE, field.size() * sizeof(float));
    polar.run(in, mine);
    std::vector<float> into(field.size());
    cl().queue().enqueueReadBuffer(mine, CL_TRUE, 0, into.size() * sizeof(float), into.data());
    EXPECT_EQ(into, out);
    EXPECT_NE(messageOf([&] { polar.run(in, in); }).find("out is the field it reads"), std::string::npos);
    const cl::Buffer small(cl().context(), CL_MEM_READ_WRITE, 16 * sizeof(float));
    EXPECT_NE(messageOf([&] { polar.run(in, small); }).find("PolarFilter::run: out holds 64 bytes"), std::string::npos);
    widths[3] = -1.0f;
    EXPECT_NE(messageOf([&] { PolarFilter(cl(), W, H, widths); }).find("row 3's width"), std::string::npos);
    widths.pop_back();
    EXPECT_NE(messageOf([&] { PolarFilter(cl(), W, H, widths); }).find("63 row widths for 64 rows"), std::string::npos);
}

TEST_F(Polar, BadSizesAndSmoothingsAreRefusedByName) {
    EXPECT_NE(messageOf([&] { PolarFilter(cl(), 0, 8, 1.0f); }).find("PolarFilter size"), std::string::npos);
    EXPECT_NE(messageOf([&] { PolarFilter(cl(), 64, 32, -1.0f); }).find("smoothing must be in [0, 60]"),
              std::string::npos);
    EXPECT_NE(messageOf([&] { PolarFilter(cl(), 64, 32, std::nanf("")); }).find("nan"), std::string::npos);
    PolarFilter polar(cl(), 64, 32, 1.0f);
    const cl::Buffer small(cl().context(), CL_MEM_READ_WRITE, 16 * sizeof(float));
    EXPECT_NE(messageOf([&] { polar.run(small); }).find("64x32 floats need"), std::string::npos);
    EXPECT_NE(messageOf([&] { PolarFilter::reference(std::vector<float>(10), 64, 32, 1.0f); }).find("10 values for 64x32"),
              std::string::npos);
}

} // namespace
} // namespace hfx::test
