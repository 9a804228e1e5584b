// Receiving a directional light's shadow maps (hfx::ShadowMap's, one cascade; or an engine's own,
// hfx::ShadowCascades): the share of the light that reaches a world point, 3x3 taps of the
// hardware's 2x2 comparison in the first cascade, finest first, that holds the point with the
// filter's reach; lit where none does. The lookup moves off the surface along its normal by
// about a map texel and compares with a small depth bias, so a surface does not shadow itself
// through the map's rounding. Composed after surface/uniforms.glsl.
// HFX_SHADOW_MAP 0: the light is whole; 1: the maps are tiles of a 2D depth texture; 2: layers
// (and tiles) of a 2D array one (a define rather than a uniform: a CPU rasteriser runs both sides
// of a branch, so a switched-off uniform still paid the nine taps; and the sampler's type).
#ifndef HFX_SHADOW_MAP
#define HFX_SHADOW_MAP 0
#endif

#if HFX_SHADOW_MAP
const int HFX_MAX_SHADOW_CASCADES = 4; // hfx::kMaxShadowCascades

layout(std140, binding = HFX_BLOCK_SHADOWS) uniform HfxShadows {
    mat4 u_shadowViewProj[HFX_MAX_SHADOW_CASCADES]; // world to each cascade's clip space
    vec4 u_shadowTile[HFX_MAX_SHADOW_CASCADES];     // its viewport in the texture: x, y, width, height
    vec4 u_shadowLookup[HFX_MAX_SHADOW_CASCADES];   // normal offset (world), depth bias, layer, filter reach in the tile
    vec2 u_shadowTexel;                             // 1 / the texture's size
    int u_shadowCount;                              // cascades, finest first
    int u_shadowReversedZ;                          // 1: near at depth 1, compared greater
};

#if HFX_SHADOW_MAP == 2
layout(binding = HFX_UNIT_SHADOW_MAP) uniform sampler2DArrayShadow s_shadowMap;
#else
layout(binding = HFX_UNIT_SHADOW_MAP) uniform sampler2DShadow s_shadowMap;
#endif
#endif

float hfx_shadow_map(vec3 world, vec3 normal) {
#if !HFX_SHADOW_MAP
    return 1.0;
#else
    // The cascade first, then its taps once: a warp whose lanes read different cascades filters
    // once, not once a cascade.
    const bool reversed = u_shadowReversedZ != 0;
    vec3 lookup = vec3(-1.0); // the chosen cascade's texture coordinates and reference depth
    float layer = 0.0;
    for (int i = 0; i < u_shadowCount; ++i) {
        const vec4 c = u_shadowLookup[i];
        const vec4 clip = u_shadowViewProj[i] * vec4(world + normal * c.x, 1.0);
        const vec3 ndc = clip.xyz / clip.w;
        const vec2 inTile = ndc.xy * 0.5 + 0.5;
        // Window depth (GL's default: [-1, 1] onto [0, 1]; reversed: [0, 1] as it is), moved
        // towards the light by the bias. Beyond the far plane nothing casts.
        const float depth = reversed ? ndc.z : ndc.z * 0.5 + 0.5;
        if (all(greaterThanEqual(inTile, vec2(c.w))) && all(lessThanEqual(inTile, vec2(1.0 - c.w))) &&
            (reversed ? depth > 0.0 : depth < 1.0)) {
            lookup = vec3(u_shadowTile[i].xy + inTile * u_shadowTile[i].zw, reversed ? depth + c.y : depth - c.y);
            layer = c.z;
            break;
        }
    }
    if (lookup.x < 0.0) return 1.0; // in no cascade: nothing casts there
    // Level 0 by name: the taps run where the flow has parted (a lane in no cascade has returned;
    // a triplanar mapping's projections branch), where implicit derivatives are undefined.
    float sum = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            const vec2 tap = lookup.xy + vec2(x, y) * u_shadowTexel;
#if HFX_SHADOW_MAP == 2
            sum += textureGrad(s_shadowMap, vec4(tap, layer, lookup.z), vec2(0.0), vec2(0.0));
#else
            sum += textureLod(s_shadowMap, vec3(tap, lookup.z), 0.0);
#endif
        }
    return sum / 9.0;
#endif
}
