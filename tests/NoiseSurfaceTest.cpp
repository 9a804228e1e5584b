// The noise user: every option combination of the noise scene either renders (a lit relief in
// range, not flat) or is refused by name leaving the surface as it was; and a tiling noise
// continues across its edges to float rounding (the texels at one edge are the shared math's
// values one period beyond the other).

#include "support/Fixtures.h"

#include "hfx/compute/shared/NoiseMath.h"
#include "hfx/core/Error.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/NoiseSurfaceEffect.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/tools/AccuracyProbe.h"

#include <cmath>

namespace hfx::test {
namespace {

class NoiseSurface : public DeviceTest {};

TEST_F(NoiseSurface, EveryOptionCombinationRendersOrIsRefusedByName) {
    NoiseSurfaceEffect effect(cl(), {.noise = {.width = 64, .height = 64}});
    SurfaceRenderer renderer;
    const Mesh plane(makePlane({.size = 2.0f, .texcoordScale = 2.0f}));
    const Camera camera = accuracyCamera(55.0);
    RenderTarget target(48, 32);
    int rendered = 0, refused = 0;
    for (const NoiseKind kind : {NoiseKind::Perlin, NoiseKind::Simplex, NoiseKind::Psrd})
        for (const Fractal fractal : {Fractal::Fbm, Fractal::Ridged, Fractal::Turbulence})
            for (const EdgeMode edges : kEdgeModes)
                for (const float warp : {0.0f, 0.8f})
                    for (const int octaves : {1, 6}) {
                        const NoiseConfig noise{.width = 64, .height = 64, .kind = kind, .fractal = fractal,
                                                .frequency = 4.0f, .octaves = octaves, .warp = warp, .edges = edges};
                        const std::string what = str("kind ", int(kind), " fractal ", int(fractal), " edges ",
                                                     edgeModeName(edges), " warp ", warp, " octaves ", octaves);
                        bool valid = true;
                        try {
                            noise.validate();
                        } catch (const Error&) {
                            valid = false;
                        }
                        if (!valid) {
                            const NoiseConfig before = effect.noise().config();
                            EXPECT_NE(messageOf([&] { effect.setNoise(noise); }).find("edges"), std::string::npos) << what;
                            EXPECT_EQ(effect.noise().config().kind, before.kind) << what;
                            EXPECT_EQ(effect.noise().config().edges, before.edges) << what;
                            ++refused;
                            continue;
                        }
                        effect.setNoise(noise);
                        effect.update(0.1);
                        for (float h : readHeights(cl(), effect.noise()))
                            ASSERT_TRUE(h >= 0.0f && h <= 1.0f) << what << ": height " << h;
                        target.bind();
                        target.clear({0.0f, 0.0f, 0.0f, 1.0f});
                        renderer.draw(plane, glm::mat4(1.0f), effect.layers(), effect.material(), camera, {});
                        const Image image = target.readColor();
                        double sum = 0, sum2 = 0;
                        for (float p : image.pixels) sum += p, sum2 += double(p) * p;
                        const double n = double(image.pixels.size()), spread = std::sqrt(sum2 / n - (sum / n) * (sum / n));
                        EXPECT_GT(spread, 0.02) << what << ": a flat image";
                        ++rendered;
                    }
    EXPECT_GT(rendered, 60);
    EXPECT_GT(refused, 0) << "simplex noise has no tiling variant";
}

TEST_F(NoiseSurface, ATilingNoiseContinuesAcrossItsEdgesToFloatRounding) {
    for (const auto& [kind, edges] : {std::pair{NoiseKind::Perlin, EdgeMode::Wrap}, std::pair{NoiseKind::Psrd, EdgeMode::Wrap},
                                      std::pair{NoiseKind::Perlin, EdgeMode::WrapU}})
        for (const float warp : {0.0f, 0.7f}) {
            NoiseSurfaceEffect effect(cl(), {.noise = {.width = 96, .height = 64, .kind = kind, .frequency = 5.0f,
                                                        .octaves = 4, .warp = warp, .edges = edges}});
            effect.update(0.25);
            const NoiseField& field = effect.noise();
            const NoiseConfig& c = field.config();
            const std::vector<float> h = readHeights(cl(), field);
            const int W = c.width, H = c.height;
            const float t = field.timeCoordinate(field.time());
            auto shared = [&, edges = edges](float u, float v) {
                return hfx_noise_texel(int(c.kind), int(c.fractal), u, v, c.frequency, c.frequencyY(), wrapsU(edges),
                                       wrapsV(edges), t, c.octaves, c.lacunarity, c.gain, c.warp);
            };
            double acrossU = 0, acrossV = 0;
            for (int y = 0; y < H; ++y) // the texel one period to the right of the last column is column 0
                acrossU = std::max(acrossU, double(std::abs(shared((W + 0.5f) / W, (y + 0.5f) / H) - h[size_t(y) * W])));
            for (int x = 0; x < W; ++x)
                acrossV = std::max(acrossV, double(std::abs(shared((x + 0.5f) / W, (H + 0.5f) / H) - h[size_t(x)])));
            const std::string what = str("kind ", int(kind), " edges ", edgeModeName(edges), " warp ", warp);
            EXPECT_LT(acrossU, 2e-5) << what;
            if (wrapsV(edges))
                EXPECT_LT(acrossV, 2e-5) << what;
            else
                EXPECT_GT(acrossV, 1e-3) << what << ": matched across v, which does not tile";
        }
}

} // namespace
} // namespace hfx::test
