#pragma once
// The C++ mirrors of the surface shaders' std140 uniform blocks: HfxSurface
// (shaders/surface/uniforms.glsl, binding 0), HfxWater (shaders/shade/sky.glsl, binding 1),
// HfxRings (binding 2), HfxPlanet (shaders/shade/rings.glsl, binding 3) and HfxShadows
// (shaders/surface/shadowmap.glsl, binding 4). SurfaceRenderer fills
// them once per draw into uniform buffers; the layout is checked at compile time here (std140: a
// vec3 takes 16 bytes unless a scalar follows it) and against the driver's own offsets by a test.
//
// Thread: any (plain values).

#include "hfx/core/EdgeMode.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>

namespace hfx {

struct SurfaceUniforms {
    glm::mat4 model{1.0f};
    glm::mat4 viewProj{1.0f};
    glm::mat4 normalMatrix{1.0f};
    glm::vec4 patchBounds{0.0f, 0.0f, 1.0f, 1.0f};
    glm::vec3 cameraPos{0.0f};
    float depthScale = 0.0f;
    glm::vec3 lightDir{0.0f, 1.0f, 0.0f};
    float normalScale = 1.0f;
    glm::vec3 lightColor{1.0f};
    float lodThreshold = 0.0f;
    glm::vec3 ambient{0.0f};
    float shadowSharpness = 1.0f;
    glm::vec2 normalDecode{1.0f, 0.0f};
    float specularStrength = 0.0f;
    float specularPower = 1.0f;
    float silhouetteFade = 0.0f;
    int minSamples = 1;
    int maxSamples = 1;
    int shadowSamples = 1;
    int clipToPatch = 0;
    float varianceFloor = 0.0f;
    /// The field's texel indexing (setField): its last texel, and per axis the mask a cell index is
    /// anded with before it is clamped to the last texel, fieldLast where the edges wrap and -1
    /// where they clamp. Unset, every cell reads texel 0. std140 aligns an ivec2 to 8 bytes.
    alignas(8) glm::ivec2 fieldLast{0, 0};
    glm::ivec2 wrapMask{-1, -1};
    float untracedHeight = 0.0f;
    float pixelBudget = 0.0f; ///< SurfaceMaterial::pixelBudget
    glm::vec4 layerScale{1.0f};
    glm::vec4 layerWeight{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec4 layerSlope{0.0f};
    glm::vec4 layerLevel{0.0f};
    /// 1: colours written linear and unclamped (a float or sRGB target: hfx::ColorOutput); 0:
    /// clamped and gamma-encoded.
    int linearOutput = 0;
    /// The texel shadows' light (ShadowLight: uvPerClimb, penumbra, slack; read where
    /// HFX_TEXEL_SHADOWS is 1). (std140 aligns a vec4 to 16 bytes.)
    alignas(16) glm::vec4 shadowLight{0.0f};
    /// 1 / the field's size (setField): where the exact tracer gathers a level-0 cell's samples.
    glm::vec2 texelSize{1.0f};
    /// The exact tracer's walks in a compute pass (ExactTracer, HFX_COMPUTE_TRACE): the viewport's
    /// width, the draw's stamp on the slots it wrote, the viewport's origin and height.
    int traceWidth = 0;
    std::uint32_t traceStamp = 0;
    glm::ivec2 traceOrigin{0};
    int traceHeight = 0;
    /// 1 where the view's depth is reversed (Camera::reversedZ: the near plane at depth 1, GL's
    /// [0, 1] clip depth), for the beam start's rays; the draw's own depth writes follow
    /// HFX_REVERSED_Z. (It also rounds the block's size to a multiple of 16 bytes, as std140 does.)
    int reversedZ = 0;
    /// The screen motion a draw writes (SurfaceRenderer::setMotionOutput, HFX_MOTION_OUTPUT): the
    /// world of this frame to the previous frame's clip space (its view-projection, the mesh's
    /// previous model times this one's inverse), and the jitter this frame's u_viewProj holds.
    glm::mat4 previousFromWorld{1.0f};
    glm::vec2 jitter{0.0f};
    /// A triplanar mapping's (SurfaceMaterial::triplanar, HFX_TRIPLANAR): texcoords per unit of
    /// the mesh's own space, and the blend weights' power.
    float triplanarScale = 1.0f;
    float triplanarSharpness = 1.0f;
    /// An orthographic camera's (Camera::orthographic): 1, and the unit direction towards the
    /// eye, the same for every point (hfx_to_eye); 0: the eye is cameraPos.
    glm::vec3 towardsEye{0.0f};
    int orthographic = 0;

    /// The field the heights' accessors index (surface/heights.glsl): `size` texels (powers of
    /// two where the pyramid is read), its edges wrapped or clamped.
    constexpr void setField(glm::ivec2 size, EdgeMode edges) {
        fieldLast = size - 1;
        wrapMask = {wrapsU(edges) ? fieldLast.x : -1, wrapsV(edges) ? fieldLast.y : -1};
        texelSize = 1.0f / glm::vec2(size);
    }
};

struct WaterUniforms {
    glm::vec3 deepColor{0.0f};
    float fresnelF0 = 0.0f;
    glm::vec3 shallowColor{0.0f};
    float glintPower = 1.0f;
    glm::vec3 skyZenith{0.0f};
    float glintStrength = 0.0f;
    glm::vec3 skyHorizon{0.0f};
    float hazeDistance = 1.0f;
    int foam = 0;
    float sunGlow = 0.0f;
    float translucency = 0.0f;
    float foamCells = 0.0f;
    glm::vec3 foamColor{1.0f};
    float foamRoughness = 0.0f;
    glm::vec2 foamDrift{0.0f};
    glm::vec2 windDirection{1.0f, 0.0f};
    float spindrift = 0.0f;
    float streakCells = 0.0f;
    glm::vec2 windDirectionFrom{1.0f, 0.0f};
    float spindriftFrom = 0.0f;
    float cloudHeight = 1.0f;     ///< WaterLook::cloudHeight (the clouds: HFX_SKY 1)
    glm::vec2 cloudDrift{0.0f};   ///< WaterLook::cloudDrift
    float cloudScale = 1.0f;
    float cloudThreshold = 1.0f;  ///< hfx::cloudThreshold(WaterLook::cloudCover): where the noise is clouded
    glm::vec2 cloudSunward{0.0f}; ///< hfx::cloudSunwardStep(WaterLook, light): where a cloud's light came through
    float cloudCover = 0.0f;      ///< WaterLook::cloudCover: what the layer fades into at the horizon
    float cloudVeil = 0.0f;       ///< hfx::cloudVeil(WaterLook): the veil over an overcast deck's gaps
    float cloudMeanThickness = 0.0f; ///< hfx::cloudMeanThickness(WaterLook): the layer's clouds' mean
    float padding = 0.0f;
};

/// HfxRings (shaders/surface/uniforms.glsl, binding 2): the water's impact rings.
inline constexpr int kMaxWaterRings = 8;
struct RingUniforms {
    glm::vec4 shape[kMaxWaterRings]{}; ///< centre u, v (mesh texcoords), radius, width (texcoords)
    glm::vec4 wave[kMaxWaterRings]{};  ///< wavenumber (radians per texcoord), amplitude (h units), foam, 0
    int count = 0;
    int padding[3] = {0, 0, 0};
};

/// HfxPlanet (shaders/shade/rings.glsl, binding 3): a planet's rings, in world space, for the
/// planet's shading (their shadow) and the rings' draw (the planet's shadow on them).
struct PlanetUniforms {
    glm::vec3 planetCentre{0.0f};
    float planetRadius = 1.0f;
    glm::vec3 ringAxis{0.0f, 1.0f, 0.0f};
    float ringInner = 0.0f;
    float ringOuter = 0.0f; ///< 0: no rings
    float sunRadius = 0.0f; ///< radians
    float ringTexels = 1.0f;
    float ringShine = 0.0f; ///< 1: the rings light the planet (RingShine's table)
};

/// HfxShadows (shaders/surface/shadowmap.glsl, binding 4): the shadow maps of a draw's light
/// (ShadowCascades, or a ShadowMap as one cascade), read where HFX_SHADOW_MAP is 1 or 2.
inline constexpr int kMaxShadowCascades = 4;
struct ShadowUniforms {
    glm::mat4 viewProj[kMaxShadowCascades]{}; ///< world to each cascade's clip space
    glm::vec4 tile[kMaxShadowCascades]{};     ///< its viewport in the texture: x, y, width, height in [0, 1]
    /// Per cascade: the lookup's normal offset (world units, 1.5 of its texels), its depth bias
    /// (window depth, the offset's), its layer of an array texture, and the filter's reach in its
    /// tile (1.5 texels over the tile's width).
    glm::vec4 lookup[kMaxShadowCascades]{};
    glm::vec2 texel{0.0f}; ///< 1 / the texture's size (the filter's tap spacing)
    int count = 0;         ///< cascades, finest first; 0: the light is whole
    int reversedZ = 0;     ///< 1: the maps' depth is reversed (near at 1, compared greater)
};

// std140 offsets of the GLSL blocks, member by member where alignment could slip.
static_assert(offsetof(SurfaceUniforms, patchBounds) == 192);
static_assert(offsetof(SurfaceUniforms, depthScale) == 220);
static_assert(offsetof(SurfaceUniforms, shadowSharpness) == 268);
static_assert(offsetof(SurfaceUniforms, normalDecode) == 272);
static_assert(offsetof(SurfaceUniforms, silhouetteFade) == 288);
static_assert(offsetof(SurfaceUniforms, varianceFloor) == 308);
static_assert(offsetof(SurfaceUniforms, fieldLast) == 312);
static_assert(offsetof(SurfaceUniforms, wrapMask) == 320);
static_assert(offsetof(SurfaceUniforms, pixelBudget) == 332);
static_assert(offsetof(SurfaceUniforms, layerScale) == 336);
static_assert(offsetof(SurfaceUniforms, linearOutput) == 400);
static_assert(offsetof(SurfaceUniforms, shadowLight) == 416);
static_assert(offsetof(SurfaceUniforms, texelSize) == 432);
static_assert(offsetof(SurfaceUniforms, traceWidth) == 440);
static_assert(offsetof(SurfaceUniforms, traceOrigin) == 448);
static_assert(offsetof(SurfaceUniforms, previousFromWorld) == 464);
static_assert(offsetof(SurfaceUniforms, jitter) == 528);
static_assert(offsetof(SurfaceUniforms, triplanarScale) == 536);
static_assert(offsetof(SurfaceUniforms, triplanarSharpness) == 540);
static_assert(offsetof(SurfaceUniforms, towardsEye) == 544);
static_assert(offsetof(SurfaceUniforms, orthographic) == 556);
static_assert(sizeof(SurfaceUniforms) == 560);
static_assert(offsetof(ShadowUniforms, tile) == 256);
static_assert(offsetof(ShadowUniforms, lookup) == 320);
static_assert(offsetof(ShadowUniforms, texel) == 384);
static_assert(offsetof(ShadowUniforms, reversedZ) == 396);
static_assert(sizeof(ShadowUniforms) == 400);
static_assert(offsetof(WaterUniforms, hazeDistance) == 60);
static_assert(offsetof(WaterUniforms, foam) == 64);
static_assert(offsetof(WaterUniforms, translucency) == 72);
static_assert(offsetof(WaterUniforms, foamColor) == 80);
static_assert(offsetof(WaterUniforms, foamDrift) == 96);
static_assert(offsetof(WaterUniforms, spindrift) == 112);
static_assert(offsetof(WaterUniforms, windDirectionFrom) == 120);
static_assert(offsetof(WaterUniforms, spindriftFrom) == 128);
static_assert(offsetof(WaterUniforms, cloudHeight) == 132);
static_assert(offsetof(WaterUniforms, cloudDrift) == 136);
static_assert(offsetof(WaterUniforms, cloudThreshold) == 148);
static_assert(offsetof(WaterUniforms, cloudSunward) == 152);
static_assert(offsetof(WaterUniforms, cloudCover) == 160);
static_assert(sizeof(WaterUniforms) == 176);
static_assert(offsetof(PlanetUniforms, ringAxis) == 16);
static_assert(offsetof(PlanetUniforms, ringOuter) == 32);
static_assert(sizeof(PlanetUniforms) == 48);
static_assert(offsetof(RingUniforms, wave) == 16 * kMaxWaterRings);
static_assert(offsetof(RingUniforms, count) == 32 * kMaxWaterRings);

} // namespace hfx
