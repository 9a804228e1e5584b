#pragma once
// The procedural sky of a water look (shaders/shade/sky.glsl) on the CPU, with the same float
// operations as the shader: its colour in a direction, how much of it its clouds cover there
// (WaterLook::cloudCover), and how much of the sun's light they let through to a point. For an
// engine that matches its fog, its ambient light or its own sky to the one the water reflects,
// for gameplay that asks whether a point of the sky is overcast or a point of the sea in a cloud's
// shadow, and for the tests that hold the shaders to it.
//
// Thread: any (no GL).

#include "hfx/effects/SurfaceRenderer.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace hfx {

/// The clouds are a value noise over a layer WaterLook::cloudHeight over the world's y = 0:
/// HFX_CLOUD_OCTAVES octaves, each twice the last's frequency at half its amplitude and turned
/// against it so that no grid lines up, the first with WaterLook::cloudScale cells per cloud
/// height, moved by WaterLook::cloudDrift. What the clouds cover in direction `dir` (unit, y up)
/// from the eye at `eye` (world), seen by a pixel whose directions spread over `spread` radians
/// (a sky pixel's width; a reflection's, widened by the water's roughness): `density` 0 (clear)
/// to 1 (the cloud hides the sky), and `thickness`, how far into the cloud the point lies (0 at
/// its edge, 1 in its middle), which darkens its underside. Each octave keeps about the share of
/// its variance that a box the size of the pixel's patch of the layer leaves it (spread / y
/// across, spread / y^2 along the view), and what the octaves no longer show softens the edge
/// instead: about the share of the pixel under cloud, not an aliased sample. Towards the horizon,
/// where the layer is seen edge on, both fade into the layer's mean (1 - e^(-8 y) of the sample
/// kept): the density into the cover, the thickness into the clouds' mean, 0.15 + 0.55 cover +
/// 0.17 cover^12 (fitted to the mean measured over the layer: 0.26 at a cover of 0.2, 0.76 at
/// 0.95, 0.90 at 1). 0 below the horizon and
/// where the look has no clouds. The layer's alone: the veil over an overcast deck (cloudVeil)
/// is not in it.
struct CloudSample {
    float density = 0.0f;
    float thickness = 0.0f;
};
CloudSample cloudSample(const WaterLook& look, glm::vec3 eye, glm::vec3 dir, float spread);

/// How much of the clear sky in the layer's gaps a higher veil hides (a storm's altostratus and
/// nimbostratus over its deck): 0 up to a cover of 0.7, rising smoothly to 1 at a full cover. The
/// gaps of an overcast sky are a paler grey than its clouds, not blue: skyColor draws them as a
/// cloud half as thick as the deck's mean, lit through it, and cloudSunlight dims the sun's light
/// through them as that cloud does (at a full veil to 0.3 less a quarter of its thickness).
float cloudVeil(const WaterLook& look);

/// The thickness of the layer's clouds, averaged over the layer: 0.15 + 0.55 cover + 0.17 cover^12
/// (fitted to the mean measured over it, CloudSample's). What the layer fades into at the horizon,
/// and the veil's thickness is half of it. The shaders read it and cloudVeil as uniforms
/// (hfx::WaterUniforms), so both are written once, here.
float cloudMeanThickness(const WaterLook& look);

/// The share of `light`'s direct light that the clouds let through to the world point
/// `position`, a pixel there spanning `footprint` world units (what the water's shading
/// multiplies the sun's light by): 1 where the sun's ray from it meets no cloud, 0.3 at a cloud's
/// edge down to 0.05 in its thick middle (the veil of an overcast deck, cloudVeil, as a thin
/// cloud), over the pixel's patch or the penumbra of the sun's disc (HFX_SUN_RADIUS), whichever
/// is wider; 1 without clouds or with the sun under the horizon.
float cloudSunlight(const WaterLook& look, const DirectionalLight& light, glm::vec3 position, float footprint);

/// Where a clouded point's direct light came through the cloud, as a step along the layer in
/// cloud heights: HFX_CLOUD_DEPTH cloud heights up the sun's ray, at most half a noise cell
/// (1 / cloudScale). The sky reads the cloud there to shade a cloud's far side (skyColor; the
/// shaders get it in their water block). Zero for a sun straight overhead.
glm::vec2 cloudSunwardStep(const WaterLook& look, const DirectionalLight& light);

/// The value of the clouds' noise above which the sky is clouded, for `cover` (0 to 1): its
/// quantile, so that `cover` of the sky overhead lies under a cloud's middle (density > 0.5).
/// Read from a table of the noise's distribution (measured over 2^22 points, every 5% and every 1%
/// in its tails, interpolated).
float cloudThreshold(float cover);

/// The sky's colour (linear RGB) in direction `dir` from `eye` under `light`: the look's
/// gradient, the sun's glow and, where the look has them, its clouds seen over `spread` radians,
/// darker where thick and where the sun's light reaching them crossed more of the cloud (half a
/// cell up the sun's ray: a cloud's sunward side is bright, its far side grey), and over an
/// overcast deck the veil in its gaps (cloudVeil). At the horizon
/// and below it the layer's mean continues (the cover's share of the clouds' mean colour over
/// the clear sky's): the colour the water's haze fades into, so an overcast horizon is grey. A
/// level `dir` gives an engine the colour its fog should take to meet the sea and the sky.
/// The environment image of a look that has one is not read: what it returns is the procedural
/// sky's.
glm::vec3 skyColor(const WaterLook& look, const DirectionalLight& light, glm::vec3 eye, glm::vec3 dir, float spread);

} // namespace hfx
