// The sky the water reflects and the sky pass draws (SurfaceRenderer::drawSky), from the look in
// the HfxWater block (mirrored by hfx::WaterUniforms): an equirectangular environment image
// (HFX_ENVIRONMENT, a define of the program: on a CPU rasteriser a branch on a uniform runs both
// sides, and each water pixel asks for the sky twice), or a gradient from the horizon's colour up
// to the zenith's with the sun's glow around the light.
// Below the horizon the horizon's colour continues: what distant water fades into, so the sea
// meets the sky without a seam.

layout(std140, binding = HFX_BLOCK_WATER) uniform HfxWater {
    vec3 u_deepColor;     // troughs: light travels far in the water
    float u_fresnelF0;    // reflectance seen head-on
    vec3 u_shallowColor;  // crests: thin water scatters the sun
    float u_glintPower;   // sharpness of the sun's reflection
    vec3 u_skyZenith;     // procedural sky, used without an environment
    float u_glintStrength;
    vec3 u_skyHorizon;
    float u_hazeDistance; // world units where half the colour is haze
    int u_foam;           // 1: the albedo's alpha is foam coverage (the ocean writes it)
    float u_sunGlow;      // strength of the glow around the sun in the sky
    float u_translucency; // how brightly a crest lit from behind glows (0: not at all)
    float u_foamCells;    // the foam's bubble lattice cells per texcoord (0: no lace)
    vec3 u_foamColor;
    float u_foamRoughness; // how much foam widens and dims the sun's glint (0..1)
    vec2 u_foamDrift;      // texcoords the foam has drifted downwind: the streaks ride with it
    vec2 u_windDirection;  // where the wind blows, texcoords, unit
    float u_spindrift;     // wind streaks' strength (0: none)
    float u_streakCells;   // wind streaks' lattice cells per texcoord across the wind
    vec2 u_windDirectionFrom; // a wind change: the last wind's streaks fading out, their direction
    float u_spindriftFrom;    // ... and their strength now (0: none)
    float u_waterPadding0;
    vec2 u_waterPadding1;
};
layout(binding = HFX_UNIT_ENVIRONMENT) uniform sampler2D s_environment;

vec3 hfx_sky(vec3 dir) {
#if HFX_ENVIRONMENT
    const float pi = 3.14159265;
    const vec2 uv = vec2(atan(dir.z, dir.x) / (2.0 * pi) + 0.5, acos(clamp(dir.y, -1.0, 1.0)) / pi);
    return textureLod(s_environment, vec2(uv.x, 1.0 - uv.y), 0.0).rgb;
#else
    // Most of the change happens near the horizon, as in a clear sky.
    const float up = clamp(dir.y, 0.0, 1.0);
    const vec3 base = mix(u_skyHorizon, u_skyZenith, pow(up, 0.4));
    const float sun = max(dot(normalize(dir), normalize(u_lightDir)), 0.0);
    return base + u_sunGlow * u_lightColor * (0.5 * pow(sun, 48.0) + 0.12 * pow(sun, 6.0));
#endif
}

/// The haze at a distance: the sky at the horizon in the direction of the point.
vec3 hfx_haze(vec3 toPoint) {
    const vec3 level = vec3(toPoint.x, 0.0, toPoint.z);
    return hfx_sky(dot(level, level) > 0.0 ? normalize(level) : vec3(1.0, 0.0, 0.0));
}
