// Noise against Perlin's reference algorithm, its own periodicity, its value range, and the
// exact gradient of psrdnoise (also a second check of the Sobel normals).

#include "support/Fixtures.h"

#include "hfx/compute/NoiseField.h"
#include "hfx/compute/SobelNormals.h"
#include "hfx/compute/shared/NoiseMath.h"
#include "hfx/core/Error.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>

namespace hfx::test {
namespace {

// Perlin's Improved Noise reference (his 2002 Java listing) in double precision.
struct PerlinReference {
    int p[512];
    PerlinReference() {
        for (int i = 0; i < 256; ++i) p[256 + i] = p[i] = hfx_perm[i];
    }
    static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
    static double lerp(double t, double a, double b) { return a + t * (b - a); }
    static double grad(int hash, double x, double y, double z) {
        int h = hash & 15;
        double u = h < 8 ? x : y, v = h < 4 ? y : h == 12 || h == 14 ? x : z;
        return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
    }
    double noise(double x, double y, double z) const {
        int X = (int)std::floor(x) & 255, Y = (int)std::floor(y) & 255, Z = (int)std::floor(z) & 255;
        x -= std::floor(x);
        y -= std::floor(y);
        z -= std::floor(z);
        double u = fade(x), v = fade(y), w = fade(z);
        int A = p[X] + Y, AA = p[A] + Z, AB = p[A + 1] + Z, B = p[X + 1] + Y, BA = p[B] + Z, BB = p[B + 1] + Z;
        return lerp(w, lerp(v, lerp(u, grad(p[AA], x, y, z), grad(p[BA], x - 1, y, z)),
                            lerp(u, grad(p[AB], x, y - 1, z), grad(p[BB], x - 1, y - 1, z))),
                    lerp(v, lerp(u, grad(p[AA + 1], x, y, z - 1), grad(p[BA + 1], x - 1, y, z - 1)),
                         lerp(u, grad(p[AB + 1], x, y - 1, z - 1), grad(p[BB + 1], x - 1, y - 1, z - 1))));
    }
};

TEST(Noise, PermutationIsPerlins) {
    const std::set<int> values(std::begin(hfx_perm), std::end(hfx_perm));
    EXPECT_EQ(values.size(), 256u);
    EXPECT_EQ(hfx_perm[0], 151);
    EXPECT_EQ(hfx_perm[255], 180);
}

TEST(Noise, ReferenceReproducesKnownValues) {
    const PerlinReference reference;
    // Derived by hand from Perlin's listing (DESIGN.md): exact in double.
    EXPECT_DOUBLE_EQ(reference.noise(3.14, 42, 7), 0.13691995878400012);
    EXPECT_DOUBLE_EQ(reference.noise(0.5, 0.5, 0.5), -0.25);
    // At lattice points the noise is zero.
    EXPECT_EQ(reference.noise(3, 7, 11), 0.0);
}

TEST(Noise, FloatPerlinFollowsTheReference) {
    const PerlinReference reference;
    std::mt19937 random(11);
    std::uniform_real_distribution<float> coordinate(-300.0f, 300.0f);
    double maxDiff = 0;
    for (int i = 0; i < 200000; ++i) {
        const float x = coordinate(random), y = coordinate(random), z = coordinate(random);
        maxDiff = std::max(maxDiff, std::abs(hfx_perlin3(x, y, z) - reference.noise(x, y, z)));
    }
    // float rounding of the fractional coordinates (|x| < 300: ulp 3e-5) and of the blend
    EXPECT_LT(maxDiff, 2e-4);
    EXPECT_NEAR(hfx_perlin3(3.14f, 42.0f, 7.0f), 0.13691995878400012, 1e-6);
    EXPECT_EQ(hfx_perlin3(0.5f, 0.5f, 0.5f), -0.25f);
}

TEST(Noise, OctavesStayInRange) {
    std::mt19937 random(3);
    std::uniform_real_distribution<float> coordinate(-50.0f, 50.0f);
    float lo[3] = {1, 1, 1}, hi[3] = {-1, -1, -1};
    for (int i = 0; i < 300000; ++i) {
        const float x = coordinate(random), y = coordinate(random), z = coordinate(random);
        float g[2];
        const float n[3] = {hfx_perlin3(x, y, z), hfx_simplex3(x, y, z),
                            hfx_psrdnoise2(x, y, 0.0f, 0.0f, z, g)};
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], n[k]);
            hi[k] = std::max(hi[k], n[k]);
        }
    }
    for (int k = 0; k < 3; ++k) {
        // Each octave lies in [-1, 1] (so fBm of any octaves lies in [0, 1] unclamped) and
        // spans most of it (a scale error of 2x would fail one side or the other).
        EXPECT_GE(lo[k], -1.0f) << "noise " << k;
        EXPECT_LE(hi[k], 1.0f) << "noise " << k;
        EXPECT_LT(lo[k], -0.7f) << "noise " << k;
        EXPECT_GT(hi[k], 0.7f) << "noise " << k;
    }
}

TEST(Noise, PeriodicVariantsTile) {
    std::mt19937 random(5);
    std::uniform_real_distribution<float> coordinate(0.0f, 20.0f);
    for (int i = 0; i < 20000; ++i) {
        const float x = coordinate(random), y = coordinate(random), z = coordinate(random);
        float g[2];
        EXPECT_NEAR(hfx_perlin3_periodic(x, y, z, 6, 10), hfx_perlin3_periodic(x + 6, y + 10, z, 6, 10), 2e-5);
        EXPECT_NEAR(hfx_psrdnoise2(x, y, 6, 10, z, g), hfx_psrdnoise2(x + 6, y - 10, 6, 10, z, g), 2e-5);
    }
    // Perlin with period 256 is Perlin's own noise.
    EXPECT_EQ(hfx_perlin3_periodic(3.14f, 42.0f, 7.0f, 256, 256), hfx_perlin3(3.14f, 42.0f, 7.0f));
}

TEST(Noise, PsrdGradientIsExact) {
    std::mt19937 random(9);
    std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
    double maxError = 0;
    for (int i = 0; i < 5000; ++i) {
        const float x = float(coordinate(random)), y = float(coordinate(random)), alpha = float(coordinate(random));
        float g[2], unused[2];
        hfx_psrdnoise2(x, y, 0, 0, alpha, g);
        const float h = 1e-2f;
        const double dx = (hfx_psrdnoise2(x + h, y, 0, 0, alpha, unused) - hfx_psrdnoise2(x - h, y, 0, 0, alpha, unused)) / (2 * h);
        const double dy = (hfx_psrdnoise2(x, y + h, 0, 0, alpha, unused) - hfx_psrdnoise2(x, y - h, 0, 0, alpha, unused)) / (2 * h);
        maxError = std::max({maxError, std::abs(dx - g[0]), std::abs(dy - g[1])});
    }
    // Central differences at h = 0.01 err by h^2 f'''/6 (f''' up to a few hundred here) plus
    // float cancellation; a missing chain-rule term errs by whole units.
    EXPECT_LT(maxError, 0.05);
}

class NoiseKernel : public ClTest {
protected:
    std::vector<float> read(const NoiseField& field) {
        std::vector<float> out(size_t(field.width()) * field.height());
        cl().queue().enqueueReadBuffer(field.buffer(), CL_TRUE, 0, out.size() * sizeof(float), out.data());
        return out;
    }
    std::vector<float> reference(const NoiseField& field) {
        const NoiseConfig& c = field.config();
        std::vector<float> h(size_t(c.width) * c.height);
        for (int y = 0; y < c.height; ++y)
            for (int x = 0; x < c.width; ++x)
                h[size_t(y) * c.width + x] = hfx_noise_texel(
                    int(c.kind), int(c.fractal), (x + 0.5f) / c.width, (y + 0.5f) / c.height, c.frequency,
                    c.frequencyY(), wrapsU(c.edges), wrapsV(c.edges), field.timeCoordinate(field.time()), c.octaves,
                    c.lacunarity, c.gain, c.warp);
        return h;
    }
};

TEST_F(NoiseKernel, PerlinAndSimplexKernelsAreBitExact) {
    for (const NoiseConfig& config :
         {NoiseConfig{.width = 96, .height = 64, .kind = NoiseKind::Perlin, .octaves = 4},
          NoiseConfig{.width = 64, .height = 64, .kind = NoiseKind::Perlin, .fractal = Fractal::Ridged, .warp = 1.5f},
          NoiseConfig{.width = 64, .height = 40, .kind = NoiseKind::Perlin, .octaves = 3, .edges = EdgeMode::WrapU},
          NoiseConfig{.width = 64, .height = 80, .kind = NoiseKind::Simplex, .fractal = Fractal::Turbulence,
                      .frequency = 5.5f, .edges = EdgeMode::Clamp}}) {
        NoiseField field(cl(), config);
        field.setTime(12.5);
        const auto gpu = read(field), cpu = reference(field);
        size_t different = 0;
        for (size_t i = 0; i < gpu.size(); ++i) different += gpu[i] != cpu[i];
        EXPECT_EQ(different, 0u) << "kind " << int(config.kind) << " fractal " << int(config.fractal);
    }
}

TEST_F(NoiseKernel, PsrdKernelMatchesReference) {
    NoiseField field(cl(), {.width = 64, .height = 64, .kind = NoiseKind::Psrd, .octaves = 3, .warp = 0.5f});
    field.setTime(3.0);
    const auto gpu = read(field), cpu = reference(field);
    double maxDiff = 0;
    for (size_t i = 0; i < gpu.size(); ++i) maxDiff = std::max(maxDiff, double(std::abs(gpu[i] - cpu[i])));
    // The device's sin/cos may differ from the host's by a few ulp.
    EXPECT_LT(maxDiff, 1e-5);
}

TEST_F(NoiseKernel, PeriodicFieldsHaveNoSeam) {
    // Both seams where the edges wrap; the u seam only for a longitude-latitude field (wrap-u),
    // whose v seam is an ordinary jump (checked, so the test sees the difference).
    for (const auto& [kind, edges] : {std::pair{NoiseKind::Perlin, EdgeMode::Wrap}, std::pair{NoiseKind::Psrd, EdgeMode::Wrap},
                                      std::pair{NoiseKind::Perlin, EdgeMode::WrapU}}) {
        NoiseField field(cl(), {.width = 128, .height = 128, .kind = kind, .frequency = 4, .octaves = 3, .edges = edges});
        const auto h = read(field);
        const int N = 128;
        double interior = 0, seam = 0, seamV = 0;
        for (int a = 0; a < N; ++a) {
            for (int b = 0; b + 1 < N; ++b) {
                interior = std::max(interior, double(std::abs(h[a * N + b + 1] - h[a * N + b])));
                interior = std::max(interior, double(std::abs(h[(b + 1) * N + a] - h[b * N + a])));
            }
            seam = std::max(seam, double(std::abs(h[a * N] - h[a * N + N - 1])));
            seamV = std::max(seamV, double(std::abs(h[a] - h[(N - 1) * N + a])));
        }
        EXPECT_LE(seam, interior * 1.05) << "noise kind " << int(kind) << " has a seam across u";
        if (wrapsV(edges))
            EXPECT_LE(seamV, interior * 1.05) << "noise kind " << int(kind) << " has a seam across v";
        else
            EXPECT_GT(seamV, interior * 1.5) << "a field that does not wrap in v matched across it";
    }
}

TEST_F(NoiseKernel, FieldIsAnimated) {
    NoiseField field(cl(), {.width = 64, .height = 64, .kind = NoiseKind::Psrd});
    const auto before = read(field);
    field.step(0.5);
    const auto after = read(field);
    double change = 0;
    for (size_t i = 0; i < before.size(); ++i) change = std::max(change, double(std::abs(before[i] - after[i])));
    EXPECT_GT(change, 0.01);
}

TEST_F(NoiseKernel, SobelNormalsMatchPsrdAnalyticGradient) {
    // One octave of fBm: h = 0.5 + 0.5 n(u f, v f), so dh/du = 0.5 f dn/dx exactly.
    constexpr int N = 256;
    constexpr float f = 4.0f, depthScale = 0.02f;
    NoiseField field(cl(), {.width = N, .height = N, .kind = NoiseKind::Psrd, .frequency = f, .octaves = 1});
    SobelNormals sobel(cl(), {.width = N, .height = N, .normalDepth = depthScale});
    sobel.run(field.buffer());
    std::vector<cl_float4> normals(N * N);
    cl().queue().enqueueReadBuffer(sobel.output(), CL_TRUE, 0, normals.size() * sizeof(cl_float4), normals.data());
    const float t = field.timeCoordinate(0.0);
    double maxAngle = 0;
    for (int y = 0; y < N; y += 3)
        for (int x = 0; x < N; x += 3) {
            float g[2];
            hfx_psrdnoise2((x + 0.5f) / N * f, (y + 0.5f) / N * f, f, f, t, g);
            const glm::dvec3 exact = glm::normalize(glm::dvec3(-depthScale * 0.5 * f * g[0], -depthScale * 0.5 * f * g[1], 1.0));
            const cl_float4 n = normals[y * N + x];
            maxAngle = std::max(maxAngle, std::acos(std::min(1.0, glm::dot(exact, glm::dvec3(n.s[0], n.s[1], n.s[2])))));
        }
    // The Sobel stencil's truncation error at 64 texels per noise cell.
    EXPECT_LT(maxAngle * 180 / std::numbers::pi, 0.5);
}

TEST_F(NoiseKernel, BadConfigurationNamesTheField) {
    auto message = [&](const NoiseConfig& c) {
        try {
            NoiseField field(cl(), c);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message({.width = 0}).find("size"), std::string::npos);
    EXPECT_NE(message({.octaves = 0}).find("octaves"), std::string::npos);
    EXPECT_NE(message({.frequency = 2.5f}).find("whole number"), std::string::npos);
    EXPECT_NE(message({.kind = NoiseKind::Simplex}).find("simplex"), std::string::npos);
    EXPECT_NE(message({.kind = NoiseKind::Psrd, .edges = EdgeMode::WrapU}).find("wrap-u"), std::string::npos);
    EXPECT_NE(message({.gain = 0.0f}).find("gain"), std::string::npos);
    EXPECT_NE(message({.frequency = 64, .octaves = 6}).find("256"), std::string::npos);
    EXPECT_THROW(parseNoiseKind("worley"), Error);
}

} // namespace
} // namespace hfx::test
