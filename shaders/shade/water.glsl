// Water: the body colour deepens in the troughs, backlit crests glow, the sky (shade/sky.glsl) is
// reflected by Schlick's Fresnel weight, the sun leaves a sharp glint, foam (the ocean's, in the
// albedo's alpha, with wind streaks in a gale) covers both, and distance fades everything into
// the horizon's haze. The normals' variance at the level of the pixel's footprint on the surface
// (Toksvig; surface.frag's hfx_shade_level) widens the glint and roughens the Fresnel term, so the
// far sea does not shimmer.

// Crest translucency: sunlight that enters a wave's far side and crosses its thin top towards the
// eye (the green glow of backlit crests). It grows with the crest's height above the mean sea
// (the thinner the water between the sun and the eye: h = 0.5 is the mean, 0.75 two sigma of
// the sea above it) and as the eye looks towards the sun through the wave: against the light's
// direction bent by the surface's normal, as light is where it leaves the water.
float hfx_crest_glow(HfxSurfacePoint p) {
    const float crest = smoothstep(0.55, 0.8, p.height);
    const float through = pow(clamp(dot(p.viewDir, -normalize(p.lightDir + 0.4 * p.normal)), 0.0, 1.0), 4.0);
    return 4.0 * u_translucency * crest * through;
}

// Two values in [0, 1) for an integer cell (a sine-free hash: the same on every device).
vec2 hfx_hash2(vec2 cell) {
    vec3 q = fract(vec3(cell.xyx) * vec3(0.1031, 0.1030, 0.0973));
    q += dot(q, q.yzx + 33.33);
    return fract((q.xx + q.yz) * q.zy);
}

// Wind streaks (spindrift, u_spindrift above Beaufort 7): foam drawn out downwind into thin lines,
// u_streakCells lattice cells per texcoord across the wind and 12 times longer along it, riding
// with the foam's drift. A line runs where a value noise over that lattice crosses its middle,
// wavering as the noise does, broken into lengths by the noise's second value; it is 0.12 of a
// cell wide (12 cm at OceanEffect's 1 m), measured across the wind from the noise's slope, and
// what of it a pixel `footprint` texcoords wide covers is its share of the pixel (a box filter:
// far off a faint line, not an aliased one). Returns the streaks' cover, 0..0.8.
float hfx_spindrift(vec2 uv, float footprint) {
    if (!(u_spindrift > 0.0)) return 0.0;
    const vec2 w = u_windDirection, d = uv - u_foamDrift;
    const float along = dot(d, w) * u_streakCells, across = dot(d, vec2(-w.y, w.x)) * u_streakCells;
    const vec2 q = vec2(across, along / 12.0), cell = floor(q), f = q - cell;
    const vec2 s = f * f * (3.0 - 2.0 * f);
    const vec2 a = hfx_hash2(cell), b = hfx_hash2(cell + vec2(1, 0));
    const vec2 c = hfx_hash2(cell + vec2(0, 1)), e = hfx_hash2(cell + vec2(1, 1));
    const vec2 n = mix(mix(a, b, s.x), mix(c, e, s.x), s.y);
    // The noise's change per cell across the wind, and how many cells away its middle is.
    const float slope = abs(mix(b.x - a.x, e.x - c.x, s.y)) * 6.0 * f.x * (1.0 - f.x);
    const float dist = abs(n.x - 0.5) / max(slope, 0.05);
    const float halfWidth = 0.06, pixel = max(u_streakCells * footprint, 1e-4);
    const float covered =
        max(min(dist + 0.5 * pixel, halfWidth) - max(dist - 0.5 * pixel, -halfWidth), 0.0) / pixel;
    return 0.8 * u_spindrift * smoothstep(0.35, 0.65, n.y) * covered;
}

vec3 hfx_shade(HfxSurfacePoint p) {
    const vec3 body = mix(u_deepColor, u_shallowColor, p.height * p.height) * (u_ambient + p.lit * p.diffuse * u_lightColor) +
                      hfx_crest_glow(p) * u_shallowColor * u_lightColor;
    vec3 reflected = reflect(-p.viewDir, p.normal);
    reflected.y = abs(reflected.y); // a ray reflected downwards sees the next wave's sky
    // Roughness from the slope variance: Schlick's Fresnel with roughness (Lagarde) and a glint
    // whose Phong power drops as the reflection direction spreads (twice the normal's angle).
    const float roughness = clamp(sqrt(p.slopeVariance), 0.0, 1.0);
    const float cosView = clamp(dot(p.normal, p.viewDir), 0.0, 1.0);
    const float fresnel = u_fresnelF0 + (max(1.0 - roughness, u_fresnelF0) - u_fresnelF0) * pow(1.0 - cosView, 5.0);
    // Foam breaks up where it thins: a layer's coverage f shows where the next finer waves stand
    // highest, a fraction f of them, so young foam is solid and old foam frays into patches; the
    // layers' foams combine as independent coverages. Where it shows it is white: foam dimmed by
    // its coverage read as a grey veil, and a calm sea's thin whitecaps did not show at all
    // (OceanShading.WhitecapsCoverTheFrameAsMonahansLawSays).
    const vec4 ripple = clamp(0.5 + 3.0 * (p.foamDetail - 0.5), 0.0, 1.0);
    const vec4 coverage = clamp(p.foam, 0.0, 1.0);
    const vec4 shown = smoothstep(1.0 - coverage, 1.4 - coverage, ripple);
    const vec4 clear = 1.0 - shown;
    // The wind's streaks over it, in a gale.
    const float foam = u_foam != 0 ? max(1.0 - clear.x * clear.y * clear.z * clear.w,
                                         hfx_spindrift(p.texcoord, p.footprint))
                                   : 0.0;
    const float variance = p.slopeVariance + foam * u_foamRoughness;
    const float power = u_glintPower / (1.0 + 4.0 * u_glintPower * variance);
    const float glint = u_glintStrength * (power + 2.0) / (u_glintPower + 2.0) * pow(max(dot(reflected, p.lightDir), 0.0), power);
    vec3 color = mix(body, hfx_sky(reflected), fresnel) + p.lit * glint * u_lightColor;
    // Foam: a rough white layer, lit like snow, that hides the water under it.
    const vec3 foamLit = u_foamColor * (u_ambient + p.lit * max(dot(p.normal, p.lightDir), 0.0) * u_lightColor);
    color = mix(color, foamLit, foam);
    const float distance = length(u_cameraPos - p.position);
    color = mix(color, hfx_haze(p.position - u_cameraPos), distance / (distance + u_hazeDistance));
    // Highlights roll off above a knee instead of clipping: the sun's path on the water keeps
    // its glitter where a clamp turned it into one white sheet.
    const float knee = 0.75;
    const vec3 over = max(color - knee, 0.0);
    return min(color, knee) + (1.0 - knee) * (1.0 - exp(-over / (1.0 - knee)));
}
