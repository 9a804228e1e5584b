#include "hfx/tools/AccuracyMaps.h"

#include "hfx/compute/DecalMap.h"
#include "hfx/compute/NoiseField.h"
#include "hfx/core/Error.h"
#include "hfx/effects/BrickWall.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

namespace hfx {
namespace {

std::vector<float> readBuffer(ClContext& cl, const cl::Buffer& buffer, size_t n) {
    std::vector<float> out(n);
    cl.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, n * sizeof(float), out.data());
    return out;
}

} // namespace

std::vector<AccuracyMap> accuracyMaps(ClContext& cl, int n) {
    if (n < 16 || !std::has_single_bit(unsigned(n)))
        throw Error(str("accuracyMaps: the maps' size must be a power of two from 16 up, got ", n));
    std::vector<AccuracyMap> maps;
    maps.push_back({"smooth waves", smoothWaves(n)});
    const BrickWallMaps bricks = makeBrickWall({.size = n});
    maps.push_back({"bricks", bricks.heights});
    NoiseField noise(cl, {.width = n, .height = n, .frequency = 6.0f, .octaves = 5});
    std::vector<float> noisy = readBuffer(cl, noise.buffer(), size_t(n) * n);
    for (float& h : noisy) h = std::clamp(0.5f + 0.9f * (h - 0.5f), 0.0f, 1.0f);
    maps.push_back({"noise", noisy});
    DecalMap decals(cl, {.width = n, .height = n}, bricks.heights);
    for (int i = 0; i < 40; ++i)
        decals.addBulletHole({.u = float(std::fmod(0.137 * i * 7.3, 1.0)), .v = float(std::fmod(0.291 * i * 3.1, 1.0)),
                              .radius = 0.02f, .depth = 0.5f});
    decals.addExplosion({.u = 0.6f, .v = 0.4f, .radius = 0.08f, .debris = 30});
    decals.step(1.0 / 30.0);
    maps.push_back({"damaged wall", readBuffer(cl, decals.buffer(), size_t(n) * n)});
    return maps;
}

std::vector<float> smoothWaves(int n) {
    std::vector<float> sines(size_t(n) * n);
    const double k = 2.0 * std::numbers::pi / n;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            sines[size_t(y) * n + x] = float(0.5 + 0.22 * std::sin(k * (3 * x + 1 * y) + 0.3) +
                                             0.13 * std::sin(k * (-2 * x + 5 * y) + 1.1) +
                                             0.07 * std::sin(k * (7 * x + 4 * y) + 2.0));
    return sines;
}

glm::vec3 accuracyLight(float degreesOffNormal) {
    const float off = degreesOffNormal * std::numbers::pi_v<float> / 180.0f;
    return {std::sin(off) * 0.8f, std::cos(off), std::sin(off) * 0.6f};
}

} // namespace hfx
