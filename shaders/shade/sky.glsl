// The sky the water reflects and the sky pass draws (SurfaceRenderer::drawSky), from the look in
// the HfxWater block (mirrored by hfx::WaterUniforms), as HFX_SKY says (hfx::SkyKind, a define of
// the program: on a CPU rasteriser a branch on a uniform runs both sides, and each water pixel
// asks for the sky twice): 0, a gradient from the horizon's colour up to the zenith's with the
// sun's glow around the light; 1, the same with clouds; 2, an equirectangular environment image.
// Below the horizon the horizon's colour continues: what distant water fades into, so the sea
// meets the sky without a seam.
// effects/src/Sky.cpp computes the procedural sky on the CPU with the same float operations
// (hfx::skyColor): change both together.

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
    float u_cloudHeight;      // the clouds' layer over the world's y = 0 (world units)
    vec2 u_cloudDrift;        // how far the cloud layer has moved, cloud heights along world x, z
    float u_cloudScale;       // clouds (the noise's first cells) per cloud height
    float u_cloudThreshold;   // where the noise is clouded: its (1 - cover) quantile
    vec2 u_cloudSunward;      // where a cloud's direct light came through, cloud heights (hfx::cloudSunwardStep)
    float u_cloudCover;       // the share of the sky under cloud: what the layer fades into at the horizon
    float u_cloudVeil;        // the veil over an overcast deck's gaps, 0 to 1 (hfx::cloudVeil)
    float u_cloudMeanThickness; // the layer's clouds' mean thickness (hfx::cloudMeanThickness)
};
layout(binding = HFX_UNIT_ENVIRONMENT) uniform sampler2D s_environment;
#ifndef HFX_SKY
#define HFX_SKY 0
#endif

// A value in [0, 1) for an integer cell: pcg2d (Jarzynski and Olano 2020), integer arithmetic, so
// every device gets the same bits (a hash of float products turned on their last bit near a
// whole number, and a cell's value with it).
float hfx_cell_value(vec2 cell) {
    uvec2 v = uvec2(ivec2(cell)) * 1664525u + 1013904223u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    return float(v.x >> 8u) * (1.0 / 16777216.0);
}

// A value noise: the cells' values at the corners, blended by smoothstep weights.
float hfx_value_noise(vec2 q) {
    const vec2 cell = floor(q), f = q - cell, s = f * f * (3.0 - 2.0 * f);
    const float a = hfx_cell_value(cell), b = hfx_cell_value(cell + vec2(1, 0));
    const float c = hfx_cell_value(cell + vec2(0, 1)), d = hfx_cell_value(cell + vec2(1, 1));
    const float ab = a + (b - a) * s.x, cd = c + (d - c) * s.x;
    return ab + (cd - ab) * s.y;
}

// The clouds over the layer's point `p` (in cloud heights: world x and z over u_cloudHeight, the
// layer's drift added), seen over a patch of it `across` by `along` (cloud heights):
// (density, thickness). A value noise of HFX_CLOUD_OCTAVES octaves is clouded above
// u_cloudThreshold. An octave keeps the share of its variance a box that size leaves it,
// 1 / sqrt((1 + (along / wavelength)^2) (1 + (across / wavelength)^2)), about its mean, and the
// variance it no longer shows widens the edge's ramp as a Gaussian of it would (a smoothstep's
// variance is a fifth of its half-width's square): far off, in rough water and in a wide pixel's
// shadow a pixel shows about the share of it under cloud, not an aliased sample of it.
vec2 hfx_cloud_cover(vec2 p, float across, float along) {
    p = (p + u_cloudDrift) * u_cloudScale;
    // The octaves' amplitudes 1/2, 1/4, ...: their sum and the sum of their squares.
    const float sum = 1.0 - exp2(-float(HFX_CLOUD_OCTAVES)), squares = (1.0 - exp2(-2.0 * float(HFX_CLOUD_OCTAVES))) / 3.0;
    float wavelength = 1.0 / u_cloudScale, amplitude = 0.5, value = 0.5 * sum, kept = 0.0;
    for (int i = 0; i < HFX_CLOUD_OCTAVES; ++i) {
        const float a = along / wavelength, b = across / wavelength;
        float keep = sqrt(inversesqrt((1.0 + a * a) * (1.0 + b * b))); // of the deviation
        keep *= smoothstep(0.15, 0.35, keep);
        // The finer octaves keep less still: none is read past the first that keeps nothing
        // (where the sky or the water's roughness spreads a pixel wide, most of them).
        if (!(keep > 0.0)) break;
        value += amplitude * keep * (hfx_value_noise(p + 17.0 * float(i)) - 0.5);
        kept += amplitude * amplitude * keep * keep;
        // Turned by atan(3/4) and doubled: the next octave's grid lies across this one's.
        p = vec2(1.6 * p.x - 1.2 * p.y, 1.2 * p.x + 1.6 * p.y);
        amplitude *= 0.5;
        wavelength *= 0.5;
    }
    value /= sum;
    const float lost = max(squares - kept, 0.0);
    const float lostVariance = HFX_CLOUD_OCTAVE_VARIANCE * lost / (sum * sum);
    const float width = sqrt(0.04 * 0.04 + 5.0 * lostVariance);
    const float density = smoothstep(u_cloudThreshold - width, u_cloudThreshold + width, value);
    // The thickness ramps over 0.2 of the noise past the threshold, or, where the clouds cover
    // nearly all the sky (from about 0.98), up to 0.45: a full deck's thickness follows the noise's
    // body, not only its rare lowest values (pale flecks in an even grey).
    const float ramp = max(0.2, 0.45 - u_cloudThreshold) + width;
    return vec2(density, clamp((value - u_cloudThreshold) / ramp, 0.0, 1.0));
}

// The layer's mean (density, thickness, sunward): the cover's share of it clouded, its clouds'
// mean thickness (hfx::cloudMeanThickness, 0.15 + 0.55 cover + 0.17 cover^12: a deck that covers
// more of the sky is deeper and greyer underneath; fitted within 0.012 to the mean measured over
// the layer at covers 0.1 to 0.99: 0.26 at 0.2, 0.76 at 0.95, 0.83 at 0.99; 0.90 at a full cover,
// 0.03 over the fit), their light crossing the cover's share of cloud.
vec3 hfx_cloud_mean() { return vec3(u_cloudCover, u_cloudMeanThickness, u_cloudCover); }

// A deck that covers most of the sky lies under a higher, even veil (a storm's altostratus and
// nimbostratus): from a cover of 0.7 to a full one it hides the clear sky in the layer's gaps, 0 to
// 1 of it (u_cloudVeil, hfx::cloudVeil). The veil is half as thick as the deck's mean cloud and lit
// through it (sunward the cover): a gap is a paler grey, not blue, and passes the sun's light as
// that thin a cloud does. `cloud` is (density, thickness, sunward) of the layer; the veil fills the
// rest of the density, and the thickness and the sunward density become the two's means over it.
vec3 hfx_cloud_veiled(vec3 cloud) {
    const float veil = u_cloudVeil * (1.0 - cloud.x), density = cloud.x + veil;
    const float layer = density > 0.0 ? cloud.x / density : 0.0;
    return vec3(density, cloud.y * layer + 0.5 * u_cloudMeanThickness * (1.0 - layer),
                cloud.z * layer + u_cloudCover * (1.0 - layer));
}

// The clouds in direction `dir` (y > 0) from the eye, seen over `spread` radians (a sky pixel's
// width, a reflection's widened by the water's roughness): (density, thickness, sunward). The layer
// lies u_cloudHeight over the world's y = 0 (the water's level); the direction meets it (height -
// eye) / y away, so the pixel covers a patch of it about spread / y across and spread / y^2 along
// the view (foreshortened by y again), in cloud heights (the patch's size leaves out the eye's
// height, a few metres beside the layer's 1,500). `sunward` is the density of the cloud towards
// the sun, where a clouded point's direct light came through.
vec3 hfx_clouds(vec3 dir, float spread) {
    const float y = max(dir.y, 0.01);
    const vec2 p = u_cameraPos.xz / u_cloudHeight + dir.xz / y * (1.0 - u_cameraPos.y / u_cloudHeight);
    const float across = spread / y, along = spread / (y * y);
    const vec2 c = hfx_cloud_cover(p, across, along);
    // The sun's light reaches a cloud's underside through the cloud on its way: from the sunward
    // side of the cloud, a short way; past its middle, through all of it. So the cloud is read
    // again u_cloudSunward along the layer (HFX_CLOUD_DEPTH cloud heights up the sun's ray, at
    // most half a cell: the host's, once a draw), over a cell at least: the light spreads in the
    // cloud, and so wide a patch reads three octaves (half a cell read four, for 1.11x rather
    // than 1.08x between a cloud's sides: docs/history/tuning.md). Only where there is a cloud.
    float sunward = 0.0;
    if (c.x > 0.0) {
        const float cell = 1.0 / u_cloudScale;
        sunward = hfx_cloud_cover(p + u_cloudSunward, max(across, cell), max(along, cell)).x;
    }
    // Far off, the layer is seen edge on, more of it in a pixel than the octaves show: it fades
    // into its mean (hfx_cloud_mean). An overcast horizon is the clouds' grey, as a clear one is
    // the sky's.
    return mix(hfx_cloud_mean(), vec3(c, sunward), 1.0 - exp(-8.0 * dir.y));
}

// The share of the sun's direct light the clouds let through to the world point `position`,
// whose pixel spans `footprint` world units there: the sun's ray from it meets the layer `reach`
// cloud heights away where the clouds cover it, over the pixel's patch of the sea (a horizontal
// patch falls on one as wide) or the sun's disc seen from the point, 2 HFX_SUN_RADIUS reach
// across and that over y along the sun's way (the penumbra), whichever is wider. A cloud passes
// 0.3 of the light at its edge, 0.05 in its thick middle; the veil over an overcast deck
// (hfx_cloud_veiled) as a cloud of its thickness does.
float hfx_cloud_sunlight(vec3 position, float footprint) {
    const vec3 l = normalize(u_lightDir);
    if (!(l.y > 0.0)) return 1.0; // a sun under the horizon lights nothing through the layer
    const float y = max(l.y, 0.01), reach = (1.0 - position.y / u_cloudHeight) / y;
    const float size = footprint / u_cloudHeight, penumbra = 2.0 * HFX_SUN_RADIUS * reach;
    const vec2 c = hfx_cloud_veiled(vec3(hfx_cloud_cover(position.xz / u_cloudHeight + l.xz * reach,
                                                         max(size, penumbra), max(size, penumbra / y)), 0.0)).xy;
    return 1.0 - c.x * (0.7 + 0.25 * c.y);
}

// The sky without clouds: most of the change happens near the horizon, as in a clear sky.
vec3 hfx_clear_sky(vec3 dir) {
    const float up = clamp(dir.y, 0.0, 1.0);
    const vec3 base = u_skyHorizon + (u_skyZenith - u_skyHorizon) * pow(up, 0.4);
    const float sun = max(dot(normalize(dir), normalize(u_lightDir)), 0.0);
    return base + u_sunGlow * u_lightColor * (0.5 * pow(sun, 48.0) + 0.12 * pow(sun, 6.0));
}

// A cloud's colour: the sky's light from around it, dimmed where it is thick (its underside is in
// its own shade), and the sun's, dimmed also by the cloud towards the sun (`sunward`: its sunlit
// side is bright, its far side grey), and at its thin edges towards the sun the light it scatters
// forwards (the silver lining).
vec3 hfx_cloud_color(vec3 dir, float thickness, float sunward) {
    const vec3 l = normalize(u_lightDir);
    const float sun = max(dot(normalize(dir), l), 0.0);
    const vec3 ambient = u_skyHorizon + (u_skyZenith - u_skyHorizon) * 0.3;
    const float shade = 0.7 + 0.3 * (1.0 - thickness);
    const vec3 lit = shade * (0.5 * ambient + (1.0 - HFX_CLOUD_SUNWARD_SHADE * sunward) *
                                                  (0.55 + 0.45 * clamp(l.y, 0.0, 1.0)) * u_lightColor);
    const vec3 silver = u_sunGlow * u_lightColor * (1.0 - thickness) * (1.5 * pow(sun, 16.0) + 0.3 * pow(sun, 4.0));
    return lit + silver;
}

// The sun's light the clouds let through to the pixel's point (hfx_cloud_sunlight), which the
// water's shading multiplies its direct light by: surface.frag's main finds it first, while
// little else is live (in the shading, among the traced point's values, the noise's loop took the
// ocean's program on RDNA2 from 64 registers to 80: 16 waves a SIMD to 12).
float g_cloudSunlight = 1.0;

// The sky in direction `dir`, seen over `spread` radians (what the clouds are filtered over).
vec3 hfx_sky(vec3 dir, float spread) {
#if HFX_SKY == 2
    const float pi = 3.14159265;
    const vec2 uv = vec2(atan(dir.z, dir.x) / (2.0 * pi) + 0.5, acos(clamp(dir.y, -1.0, 1.0)) / pi);
    return textureLod(s_environment, vec2(uv.x, 1.0 - uv.y), 0.0).rgb;
#elif HFX_SKY == 1
    const vec3 clear = hfx_clear_sky(dir);
    // At and below the horizon the clouds' far field (what hfx_clouds fades into) continues.
    const vec3 cloud = hfx_cloud_veiled(dir.y > 0.0 ? hfx_clouds(dir, spread) : hfx_cloud_mean());
    return clear + (hfx_cloud_color(dir, cloud.y, cloud.z) - clear) * cloud.x;
#else
    return hfx_clear_sky(dir);
#endif
}

/// The haze at a distance: the sky at the horizon in the direction of the point (where the clouds
/// have faded into their cover's mean).
vec3 hfx_haze(vec3 toPoint) {
    const vec3 level = vec3(toPoint.x, 0.0, toPoint.z);
    return hfx_sky(dot(level, level) > 0.0 ? normalize(level) : vec3(1.0, 0.0, 0.0), 0.0);
}
