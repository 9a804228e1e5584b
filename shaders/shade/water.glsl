// Water: the body colour deepens in the troughs, backlit crests glow, the sky (shade/sky.glsl) is
// reflected by Schlick's Fresnel weight, the sun leaves a sharp glint, foam (the ocean's, in the
// albedo's alpha, its young part in the red; dense while young, a lace of bubbles as it ages;
// with wind streaks in a gale) covers both, and distance fades everything into
// the horizon's haze. The normals' variance at the level of the pixel's footprint on the surface
// (Toksvig; surface.frag's hfx_shade_level) widens the glint and roughens the Fresnel term, so the
// far sea does not shimmer.

// Crest translucency: sunlight that enters a wave's far side and crosses its thin top towards the
// eye (the green glow of backlit crests). It grows with the crest's height above the mean sea
// (the thinner the water between the sun and the eye: h = 0.5 is the mean, 0.75 two sigma of
// the sea above it) and as the eye looks towards the sun through the wave: against the light's
// direction bent by the surface's normal, as light is where it leaves the water. A smaller wave's
// steep face above the mean is as thin as a great crest: its slope (the relief's normal turned
// 5 to 16 degrees from the mesh's) lights it from the mean up to a sigma above it, so the faces
// of a rough sea glow and not only its tallest crests.
// And the light the sea scatters back out of its body towards an eye that looks towards the sun
// (Crest's approximation: (L.-V)^5, more at grazing views, 1 - v^2 with v the cosine between the
// view and the mesh's normal): a tenth of it everywhere and up to six tenths on the crests and
// steep faces, so whole faces of the waves against the sun glow, and none of it where the eye
// looks down or away.
float hfx_crest_glow(HfxSurfacePoint p) {
    const float steep = smoothstep(0.003, 0.04, 1.0 - dot(p.normal, p.geometricNormal));
    const float crest = max(smoothstep(0.55, 0.8, p.height), steep * smoothstep(0.5, 0.6, p.height));
    const float through = pow(clamp(dot(p.viewDir, -normalize(p.lightDir + 0.4 * p.normal)), 0.0, 1.0), 4.0);
    // (v is found here, at the hit, from the mesh's normal. The entry's p.cosView, read here,
    // was held through the walk and the layers' reads: one register more, which took RDNA2's
    // clouded ocean program past 64: docs/BENCHMARKS.md.)
    const float v = clamp(dot(p.geometricNormal, p.viewDir), 0.0, 1.0);
    const float towardsSun = pow(max(dot(p.lightDir, -p.viewDir), 0.0), 5.0);
    const float scattered = 3.4 * towardsSun * (1.0 - v * v) * (0.1 + 0.5 * max(crest, steep));
    return u_translucency * (4.0 * crest * through + scattered);
}

// Two values in [0, 1) for an integer cell (a sine-free hash: the same on every device).
vec2 hfx_hash2(vec2 cell) {
    vec3 q = fract(vec3(cell.xyx) * vec3(0.1031, 0.1030, 0.0973));
    q += dot(q, q.yzx + 33.33);
    return fract((q.xx + q.yz) * q.zy);
}

// Bubbles: for q, the distance to the nearest of the lattice's points (one per cell, jittered
// within its middle 80%; Worley 1996) over that point's own radius, 0.3 to 0.8 of a cell. 0 in a
// bubble's middle, 1 from its rim on.
float hfx_bubbles(vec2 q) {
    const vec2 cell = floor(q), f = q - cell;
    float nearest = 8.0;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            const vec2 o = vec2(i, j), h = hfx_hash2(cell + o), r = o + 0.1 + 0.8 * h - f;
            nearest = min(nearest, length(r) / (0.3 + 0.5 * fract(h.x * 7.31 + h.y)));
        }
    return smoothstep(0.2, 1.0, nearest);
}

// The lace's mean (hfx_foam_lace): what it fades to far off, and what the foam is shaded about.
const float HFX_LACE_MEAN = 0.6;

// The foam's lace: 1 between its bubbles, 0 in their middles, bubbles of two sizes (u_foamCells to
// the texcoord and 2.7 times as many) in a lattice bent by a value noise so that they do not
// line up, riding with the foam's drift. A size whose cells span less than 2.5 pixels
// (`footprint` texcoords a pixel) fades to about its mean, HFX_LACE_MEAN (0.64, its spread 0.36,
// over 200,000 points in numpy), and what it no longer shows goes into y, the half-width of the
// values the pixel covers: a threshold on the lace (hfx_shade's foam) is then a ramp that wide,
// the share of the pixel above it, rather than aliased, and far off thin foam still shows where
// the lace's peaks would have shown it.
vec2 hfx_foam_lace(vec2 uv, float footprint) {
    vec2 q = (uv - u_foamDrift) * u_foamCells;
    const vec2 c = floor(0.35 * q), f = 0.35 * q - c, s = f * f * (3.0 - 2.0 * f);
    q += 1.2 * (mix(mix(hfx_hash2(c), hfx_hash2(c + vec2(1, 0)), s.x),
                    mix(hfx_hash2(c + vec2(0, 1)), hfx_hash2(c + vec2(1, 1)), s.x), s.y) - 0.5);
    const float cellsPerPixel = u_foamCells * footprint;
    vec2 lace = vec2(0.0);
    const float sizes[2] = float[2](1.0, 2.7), weights[2] = float[2](0.55, 0.45);
    for (int i = 0; i < 2; ++i) {
        const float fade = smoothstep(0.2, 0.4, cellsPerPixel * sizes[i]);
        const float value =
            fade < 1.0 ? hfx_bubbles(q * sizes[i] + 17.0 * float(i)) : HFX_LACE_MEAN;
        lace += weights[i] * vec2(mix(value, HFX_LACE_MEAN, fade), 0.5 * fade);
    }
    return lace;
}

// A wind streak's density across it (1 within `inner` of its middle, falling linearly to 0 at
// `outer`) integrated from the middle out to x, odd in x: the difference of two is what a pixel's
// box covers of it.
float hfx_streak_integral(float x, float inner, float outer) {
    const float a = abs(x), fall = outer - inner, beyond = max(outer - min(a, outer), 0.0);
    const float integral = a <= inner ? a : inner + 0.5 * (fall - beyond * beyond / fall);
    return x < 0.0 ? -integral : integral;
}

// Wind streaks (spindrift, above Beaufort 7): foam drawn out downwind into long bands, along `w`
// (unit, texcoords) at `strength`, u_streakCells lattice cells per texcoord across the wind and 12
// times longer along it, riding with the foam's drift. A band runs where a value noise over that
// lattice crosses its middle, wavering as the noise does and meandering across the wind by up to
// half a cell over 8 cells along it (a second noise), broken into lengths by the first noise's
// second value and into patches about five cells long by a third, which also swells and thins
// it: its density is 1 within a third of its half-width of its middle and falls to 0 at its edge,
// the half-width 0.1 to 0.3 of a cell (a band 0.6 to 1.8 m wide at OceanEffect's 3 m cells),
// measured across the wind from the noise's slope. Returns what a pixel `footprint` texcoords wide
// covers of that density (a box filter: far off a faint line, not an aliased one) times
// `strength`: the streaks' share of the pixel, which hfx_shade draws as foam.
float hfx_streaks(vec2 uv, float footprint, vec2 w, float strength) {
    if (!(strength > 0.0)) return 0.0;
    const vec2 d = uv - u_foamDrift;
    const float along = dot(d, w) * u_streakCells;
    float across = dot(d, vec2(-w.y, w.x)) * u_streakCells;
    const vec2 mq = vec2(across / 3.0, along / 8.0), mc = floor(mq), mf = mq - mc, ms = mf * mf * (3.0 - 2.0 * mf);
    across += mix(mix(hfx_hash2(mc + 71.0).x, hfx_hash2(mc + vec2(72, 71)).x, ms.x),
                  mix(hfx_hash2(mc + vec2(71, 72)).x, hfx_hash2(mc + 72.0).x, ms.x), ms.y) - 0.5;
    const vec2 q = vec2(across, along / 12.0), cell = floor(q), f = q - cell;
    const vec2 s = f * f * (3.0 - 2.0 * f);
    const vec2 a = hfx_hash2(cell), b = hfx_hash2(cell + vec2(1, 0));
    const vec2 c = hfx_hash2(cell + vec2(0, 1)), e = hfx_hash2(cell + vec2(1, 1));
    const vec2 n = mix(mix(a, b, s.x), mix(c, e, s.x), s.y);
    // The noise's change per cell across the wind, and how many cells away its middle is.
    const float slope = abs(mix(b.x - a.x, e.x - c.x, s.y)) * 6.0 * f.x * (1.0 - f.x);
    const float dist = abs(n.x - 0.5) / max(slope, 0.05);
    const float g0 = floor(along / 5.0), g = along / 5.0 - g0;
    const vec2 patches = mix(hfx_hash2(vec2(cell.x, g0) + 33.0), hfx_hash2(vec2(cell.x, g0 + 1.0) + 33.0),
                             g * g * (3.0 - 2.0 * g));
    const float outer = 0.1 + 0.2 * patches.x, inner = outer / 3.0, pixel = max(u_streakCells * footprint, 1e-4);
    const float density = (hfx_streak_integral(dist + 0.5 * pixel, inner, outer) -
                           hfx_streak_integral(dist - 0.5 * pixel, inner, outer)) /
                          pixel;
    return strength * density * smoothstep(0.35, 0.65, n.y) * smoothstep(0.2, 0.6, patches.y);
}

// The wind's streaks (u_spindrift along u_windDirection) and, over a wind change, the last
// wind's fading out where they lie (u_spindriftFrom along u_windDirectionFrom).
float hfx_spindrift(vec2 uv, float footprint) {
    return min(hfx_streaks(uv, footprint, u_windDirection, u_spindrift) +
                   hfx_streaks(uv, footprint, u_windDirectionFrom, u_spindriftFrom),
               1.0);
}

// A foam's look where `young` of it is young: its structure, the ripple and the bubbles (`lace`,
// hfx_foam_lace) mixed as hfx_shade says, the lace's spread that widens the edge where it shows,
// and its opacity. One look for the layers' foam and, as aged foam, the wind's streaks.
struct HfxFoamLook {
    vec4 structure, spread, opacity;
};
HfxFoamLook hfx_foam_look(vec4 young, vec4 ripple, vec2 lace) {
    return HfxFoamLook(mix(0.3 * ripple + 0.7 * lace.x, 0.7 * ripple + 0.3 * lace.x, young),
                       lace.y * mix(vec4(0.7), vec4(0.3), young), mix(vec4(0.85), vec4(1.0), young));
}
// The share of a pixel a foam of that look shows white where its coverage is `thin`.
vec4 hfx_foam_shown(vec4 thin, HfxFoamLook look) {
    return look.opacity * smoothstep(1.0 - thin - look.spread, 1.4 - thin + look.spread, look.structure);
}

// The sea emits no light of its own (its crest glow is the sun's, through the wave).
vec3 hfx_emission(HfxSurfacePoint p) { return vec3(0.0); }

vec3 hfx_shade(HfxSurfacePoint p) {
    // The clouds' shadows: the sun's light they let through, here (the sky's light is left;
    // surface.frag's main found it). The glow is the sun's, through the water: they dim it too.
    float sunThrough = 1.0;
#if HFX_SKY == 1
    p.lit *= g_cloudSunlight;
    sunThrough = g_cloudSunlight;
#endif
    const vec3 body = mix(u_deepColor, u_shallowColor, p.height * p.height) * (u_ambient + p.lit * p.diffuse * u_lightColor) +
                      hfx_crest_glow(p) * sunThrough * u_shallowColor * u_lightColor;
    vec3 reflected = reflect(-p.viewDir, p.normal);
    reflected.y = abs(reflected.y); // a ray reflected downwards sees the next wave's sky
    // Roughness from the slope variance: Schlick's Fresnel with roughness (Lagarde) and a glint
    // whose Phong power drops as the reflection direction spreads (twice the normal's angle).
    const float roughness = clamp(sqrt(p.slopeVariance), 0.0, 1.0);
    const float cosView = clamp(dot(p.normal, p.viewDir), 0.0, 1.0);
    const float fresnel = u_fresnelF0 + (max(1.0 - roughness, u_fresnelF0) - u_fresnelF0) * pow(1.0 - cosView, 5.0);
    // Foam breaks up where it thins: a layer's coverage f shows where its structure stands
    // highest, a fraction f of it. The structure is the next finer waves' relief (the ripple) and
    // the foam's bubbles (hfx_foam_lace): young foam, a breaking crest's, is mostly the ripple,
    // solid where its coverage is high and frayed by the bubbles at its edges; as it ages it
    // becomes the bubbles' walls, a lace whose holes open as it thins, and shows less of the
    // water's white. The layers' foams combine as independent coverages. Where it shows it is
    // white: foam dimmed by its coverage read as a grey veil, and a calm sea's thin whitecaps did
    // not show at all (OceanShading.WhitecapsCoverTheFrameAsMonahansLawSays).
    // The wind's streaks, in a gale: their share of the pixel (hfx_spindrift).
    const bool gale = u_spindrift > 0.0 || u_spindriftFrom > 0.0;
    const float streak = gale ? hfx_spindrift(p.texcoord, p.footprint) : 0.0;
    const vec4 ripple = clamp(0.5 + 3.0 * (p.foamDetail - 0.5), 0.0, 1.0);
    const vec4 coverage = clamp(p.foam, 0.0, 1.0);
    // The lace where foam shows (else its mean, as if far off: a gale's streaks outside the foam
    // are the ripple's; drawn there too, the lace took the clouds' program from 64 registers to
    // 72 on RDNA2).
    const bool foamed = any(greaterThan(coverage, vec4(0.0)));
    const vec2 lace = u_foamCells > 0.0 && foamed ? hfx_foam_lace(p.texcoord, p.footprint) : vec2(HFX_LACE_MEAN, 0.0);
    // Near the eye a streak is aged foam whose coverage is its share, a band of the foam's own
    // bubbles, denser in its middle and frayed at its edges (drawn solid over the foam, a streak
    // read as a scratch across its bubbles); far off, where it spans under a few pixels, or
    // without bubbles, its share.
    const float streakFar = u_foamCells > 0.0 ? smoothstep(0.1, 0.4, u_streakCells * p.footprint) : 1.0;
    const float streakShown =
        streak > 0.0 ? mix(hfx_foam_shown(vec4(streak), hfx_foam_look(vec4(0.0), ripple, lace)).x, streak, streakFar)
                     : 0.0;
    // Without bubbles the ripple, solid.
    HfxFoamLook look = HfxFoamLook(ripple, vec4(0.0), vec4(1.0));
    vec4 thin = coverage;
    if (u_foamCells > 0.0 && foamed) {
        const vec4 young = clamp(p.foamYoung / max(coverage, 1.0 / 255.0), 0.0, 1.0);
        look = hfx_foam_look(young, ripple, lace);
        thin = coverage * mix(vec4(0.8), vec4(1.0), young); // aged foam's bubbles stay open
    }
    const vec4 shown = hfx_foam_shown(thin, look);
    const vec4 clear = 1.0 - shown;
    const float foam = u_foam != 0 ? max(1.0 - clear.x * clear.y * clear.z * clear.w, streakShown) : 0.0;
    const float variance = p.slopeVariance + foam * u_foamRoughness;
    const float power = u_glintPower / (1.0 + 4.0 * u_glintPower * variance);
    const float glint = u_glintStrength * (power + 2.0) / (u_glintPower + 2.0) * pow(max(dot(reflected, p.lightDir), 0.0), power);
    // The reflected sky over the directions the pixel's normals send it to: twice their spread
    // (the slopes' deviation), or a pixel's width (about 2 mrad) where they hardly spread.
    const float skySpread = 2.0 * sqrt(p.slopeVariance) + 0.002;
    vec3 color = mix(body, hfx_sky(reflected, skySpread), fresnel) + p.lit * glint * u_lightColor;
    // Foam: a rough white layer, lit like snow, that hides the water under it; its bubbles shade
    // dense foam a little where they show, about its mean brightness (no flat white sheet).
    const vec3 foamLit = u_foamColor * (1.0 + 0.3 * (lace.x - HFX_LACE_MEAN)) *
                         (u_ambient + p.lit * max(dot(p.normal, p.lightDir), 0.0) * u_lightColor);
    color = mix(color, foamLit, foam);
    // (An orthographic view's distance: along its axis, from the camera's position.)
    const float distance = u_orthographic != 0 ? max(dot(u_cameraPos - p.position, u_towardsEye), 0.0)
                                               : length(u_cameraPos - p.position);
    color = mix(color, hfx_haze(-hfx_to_eye(p.position)), distance / (distance + u_hazeDistance));
    // Highlights roll off above a knee instead of clipping: the sun's path on the water keeps
    // its glitter where a clamp turned it into one white sheet. Not where the colours are written
    // linear (hfx::ColorOutput): that is the engine's tone mapping, which wants the glint's light.
    if (u_linearOutput != 0) return color;
    const float knee = 0.75;
    const vec3 over = max(color - knee, 0.0);
    return min(color, knee) + (1.0 - knee) * (1.0 - exp(-over / (1.0 - knee)));
}
