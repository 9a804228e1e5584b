// Long runs: each user for HFX_SOAK_STEPS updates (default 10,000; the planet 4,000: each of its
// updates is a gas step of some 40 kernel launches and the advected detail's, about 50 ms on two
// cores against 5-8 ms for the others: at 8,000 its soak alone took 404 s, a third of CI's; beside
// the other tests the ocean's 20,000 took 370 s and the wall's 196 s, and CI ran 20.5 minutes) with
// random parameter changes and stamp storms. Nothing may go NaN or leave [0,1], and memory must stay flat: the resident set
// at the end is within a bound of the one after warm-up (both printed; scripts/soak.sh shows
// them).

#include "support/Fixtures.h"

#include "hfx/core/Gl.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/Random.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/DecalWallEffect.h"
#include "hfx/effects/GasPlanetEffect.h"
#include "hfx/effects/OceanEffect.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace hfx::test {
namespace {

long residentKiB() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
    return -1;
}

int soakSteps(int userDefault) {
    const char* env = std::getenv("HFX_SOAK_STEPS");
    return env ? std::max(100, std::atoi(env)) : userDefault;
}

/// Every texel finite, heights in [0,1], normals unit length.
void checkField(const SurfaceTextures& textures, const char* what, int step) {
    const std::vector<float> texels = readSurface(textures);
    for (size_t i = 0; i < texels.size(); i += 4) {
        const float h = texels[i + 3];
        const double n = std::sqrt(double(texels[i]) * texels[i] + double(texels[i + 1]) * texels[i + 1] +
                                   double(texels[i + 2]) * texels[i + 2]);
        ASSERT_TRUE(h >= 0.0f && h <= 1.0f) << what << " step " << step << " texel " << i / 4 << " h " << h;
        ASSERT_NEAR(n, 1.0, 1e-3) << what << " step " << step << " texel " << i / 4;
    }
}

class Soak : public DeviceTest {
protected:
    template <typename Effect, typename Disturb>
    void soak(const char* what, int defaultSteps, Effect& effect, const Mesh& mesh, Disturb&& disturb) {
        const int steps = soakSteps(defaultSteps);
        RenderTarget target(160, 90);
        SurfaceRenderer renderer;
        const Camera camera = Camera::orbit({0, 0, 0}, 3.0f, 0.4f, 0.4f);
        long warm = 0;
        for (int step = 0; step < steps; ++step) {
            disturb(step);
            effect.update(1.0 / 30.0);
            if (step % 100 == 0) {
                target.bind();
                target.clear();
                const std::vector<SurfaceLayer> layers = effect.layers();
                renderer.draw(mesh, glm::mat4(1.0f), layers, effect.material(), camera, {});
            }
            if (step % 1000 == 999 || step == steps - 1) {
                checkField(effect.textures(), what, step);
                if (::testing::Test::HasFatalFailure()) return;
            }
            if (step == std::min(1000, steps / 10)) warm = residentKiB();
        }
        glFinish();
        const long end = residentKiB();
        std::printf("[soak %s] %d steps, resident set %ld KiB after warm-up, %ld KiB at the end\n", what, steps,
                    warm, end);
        EXPECT_LT(end - warm, 32 * 1024) << what << ": memory grew by " << (end - warm) << " KiB";
    }
};

TEST_F(Soak, OceanWithWindChanges) {
    OceanEffect ocean(cl(), {.ocean = {.size = 128, .cascades = 2, .cascadeRatio = 2.6f}});
    SplitMix64 random(11);
    const Mesh plane(makePlane({.size = 8.0f, .texcoordScale = 2.0f}));
    soak("ocean", 10000, ocean, plane, [&](int step) {
        if (step % 50 == 0) ocean.setWind(float(random.uniform(1.0, 40.0)), float(random.uniform(-3.2, 3.2)));
    });
}

TEST_F(Soak, DecalWallUnderStampStorms) {
    // A small budget, so the storms evict, and fast heal curves, so every channel heals.
    DamageLogConfig damage{.budget = 512};
    damage.look.height = {.start = 1.0, .duration = 10.0, .end = 0.0f};
    damage.look.scorch = {.start = 0.5, .duration = 5.0, .end = 0.2f};
    DecalWallEffect wall(cl(), {.bricks = {.size = 128}, .damage = damage});
    SplitMix64 random(12);
    const Mesh plane(makePlane({.size = 4.0f, .texcoordScale = 2.0f}));
    soak("decals", 10000, wall, plane, [&](int step) {
        const int burst = step % 97 == 0 ? 3000 : 20;
        std::vector<ImpactEvent> holes(static_cast<size_t>(burst));
        for (ImpactEvent& h : holes)
            h = {.u = float(random.next()), .v = float(random.next()), .radius = float(random.uniform(0.002, 0.03)),
                 .seed = random.nextBits()};
        wall.impacts(holes);
        if (step % 31 == 0) wall.explode(random.next(), random.next(), random.nextBits());
        if (step % 500 == 250) {
            SurfaceMaterial m = wall.material();
            m.depthScale = float(random.uniform(0.01, 0.2));
            wall.setMaterial(m);
        }
        if (step % 5000 == 4999) wall.clearDamage();
    });
}

TEST_F(Soak, GasPlanetWithStorms) {
    // The advected detail at one texel per gas cell: its advection and regeneration run every
    // update as at any scale, without the 16x larger surface (and CI minutes) of the device's 4.
    GasPlanetEffect planet(cl(), {.gas = {.width = 128, .height = 64, .pressure = GasPressure::Jacobi,
                                          .pressureIterations = 20, .vorticity = 0.5f,
                                          .jetSpeed = 20.0f, .initialBands = 6.0f},
                                  .stormsPerSecond = 6.0f, .detail = {.scale = 1}});
    SplitMix64 random(13);
    const Mesh sphere(makeSphere({.segments = 32, .rings = 16}));
    soak("planet", 4000, planet, sphere, [&](int step) {
        if (step % 40 == 0) planet.addStorm(float(random.next()), float(random.uniform(0.05, 0.95)), random.next() < 0.5);
    });
}

} // namespace
} // namespace hfx::test
