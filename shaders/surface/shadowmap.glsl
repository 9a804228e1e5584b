// Receiving a directional light's shadow map (hfx::ShadowMap): the share of the light that
// reaches a world point, 3x3 taps of the hardware's 2x2 comparison. The lookup moves off the
// surface along its normal by about a map texel and compares with a small depth bias, so a
// surface does not shadow itself through the map's rounding. Composed after surface/uniforms.glsl.
// HFX_SHADOW_MAP 1: a map is received; 0: the light is whole (a define rather than a uniform: a
// CPU rasteriser runs both sides of a branch, so a switched-off uniform still paid the nine taps).
#ifndef HFX_SHADOW_MAP
#define HFX_SHADOW_MAP 0
#endif

layout(binding = HFX_UNIT_SHADOW_MAP) uniform sampler2DShadow s_shadowMap;

float hfx_shadow_map(vec3 world, vec3 normal) {
#if !HFX_SHADOW_MAP
    return 1.0;
#else
    const vec4 clip = u_shadowViewProj * vec4(world + normal * u_shadowOffset, 1.0);
    const vec3 p = clip.xyz / clip.w * 0.5 + 0.5;
    if (p.z >= 1.0) return 1.0; // beyond the map's far plane nothing casts
    float sum = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x)
            sum += texture(s_shadowMap, vec3(p.xy + vec2(x, y) * u_shadowTexel, p.z - u_shadowBias));
    return sum / 9.0;
#endif
}
