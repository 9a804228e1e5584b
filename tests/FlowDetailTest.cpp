// The gas's advected detail (FlowDetail, FlowMath.h): a uniform wind carries the noise's
// coordinates exactly, the kernels match the shared math run on the host (on the sphere's map
// too), a shear stretches the noise into filaments along it, a warp frays the gas's edges and
// leaves its flats flat, the layers regenerate at their period, the detail stays periodic in u
// and finite at 10^4 times the time scale, and a lattice a shear squeezes keeps only the octaves
// its texels can show.

#include "support/Fixtures.h"

#include "hfx/compute/FlowDetail.h"
#include "hfx/compute/GasField.h"
#include "hfx/compute/shared/FlowMath.h"
#include "hfx/core/Error.h"

#include <algorithm>
#include <cmath>

namespace hfx::test {
namespace {

class Flow : public ClTest {};

constexpr int W = 64, H = 32;

GasConfig gasConfig() { return {.width = W, .height = H, .edges = EdgeMode::WrapU, .initialBands = 4.0f}; }

// A gas whose velocity is u(y) along x (at the x-faces, rows' centres y = j + 0.5) and 0 along y.
void setZonalWind(GasField& gas, float (*u)(float y)) {
    std::vector<float> vx(W * H), vy(W * H, 0.0f), dye(W * H);
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            vx[j * W + i] = u(float(j) + 0.5f);
            dye[j * W + i] = 0.5f + 0.3f * std::sin(0.4f * float(j)) * std::cos(6.283185f * float(i) / W);
        }
    gas.setState(vx, vy, dye);
}

// Mean |dh/dx| and |dh/dy| over the inner rows of a fine field (width x height).
std::pair<double, double> meanSlopes(const std::vector<float>& h, int width, int height) {
    double dx = 0, dy = 0;
    int n = 0;
    for (int y = height / 8; y < height - height / 8; ++y)
        for (int x = 0; x < width; ++x, ++n) {
            dx += std::abs(h[size_t(y) * width + (x + 1) % width] - h[size_t(y) * width + x]);
            dy += std::abs(h[size_t(y + 1) * width + x] - h[size_t(y) * width + x]);
        }
    return {dx / n, dy / n};
}

TEST_F(Flow, AUniformWindCarriesTheNoisesCoordinatesExactly) {
    GasField gas(cl(), gasConfig());
    setZonalWind(gas, [](float) { return 3.0f; });
    const float period = 10.0f, dt = 0.25f;
    FlowDetail detail(cl(), gas, {.scale = 2, .amount = 0.3f, .period = period});
    // Layer 1 is born at t = 5 (its phase 0.5 + t / 10 turns over), layer 0 lives from t = 0.
    for (int s = 0; s < 28; ++s) detail.step(dt); // t = 7
    const std::vector<float> d = detail.readPlanes();
    const size_t n = size_t(W) * H;
    double worst = 0;
    for (size_t k = 0; k < n; ++k) {
        worst = std::max(worst, std::abs(d[k] - (-3.0 * 7.0)));       // layer 0: x moved back by U t
        worst = std::max(worst, double(std::abs(d[n + k])));           // no move in y
        worst = std::max(worst, std::abs(d[2 * n + k] - (-3.0 * 2.0))); // layer 1: since t = 5
        worst = std::max(worst, double(std::abs(d[3 * n + k])));
    }
    EXPECT_LT(worst, 1e-3);
    EXPECT_NEAR(detail.weight(0), std::sin(3.14159265 * 0.7), 1e-6);
    EXPECT_NEAR(detail.weight(1), std::sin(3.14159265 * 0.2), 1e-6);
    // So the detail at x is the fresh noise at x - U t: the pattern moves with the wind.
}

TEST_F(Flow, KernelsMatchTheSharedMathOnTheHostAndThePolesAreOneValue) {
    GasField gas(cl(), gasConfig());
    gas.step(0.1);
    const FlowDetailConfig config{.scale = 4, .amount = 0.3f, .period = 3.0f, .capRows = 2.0f};
    FlowDetail detail(cl(), gas, config);
    for (int s = 0; s < 7; ++s) {
        gas.step(0.2);
        detail.step(0.2);
    }
    detail.run();
    const std::vector<float> drawn = detail.readHeights(), planes = detail.readPlanes(), heights = gas.readHeights();
    const int columns = W * 4, rows = H * 4;
    ASSERT_EQ(drawn.size(), size_t(columns) * rows);
    double worst = 0, shown = 0;
    for (int fy = 0; fy < rows; ++fy)
        for (int fx = 0; fx < columns; ++fx) {
            const float x = (float(fx) + 0.5f) / 4.0f, y = (float(fy) + 0.5f) / 4.0f;
            float h = hfx_flow_height(heights.data(), planes.data(), W, H, x, y, detail.params());
            const float t = float(std::min(fy, rows - 1 - fy)) / (config.capRows * 4.0f);
            if (t < 1.0f) h = 0.5f + (h - 0.5f) * t * t * (3.0f - 2.0f * t);
            worst = std::max(worst, double(std::abs(drawn[size_t(fy) * columns + fx] - h)));
            if (t >= 1.0f)
                shown = std::max(shown, double(std::abs(drawn[size_t(fy) * columns + fx] -
                                                        hfx_flow_base(heights.data(), W, H, x, y))));
        }
    EXPECT_LT(worst, 1e-5);
    // The gas's heights come through as a cubic B-spline: (1, 4, 1) / 6 along each axis at its
    // cell centres, and between them without a crease: the slope is one from either side of a
    // cell's edge.
    double crease = 0, slope = 0;
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            const float x = float(i) + 0.5f, y = float(j) + 0.5f, e = 1.0f / 64.0f;
            auto at3 = [&](int di, int dj) {
                const int jj = std::clamp(j + dj, 0, H - 1), ii = (i + di + W) % W;
                return double(heights[size_t(jj) * W + ii]);
            };
            double centre = 0;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) centre += (di ? 1.0 : 4.0) * (dj ? 1.0 : 4.0) / 36.0 * at3(di, dj);
            ASSERT_NEAR(hfx_flow_base(heights.data(), W, H, x, y), centre, 1e-6);
            const float at = hfx_flow_base(heights.data(), W, H, x + 0.5f, y);
            const double left = at - hfx_flow_base(heights.data(), W, H, x + 0.5f - e, y);
            const double right = hfx_flow_base(heights.data(), W, H, x + 0.5f + e, y) - at;
            crease = std::max(crease, std::abs(right - left) / e);
            slope = std::max(slope, std::abs(left) / e);
        }
    EXPECT_LT(crease, 0.05 * slope) << "the slope steps at a cell's edge";
    // The octaves the scale shows: lattice cells along y up to scale / 2 per gas cell.
    EXPECT_EQ(detail.octaves(), 2); // 1 and 2 per cell along y (the base 0.5 along x, twice that along y)
    EXPECT_GT(shown, 0.015) << "the detail shows"; // a still gas: the calm share of it
    for (int fx = 0; fx < columns; ++fx) {
        EXPECT_EQ(drawn[size_t(fx)], 0.5f);
        EXPECT_EQ(drawn[size_t(rows - 1) * columns + fx], 0.5f);
    }
}

TEST_F(Flow, OnASphereTheKernelsMatchTheSharedMathOnTheHost) {
    // The planet's detail: a gas on the sphere's map, warped and added. A step's advection of the
    // four displacement planes (the departure traced once for all of them) and the strain against
    // hfx_flow_advect and hfx_flow_strain; the heights, both layers' two noises each, against
    // hfx_flow_height.
    GasConfig config = gasConfig();
    config.sphere = true;
    config.jetSpeed = 6.0f; // jets, and storms' worth of vorticity between them
    config.vorticity = 0.35f;
    GasField gas(cl(), config);
    FlowDetail detail(cl(), gas, {.scale = 2, .amount = 0.25f, .warp = 2.0f, .period = 3.0f});
    for (int s = 0; s < 5; ++s) { // to t = 1: neither layer starts again in the next step
        gas.step(0.2);
        detail.step(0.2);
    }
    const std::vector<float> before = detail.readPlanes(), metric = gasMetricTable(config);
    std::vector<float> u, v, dye;
    gas.readState(u, v, dye);
    detail.step(0.2);
    const std::vector<float> after = detail.readPlanes();
    const int n = W * H;
    double advected = 0, strain = 0, moved = 0;
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            const int k = j * W + i;
            for (int plane = 0; plane < 4; ++plane) {
                const float host = hfx_flow_advect(u.data(), v.data(), metric.data(), before.data() + plane * n, W, H,
                                                   i, j, 0.2f, plane & 1);
                advected = std::max(advected, double(std::abs(after[size_t(plane * n + k)] - host)));
                moved = std::max(moved, double(std::abs(after[size_t(plane * n + k)] - before[size_t(plane * n + k)])));
            }
            strain = std::max(strain, double(std::abs(after[size_t(HFX_FLOW_STRAIN * n + k)] -
                                                      hfx_flow_strain(u.data(), v.data(), metric.data(), W, H, i, j))));
        }
    EXPECT_GT(moved, 0.01) << "the test's premise: the wind moves the planes";
    EXPECT_LT(advected, 1e-5);
    EXPECT_LT(strain, 1e-5);
    detail.run();
    const std::vector<float> drawn = detail.readHeights(), heights = gas.readHeights();
    ASSERT_GT(detail.params().w0 * detail.params().w1, 0.0f) << "both layers show";
    double worst = 0;
    for (int fy = 0; fy < 2 * H; ++fy)
        for (int fx = 0; fx < 2 * W; ++fx) {
            const float x = (float(fx) + 0.5f) / 2.0f, y = (float(fy) + 0.5f) / 2.0f;
            const float host = hfx_flow_height(heights.data(), after.data(), W, H, x, y, detail.params());
            worst = std::max(worst, double(std::abs(drawn[size_t(fy) * 2 * W + fx] - host)));
        }
    EXPECT_LT(worst, 1e-5);
}

TEST_F(Flow, AShearStretchesTheNoiseIntoFilamentsAlongIt) {
    // u = S (y - H / 2): after an age a, a feature is sheared by S a cells per cell of height.
    // At t = period / 2 layer 0 has weight 1 and layer 1 none: the detail is layer 0 alone, of
    // age period / 2. Fresh (a still wind), the noise is about as steep along x as along y;
    // sheared, its slopes across the flow are over twice those along it.
    GasField still(cl(), gasConfig()), sheared(cl(), gasConfig());
    setZonalWind(still, [](float) { return 0.0f; });
    setZonalWind(sheared, [](float y) { return 1.5f * (y - 0.5f * H); });
    double ratio[2];
    GasField* gases[2] = {&still, &sheared};
    for (int g = 0; g < 2; ++g) {
        FlowDetail detail(cl(), *gases[g], {.scale = 4, .amount = 1.0f, .frequency = 0.5f, .aspect = 1.0f, .octaves = 3,
                                            .calm = 1.0f, .period = 4.0f});
        for (int s = 0; s < 20; ++s) detail.step(0.1);
        ASSERT_NEAR(detail.weight(0), 1.0f, 1e-6);
        // The strain rate of u = S (y - H / 2) is |S| (du/dy), of a still gas 0, away from the walls.
        const std::vector<float> planes = detail.readPlanes();
        for (int j = 2; j < H - 2; ++j)
            for (int i = 0; i < W; ++i) ASSERT_NEAR(planes[4 * W * H + j * W + i], g == 0 ? 0.0f : 1.5f, 1e-4) << i << "," << j;
        detail.run();
        // The detail alone: the gas's own heights subtracted (as the kernel adds them).
        std::vector<float> h = detail.readHeights();
        const std::vector<float> base = gases[g]->readHeights();
        for (int fy = 0; fy < H * 4; ++fy)
            for (int fx = 0; fx < W * 4; ++fx)
                h[size_t(fy) * W * 4 + fx] -= hfx_flow_base(base.data(), W, H, (fx + 0.5f) / 4.0f, (fy + 0.5f) / 4.0f);
        const auto [dx, dy] = meanSlopes(h, W * 4, H * 4);
        ratio[g] = dy / dx;
    }
    EXPECT_GT(ratio[0], 0.6);
    EXPECT_LT(ratio[0], 1.6);
    EXPECT_GT(ratio[1], 2.0) << "still " << ratio[0]; // 2.34 on PoCL (a shear of 3 cells per cell: sqrt(10) for an ideal slope)
}

TEST_F(Flow, AWarpFraysTheGassEdgesAndLeavesItsFlatsFlat) {
    // A still gas with one edge: dye 0.2 below row H / 2, 0.8 from it. The warp reads it at points
    // moved by at most warp * (w0 + w1) / 2 < 2.2 cells, through a B-spline reaching 2 cells: rows
    // 5 cells or more from the edge see the flat alone, and the edge becomes a frayed line along x.
    GasField gas(cl(), gasConfig());
    std::vector<float> zero(W * H, 0.0f), dye(W * H);
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) dye[j * W + i] = j < H / 2 ? 0.2f : 0.8f;
    gas.setState(zero, zero, dye);
    FlowDetail detail(cl(), gas, {.scale = 4, .amount = 0.0f, .warp = 3.0f, .calm = 1.0f, .period = 4.0f});
    for (int s = 0; s < 7; ++s) detail.step(0.2);
    ASSERT_GT(detail.weight(0), 0.0f);
    ASSERT_GT(detail.weight(1), 0.0f);
    detail.run();
    const std::vector<float> drawn = detail.readHeights(), planes = detail.readPlanes(), heights = gas.readHeights();
    const int columns = W * 4, rows = H * 4;
    double worst = 0, flat = 0, lo = 1, hi = 0, fray = 0;
    for (int fy = 0; fy < rows; ++fy) {
        const float y = (float(fy) + 0.5f) / 4.0f;
        double sum = 0, sum2 = 0;
        for (int fx = 0; fx < columns; ++fx) {
            const float x = (float(fx) + 0.5f) / 4.0f, h = drawn[size_t(fy) * columns + fx];
            worst = std::max(worst, double(std::abs(h - hfx_flow_height(heights.data(), planes.data(), W, H, x, y,
                                                                            detail.params()))));
            if (std::abs(y - 0.5f * H) >= 5.0f) flat = std::max(flat, double(std::abs(h - (y < 0.5f * H ? 0.2f : 0.8f))));
            lo = std::min(lo, double(h));
            hi = std::max(hi, double(h));
            sum += h;
            sum2 += double(h) * h;
        }
        fray = std::max(fray, std::sqrt(std::max(0.0, sum2 / columns - (sum / columns) * (sum / columns))));
    }
    EXPECT_LT(worst, 1e-5) << "the kernel against FlowMath.h on the host";
    EXPECT_LT(flat, 1e-6) << "a flat band stays flat";
    EXPECT_GE(lo, 0.2f - 1e-6);
    EXPECT_LE(hi, 0.8f + 1e-6) << "a warped height is a blend of the gas's own";
    // Unwarped, every row is constant along x (the gas is); warped, the edge's rows vary along it.
    EXPECT_GT(fray, 0.05);
    // Without a warp the same detail leaves the edge straight.
    FlowDetail straight(cl(), gas, {.scale = 4, .amount = 0.0f, .warp = 0.0f, .calm = 1.0f, .period = 4.0f, .capRows = 1.0f});
    straight.run();
    const std::vector<float> plain = straight.readHeights();
    for (int fy = 8; fy < rows - 8; ++fy)
        for (int fx = 1; fx < columns; ++fx) ASSERT_NEAR(plain[size_t(fy) * columns + fx], plain[size_t(fy) * columns], 1e-6);
}

TEST_F(Flow, LayersRegenerateAtTheirPeriodAndStayPeriodicInUAndFiniteAtLongSteps) {
    GasField gas(cl(), {.width = W, .height = H, .edges = EdgeMode::WrapU, .vorticity = 0.35f, .jetSpeed = 14.0f,
                        .jetBands = 4.5f, .jetRate = 0.2f, .jetPolar = 1.0f, .maxSpeed = 56.0f, .initialBands = 4.0f});
    FlowDetail detail(cl(), gas, {.scale = 4, .amount = 0.25f, .warp = 2.0f, .period = 4.0f, .capRows = 1.0f});
    // A regenerated layer starts from no displacement: layer 0 turns over at t = 4.
    for (int s = 0; s < 39; ++s) {
        gas.step(0.1);
        detail.step(0.1);
    }
    const size_t n = size_t(W) * H;
    std::vector<float> d = detail.readPlanes();
    const float moved = *std::max_element(d.begin(), d.begin() + n, [](float a, float b) { return std::abs(a) < std::abs(b); });
    EXPECT_GT(std::abs(moved), 5.0f) << "the jets moved layer 0";
    const float generation = detail.generation(0);
    gas.step(0.2);
    detail.step(0.2);
    d = detail.readPlanes();
    EXPECT_TRUE(std::all_of(d.begin(), d.begin() + 2 * n, [](float x) { return x == 0.0f; })) << "layer 0 reborn";
    EXPECT_NE(detail.generation(0), generation) << "with a fresh noise";
    // The planet's 10^4 time scale: steps of minutes of gas time, many lives each.
    for (int s = 0; s < 200; ++s) {
        gas.step(166.7);
        detail.step(166.7);
    }
    detail.run();
    const std::vector<float> h = detail.readHeights();
    d = detail.readPlanes();
    for (float x : d) ASSERT_TRUE(std::isfinite(x));
    const int columns = W * 4, rows = H * 4;
    double interior = 0, seam = 0;
    for (int y = 0; y < rows; ++y) {
        for (int x = 0; x < columns; ++x) ASSERT_TRUE(h[size_t(y) * columns + x] >= 0.0f && h[size_t(y) * columns + x] <= 1.0f);
        for (int x = 0; x + 1 < columns; ++x)
            interior = std::max(interior, double(std::abs(h[size_t(y) * columns + x + 1] - h[size_t(y) * columns + x])));
        seam = std::max(seam, double(std::abs(h[size_t(y) * columns] - h[size_t(y) * columns + columns - 1])));
    }
    EXPECT_GT(interior, 0.0);
    EXPECT_LE(seam, interior) << "a seam at u = 0";
    // The noise itself wraps around the longitude at every octave.
    for (float y : {3.3f, 17.9f})
        for (float x : {0.1f, 31.7f})
            EXPECT_NEAR(hfx_flow_noise(x, y, 5.5f, W, 0.25f, 2.0f, 4, 4.0f), hfx_flow_noise(x + W, y, 5.5f, W, 0.25f, 2.0f, 4, 4.0f), 1e-5);
}

// The largest singular value of the 2x2 matrix (a b; c d), by the textbook's formula in doubles.
double largestSingular(double a, double b, double c, double d) {
    const double squares = a * a + b * b + c * c + d * d, det = a * d - b * c;
    return std::sqrt(0.5 * (squares + std::sqrt(squares * squares - 4.0 * det * det)));
}

TEST_F(Flow, ASqueezedLatticeKeepsOnlyTheOctavesItsTexelsCanShow) {
    // Layer 0's displacement a shear d_x = g (y - H / 2): its carried coordinates' Jacobian is
    // (1 g; 0 1) in every cell, and the finest octave shown is log2(texels / (2 f sigma)), sigma
    // that of diag(1, aspect) J, in each cell (the walls' rows by one-sided differences) and at
    // every point between (read bilinearly), as the kernel derives it from the planes it is given.
    GasField gas(cl(), gasConfig());
    FlowDetail detail(cl(), gas, {.scale = 4, .amount = 0.3f, .frequency = 0.5f, .aspect = 2.0f, .octaves = 4});
    const HfxFlowParams p = detail.params();
    const size_t n = size_t(W) * H;
    // Unsqueezed, sigma = aspect: the octaves FlowDetail::octaves() counts (2 at 4 texels a cell)
    // all in full, and the detail is the plain fBm's.
    std::vector<float> planes = detail.readPlanes();
    ASSERT_EQ(planes.size(), size_t(HFX_FLOW_PLANES) * n);
    const float still = std::log2(4.0f / (2.0f * 0.5f * 2.0f)); // 1: octaves 0 and 1
    for (size_t k = 0; k < 2 * n; ++k) ASSERT_NEAR(planes[HFX_FLOW_FINEST * n + k], still, 1e-6) << k;
    ASSERT_EQ(detail.octaves(), 2);
    for (float x : {3.1f, 40.7f})
        EXPECT_EQ(hfx_flow_noise(x, 9.2f, 3.0f, W, 0.5f, 2.0f, 2, still),
                  float(hfx_fractal(HFX_NOISE_PERLIN, HFX_FRACTAL_FBM, x * 0.5f, 9.2f, 3.0f, 2, 2.0f, 0.5f, W * 0.5f,
                                    256.0f) - 0.5f));
    for (float g : {0.5f, 3.0f, 12.0f}) {
        std::vector<float> set(5 * n, 0.0f);
        for (int j = 0; j < H; ++j)
            for (int i = 0; i < W; ++i) set[size_t(j) * W + i] = g * (float(j) + 0.5f - 0.5f * H);
        detail.setPlanes(set);
        planes = detail.readPlanes();
        const double expected = std::log2(4.0 / (2.0 * 0.5 * largestSingular(1.0, g, 0.0, 2.0)));
        for (int j : {0, 7, 16, H - 1})
            for (int i : {0, 11, W - 1}) {
                EXPECT_NEAR(planes[HFX_FLOW_FINEST * n + size_t(j) * W + i], expected, 1e-5) << "shear " << g << " cell " << i << "," << j;
                EXPECT_NEAR(hfx_flow_cell_finest(planes.data(), W, H, i, j, 0, p), expected, 1e-5);
                EXPECT_NEAR(planes[(HFX_FLOW_FINEST + 1) * n + size_t(j) * W + i], still, 1e-6) << "layer 1 unsqueezed";
            }
    }
    // Octave i counts with weight clamp(1 + finest - i, 0, 1): past the finest the sum loses it
    // (an octave and a half: octave 1 at half weight, 2 and 3 gone), and with none to show the
    // noise is 0, not aliased.
    const auto octave = [](float x, float y, int i) {
        return hfx_noise_octave(HFX_NOISE_PERLIN, x * float(1 << i) + 17.0f * float(i), y * float(1 << i) + 17.0f * float(i),
                                3.0f + 3.7f * float(i), W * 0.5f * float(1 << i), 256.0f * float(1 << i));
    };
    const float x = 7.3f * 0.5f, y = 2.9f * 0.5f * 2.0f, total = 1.0f + 0.5f + 0.25f + 0.125f;
    EXPECT_NEAR(hfx_flow_noise(7.3f, 2.9f, 3.0f, W, 0.5f, 2.0f, 4, 0.5f),
                0.5f * (octave(x, y, 0) + 0.5f * 0.5f * octave(x, y, 1)) / total, 1e-6);
    EXPECT_EQ(hfx_flow_noise(7.3f, 2.9f, 3.0f, W, 0.5f, 2.0f, 4, -1.0f), 0.0f);
}

TEST_F(Flow, ALongShearsDetailHoldsNoTexelSizedRipples) {
    // A jet's shear of 4 cells per cell a second squeezes a layer 8-fold across it by its middle
    // age: unlimited, its noise runs finer than the texels and aliases into ripples a texel or two
    // apart across the flow (the planet's zipper along a band's edge), whose second difference
    // nears twice the first (1.72 here without the band limit, on PoCL). Limited, it stays well
    // below it, as on slopes a few texels long (0.10).
    GasField gas(cl(), gasConfig());
    setZonalWind(gas, [](float y) { return 4.0f * (y - 0.5f * H); });
    FlowDetail detail(cl(), gas, {.scale = 4, .amount = 0.5f, .warp = 2.0f, .calm = 1.0f, .period = 4.0f});
    for (int s = 0; s < 20; ++s) detail.step(0.1);
    ASSERT_NEAR(detail.weight(0), 1.0f, 1e-6);
    detail.run();
    const std::vector<float> h = detail.readHeights();
    const int columns = W * 4, rows = H * 4;
    double first = 0, second = 0;
    for (int fy = rows / 4; fy < 3 * rows / 4; ++fy)
        for (int fx = 0; fx < columns; ++fx) {
            const auto at = [&](int y) { return double(h[size_t(y) * columns + fx]); };
            first += std::abs(at(fy + 1) - at(fy));
            second += std::abs(at(fy + 1) - 2.0 * at(fy) + at(fy - 1));
        }
    EXPECT_GT(first, 0.0);
    EXPECT_LT(second / first, 0.4) << "ripples a texel apart across the shear";
}

TEST(FlowNoise, OnASphereTheNoiseIsRoundOnThePlanetAndSeamless) {
    // hfx_flow_noise_sphere on a 128x64 map: the same around the longitude's wrap; at the
    // equator as rough along x and y as the map's noise (its slopes per cell within 10%); at
    // 70 degrees its slope per cell of the map along x is cos(70) of the equator's, the same per
    // unit of the sphere (measured 0.333 against 0.342), where the map's noise keeps its own and
    // is drawn as wedges.
    constexpr int w = 128, h = 64;
    constexpr float z = 7.3f, f = 0.5f, aspect = 2.0f, e = 0.05f;
    for (const float y : {9.3f, 40.1f})
        for (const float x : {0.2f, 77.7f})
            EXPECT_NEAR(hfx_flow_noise_sphere(x, y, z, w, h, f, aspect, 4, 4.0f),
                        hfx_flow_noise_sphere(x + w, y, z, w, h, f, aspect, 4, 4.0f), 1e-5);
    // The mean |slope| per cell along x and y over a band of rows about `row`.
    auto slopes = [&](bool sphere, float row) {
        double sx = 0.0, sy = 0.0;
        int n = 0;
        auto noise = [&](float x, float y) {
            return sphere ? hfx_flow_noise_sphere(x, y, z, w, h, f, aspect, 4, 4.0f)
                          : hfx_flow_noise(x, y, z, w, f, aspect, 4, 4.0f);
        };
        for (int j = 0; j < 40; ++j)
            for (int i = 0; i < 1280; ++i) {
                const float x = i * 0.1f, y = row - 1.0f + j * 0.05f, at = noise(x, y);
                sx += std::abs(noise(x + e, y) - at) / e;
                sy += std::abs(noise(x, y + e) - at) / e;
                ++n;
            }
        return std::pair{sx / n, sy / n};
    };
    const auto [ex, ey] = slopes(true, 32.0f);
    const auto [mx, my] = slopes(false, 32.0f);
    const float polar = 56.9f; // 70 degrees north
    const auto [px, py] = slopes(true, polar);
    const auto [qx, qy] = slopes(false, polar);
    const double c = std::cos(70.0 * std::numbers::pi / 180.0);
    std::printf("[sphere noise] slopes per cell along x, y: equator %.3f, %.3f (the map's %.3f, %.3f); 70 degrees "
                "%.3f, %.3f (the map's %.3f, %.3f)\n",
                ex, ey, mx, my, px, py, qx, qy);
    EXPECT_NEAR(ex / mx, 1.0, 0.1);
    EXPECT_NEAR(ey / my, 1.0, 0.1);
    EXPECT_NEAR(px / ex, c, 0.1);
    EXPECT_NEAR(qx / mx, 1.0, 0.1) << "the map's noise keeps its cells (the test's premise)";
    // Along y the aspect fades as the polar axis leaves the surface: sqrt(c^2 a^2 + s^2) / a.
    EXPECT_NEAR(py / ey, std::sqrt(c * c * aspect * aspect + 1.0 - c * c) / aspect, 0.1);
}

TEST_F(Flow, BadConfigurationsAreRefusedByName) {
    GasField gas(cl(), gasConfig());
    auto refuses = [&](FlowDetailConfig c, const char* field) {
        try {
            FlowDetail detail(cl(), gas, c);
            ADD_FAILURE() << field << " accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
        }
    };
    refuses({.scale = 3}, "scale");
    refuses({.amount = -0.1f}, "amount");
    refuses({.warp = 9.0f}, "warp");
    refuses({.frequency = 0.3f}, "frequency"); // 64 * 0.3 is not whole: the noise would not wrap
    refuses({.octaves = 0}, "octaves");
    refuses({.aspect = 0.5f}, "aspect");
    refuses({.calm = 1.5f}, "calm");
    refuses({.strainScale = 0.0f}, "strainScale");
    refuses({.period = 0.0f}, "period");
    refuses({.capRows = 17.0f}, "capRows");
    GasField torus(cl(), {.width = W, .height = H, .edges = EdgeMode::Wrap});
    EXPECT_THROW(FlowDetail(cl(), torus, {}), Error);
    FlowDetail detail(cl(), gas, {});
    EXPECT_THROW(detail.step(std::nan("")), Error);
    EXPECT_THROW(detail.setPlanes(std::vector<float>(5 * W * H, std::nanf(""))), Error);
    EXPECT_THROW(detail.setPlanes(std::vector<float>(4 * W * H, 0.0f)), Error);
}

} // namespace
} // namespace hfx::test
