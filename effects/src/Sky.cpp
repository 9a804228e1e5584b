#include "hfx/effects/Sky.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

// Mirrors shaders/shade/sky.glsl operation for operation, in float: change both together
// (tests/SkyTest.cpp holds the shader to this file).

namespace hfx {
namespace {

float smoothstep(float e0, float e1, float x) {
    const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

/// hfx_cell_value: pcg2d, in integers (the same bits as any device's).
float cellValue(glm::vec2 cell) {
    std::uint32_t x = std::uint32_t(std::int32_t(cell.x)) * 1664525u + 1013904223u;
    std::uint32_t y = std::uint32_t(std::int32_t(cell.y)) * 1664525u + 1013904223u;
    x += y * 1664525u;
    y += x * 1664525u;
    x ^= x >> 16u;
    y ^= y >> 16u;
    x += y * 1664525u;
    y += x * 1664525u;
    x ^= x >> 16u;
    return float(x >> 8u) * (1.0f / 16777216.0f);
}

/// hfx_value_noise
float valueNoise(glm::vec2 q) {
    const glm::vec2 cell = glm::floor(q), f = q - cell, s = f * f * (3.0f - 2.0f * f);
    const float a = cellValue(cell), b = cellValue(cell + glm::vec2(1, 0));
    const float c = cellValue(cell + glm::vec2(0, 1)), d = cellValue(cell + glm::vec2(1, 1));
    const float ab = a + (b - a) * s.x, cd = c + (d - c) * s.x;
    return ab + (cd - ab) * s.y;
}

// The quantiles of the clouds' noise (the octaves' sum over their amplitudes' sum), measured over
// 2^22 random points of it (this file's noise, points in [-1000, 1000]^2): every 1% in the tails,
// where the distribution is steep (0 to 5%, 95 to 100%), and every 5% between them (5 to 95%).
constexpr std::array<float, 6> kLowTail{0.0357f, 0.2258f, 0.2512f, 0.2685f, 0.2818f, 0.2932f};
constexpr std::array<float, 19> kQuantiles{0.2932f, 0.3340f, 0.3634f, 0.3877f, 0.4093f, 0.4290f, 0.4477f,
                                           0.4656f, 0.4829f, 0.5001f, 0.5172f, 0.5346f, 0.5524f, 0.5711f,
                                           0.5908f, 0.6123f, 0.6365f, 0.6660f, 0.7068f};
constexpr std::array<float, 6> kHighTail{0.7068f, 0.7181f, 0.7315f, 0.7485f, 0.7740f, 0.9359f};

/// The table's value at `at` entries along it, interpolated.
template <size_t N> float interpolated(const std::array<float, N>& table, float at) {
    const int i = std::clamp(int(at), 0, int(N) - 2);
    return table[size_t(i)] + (table[size_t(i) + 1] - table[size_t(i)]) * (at - float(i));
}

} // namespace

float cloudThreshold(float cover) {
    // The sky is clouded where the noise is above its (1 - cover) quantile.
    const float share = 1.0f - std::clamp(cover, 0.0f, 1.0f);
    if (share < 0.05f) return interpolated(kLowTail, share * 100.0f);
    if (share > 0.95f) return interpolated(kHighTail, (share - 0.95f) * 100.0f);
    return interpolated(kQuantiles, share * 20.0f - 1.0f);
}

namespace {

/// hfx_cloud_cover: the clouds over the layer's point `p` (cloud heights, before the drift), seen
/// over a patch `across` by `along` of it.
CloudSample cover(const WaterLook& look, glm::vec2 p, float across, float along) {
    p = (p + look.cloudDrift) * look.cloudScale;
    // The octaves' amplitudes 1/2, 1/4, ...: their sum and the sum of their squares.
    const float sum = 1.0f - std::exp2(-float(HFX_CLOUD_OCTAVES));
    const float squares = (1.0f - std::exp2(-2.0f * float(HFX_CLOUD_OCTAVES))) / 3.0f;
    float wavelength = 1.0f / look.cloudScale, amplitude = 0.5f, value = 0.5f * sum, kept = 0.0f;
    for (int i = 0; i < HFX_CLOUD_OCTAVES; ++i) {
        const float a = along / wavelength, b = across / wavelength;
        float keep = std::sqrt(1.0f / std::sqrt((1.0f + a * a) * (1.0f + b * b))); // of the deviation
        keep *= smoothstep(0.15f, 0.35f, keep);
        if (!(keep > 0.0f)) break; // the finer octaves keep less still
        value += amplitude * keep * (valueNoise(p + 17.0f * float(i)) - 0.5f);
        kept += amplitude * amplitude * keep * keep;
        // Turned by atan(3/4) and doubled: the next octave's grid lies across this one's.
        p = glm::vec2(1.6f * p.x - 1.2f * p.y, 1.2f * p.x + 1.6f * p.y);
        amplitude *= 0.5f;
        wavelength *= 0.5f;
    }
    value /= sum;
    const float lost = std::max(squares - kept, 0.0f);
    const float lostVariance = float(HFX_CLOUD_OCTAVE_VARIANCE) * lost / (sum * sum);
    // The edge: a ramp 0.04 either side of the threshold, widened as a Gaussian of the lost
    // octaves' variance would widen it (a smoothstep's variance is a fifth of its half-width's
    // square). The thickness ramps over 0.2 past the threshold, up to 0.45 under a deck that
    // covers nearly all the sky (a low threshold).
    const float threshold = cloudThreshold(look.cloudCover);
    const float width = std::sqrt(0.04f * 0.04f + 5.0f * lostVariance);
    return {smoothstep(threshold - width, threshold + width, value),
            std::clamp((value - threshold) / (std::max(0.2f, 0.45f - threshold) + width), 0.0f, 1.0f)};
}

/// hfx_clouds' patch of the layer: where the direction meets it, in cloud heights, and the patch
/// of it the spread covers there: spread / y across, foreshortened by y again along the view.
struct LayerPatch {
    glm::vec2 p;
    float across, along;
};
LayerPatch layerPatch(const WaterLook& look, glm::vec3 eye, glm::vec3 dir, float spread) {
    const float y = std::max(dir.y, 0.01f);
    const glm::vec2 p = glm::vec2(eye.x, eye.z) / look.cloudHeight +
                        glm::vec2(dir.x, dir.z) / y * (1.0f - eye.y / look.cloudHeight);
    return {p, spread / y, spread / (y * y)};
}

/// hfx_clouds' fade towards the horizon: the share of a sample `dir` keeps (y > 0), the rest the
/// layer's mean.
float nearness(glm::vec3 dir) { return 1.0f - std::exp(-8.0f * dir.y); }
float fade(float value, float mean, float near) { return mean + (value - mean) * near; }

/// hfx_clouds' (density, thickness) of the sample `sharp` in direction `dir`, faded into the
/// layer's mean towards the horizon.
CloudSample faded(const WaterLook& look, CloudSample sharp, glm::vec3 dir) {
    const float near = nearness(dir);
    return {fade(sharp.density, look.cloudCover, near), fade(sharp.thickness, cloudMeanThickness(look), near)};
}

/// hfx_cloud_veiled: the veil over an overcast deck fills the layer's gaps, half as thick as the
/// deck's mean cloud and lit through it; `sunward` becomes the two's mean with the density.
CloudSample veiled(const WaterLook& look, CloudSample layer, float& sunward) {
    const float veil = cloudVeil(look) * (1.0f - layer.density), density = layer.density + veil;
    const float share = density > 0.0f ? layer.density / density : 0.0f;
    sunward = sunward * share + look.cloudCover * (1.0f - share);
    return {density, layer.thickness * share + 0.5f * cloudMeanThickness(look) * (1.0f - share)};
}

/// hfx_clouds' (density, thickness) over `patch`, faded.
CloudSample clouds(const WaterLook& look, const LayerPatch& patch, glm::vec3 dir) {
    return faded(look, cover(look, patch.p, patch.across, patch.along), dir);
}

} // namespace

float cloudVeil(const WaterLook& look) { return smoothstep(0.7f, 1.0f, look.cloudCover); }

float cloudMeanThickness(const WaterLook& look) {
    const float c2 = look.cloudCover * look.cloudCover, c4 = c2 * c2;
    return 0.15f + 0.55f * look.cloudCover + 0.17f * (c4 * c4 * c4);
}

glm::vec2 cloudSunwardStep(const WaterLook& look, const DirectionalLight& light) {
    const glm::vec3 l = glm::normalize(light.direction);
    const glm::vec2 reach = glm::vec2(l.x, l.z) * (float(HFX_CLOUD_DEPTH) / std::max(l.y, 0.01f));
    const float most = 0.5f / look.cloudScale, length2 = glm::dot(reach, reach);
    return length2 > most * most ? reach * (most / std::sqrt(length2)) : reach;
}

CloudSample cloudSample(const WaterLook& look, glm::vec3 eye, glm::vec3 dir, float spread) {
    if (!(look.cloudCover > 0.0f) || !(dir.y > 0.0f)) return {};
    return clouds(look, layerPatch(look, eye, dir, spread), dir);
}

float cloudSunlight(const WaterLook& look, const DirectionalLight& light, glm::vec3 position, float footprint) {
    const glm::vec3 l = glm::normalize(light.direction);
    if (!(look.cloudCover > 0.0f) || !(l.y > 0.0f)) return 1.0f;
    // hfx_cloud_sunlight: where the sun's ray from the point meets the layer, over the pixel's
    // patch or the sun's penumbra there.
    const float y = std::max(l.y, 0.01f), reach = (1.0f - position.y / look.cloudHeight) / y;
    const float size = footprint / look.cloudHeight, penumbra = 2.0f * float(HFX_SUN_RADIUS) * reach;
    const glm::vec2 p = glm::vec2(position.x, position.z) / look.cloudHeight + glm::vec2(l.x, l.z) * reach;
    float sunward = 0.0f;
    const CloudSample c = veiled(look, cover(look, p, std::max(size, penumbra), std::max(size, penumbra / y)), sunward);
    return 1.0f - c.density * (0.7f + 0.25f * c.thickness);
}

glm::vec3 skyColor(const WaterLook& look, const DirectionalLight& light, glm::vec3 eye, glm::vec3 dir, float spread) {
    // hfx_clear_sky: most of the change happens near the horizon, as in a clear sky.
    const glm::vec3 lightDir = glm::normalize(light.direction);
    const float up = std::clamp(dir.y, 0.0f, 1.0f);
    const glm::vec3 base = look.skyHorizon + (look.skyZenith - look.skyHorizon) * std::pow(up, 0.4f);
    const float sun = std::max(glm::dot(glm::normalize(dir), lightDir), 0.0f);
    const glm::vec3 clear =
        base + look.sunGlow * light.color * (0.5f * std::pow(sun, 48.0f) + 0.12f * std::pow(sun, 6.0f));
    if (!(look.cloudCover > 0.0f)) return clear;
    // At and below the horizon the clouds' far field continues: the layer's mean.
    CloudSample cloud{look.cloudCover, cloudMeanThickness(look)};
    float sunward = look.cloudCover;
    if (dir.y > 0.0f) {
        const LayerPatch patch = layerPatch(look, eye, dir, spread);
        const CloudSample sharp = cover(look, patch.p, patch.across, patch.along);
        // hfx_clouds' `sunward`: the cloud's density where its direct light came through, over a
        // cell at least (only where there is a cloud).
        const float cell = 1.0f / look.cloudScale;
        const float through = sharp.density > 0.0f ? cover(look, patch.p + cloudSunwardStep(look, light),
                                                           std::max(patch.across, cell), std::max(patch.along, cell))
                                                         .density
                                                   : 0.0f;
        cloud = faded(look, sharp, dir);
        sunward = fade(through, look.cloudCover, nearness(dir));
    }
    cloud = veiled(look, cloud, sunward);
    // hfx_cloud_color
    const float elevation = std::clamp(lightDir.y, 0.0f, 1.0f);
    const glm::vec3 ambient = look.skyHorizon + (look.skyZenith - look.skyHorizon) * 0.3f;
    const float shade = 0.7f + 0.3f * (1.0f - cloud.thickness);
    const glm::vec3 lit = shade * (0.5f * ambient + (1.0f - float(HFX_CLOUD_SUNWARD_SHADE) * sunward) *
                                                         (0.55f + 0.45f * elevation) * light.color);
    const glm::vec3 silver = look.sunGlow * light.color * (1.0f - cloud.thickness) *
                             (1.5f * std::pow(sun, 16.0f) + 0.3f * std::pow(sun, 4.0f));
    return clear + (lit + silver - clear) * cloud.density;
}

} // namespace hfx
