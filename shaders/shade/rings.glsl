// A planet's rings (hfx::PlanetRings) and the shadows between them and the planet, for the
// planet's shading (shade/planet.glsl: the rings' shadow on the cloud tops) and the rings' own
// draw (rings.frag: the planet's shadow on them). Mirrored by hfx::PlanetUniforms.
//
// The rings are a thin slab of particles in the plane through the planet's centre normal to
// u_ringAxis, from u_ringInner to u_ringOuter. Their radial profile holds per radius the
// particles' albedo (rgb) and the slab's opacity seen along its normal (a = 1 - e^-tau, tau the
// normal optical depth); a ray crossing the plane at cosine mu to the normal meets tau / mu.
// The sun is a disc of angular radius u_sunRadius, so both shadows have a penumbra:
//   rings on planet  the sun's disc seen from the cloud tops covers a stretch of the rings
//                    2 t u_sunRadius / mu wide (t the distance to the plane along the light):
//                    the profile is read averaged over it (its mip at that width)
//   planet on rings  the share of the sun's disc the planet's disc leaves uncovered, from the
//                    area where two discs overlap, as seen from the ring point
// The sunlight the rings scatter lights the planet in turn (ring shine, brightest on the night
// side under their lit face): the renderer integrates it over the rings per point of the planet
// in a frame fixed to the sun (shade/ringshine.comp) and the shading reads it (hfx_ring_shine).

layout(std140, binding = HFX_BLOCK_PLANET) uniform HfxPlanet {
    vec3 u_planetCentre; // world
    float u_planetRadius; // world units
    vec3 u_ringAxis;     // world, unit: normal to the rings' plane (the planet's spin axis)
    float u_ringInner;   // world units from the centre; u_ringOuter 0: no rings
    float u_ringOuter;
    float u_sunRadius;   // the sun's angular radius, radians
    float u_ringTexels;  // the profile's texels from u_ringInner to u_ringOuter
    float u_ringShine;   // 1: the rings light the planet (s_ringShine holds that light), 0: not
};
// rgb the particles' albedo, a the normal opacity, from u_ringInner (s = 0) to u_ringOuter
// (s = 1); a border of 0 beyond, at every level.
layout(binding = HFX_UNIT_RING_PROFILE) uniform sampler2D s_ringProfile;

const float HFX_RING_PI = 3.14159265;

// The sunlight a slab of normal optical depth tau scatters once towards a direction at cosine mu
// to its normal, for sunlight arriving at cosine mu0 (Chandrasekhar's single scattering with an
// isotropic phase function, scaled to a Lambert surface of the same albedo seen head-on), on the
// face the sun lights or through the slab from the other:
//   lit face     2 mu0 / (mu0 + mu) (1 - e^(-tau (1/mu + 1/mu0)))
//   unlit face   2 mu0 / (mu - mu0) (e^(-tau / mu) - e^(-tau / mu0))
// so dense rings are bright on their lit face and dark from behind, and thin ones glow on both.
float hfx_ring_scattered(float tau, float mu, float mu0, bool litFace) {
    if (litFace) return 2.0 * mu0 / (mu0 + mu) * (1.0 - exp(-tau * (1.0 / mu + 1.0 / mu0)));
    if (abs(mu - mu0) > 1e-3) return 2.0 * mu0 / (mu - mu0) * (exp(-tau / mu) - exp(-tau / mu0));
    return 2.0 * tau / mu * exp(-tau / mu); // the limit mu -> mu0
}

// Where radius r falls in the profile.
float hfx_ring_coordinate(float r) {
    return (r - u_ringInner) / (u_ringOuter - u_ringInner);
}

// The share of the sun's light that crosses the rings at world point q on their plane at
// cosine mu to their normal, the profile averaged over `width` world units of radius.
float hfx_ring_transmittance(vec3 q, float mu, float width) {
    const float texels = width / (u_ringOuter - u_ringInner) * u_ringTexels;
    const float s = hfx_ring_coordinate(length(q - u_planetCentre));
    const float opacity = textureLod(s_ringProfile, vec2(s, 0.5), log2(max(texels, 1.0))).a;
    return pow(max(1.0 - opacity, 0.0), 1.0 / max(mu, 1e-3));
}

// The rings' shadow at world point p (the cloud tops) for light towards l: 1 where none.
float hfx_ring_shadow(vec3 p, vec3 l) {
    const float toward = dot(l, u_ringAxis);
    const float t = dot(u_planetCentre - p, u_ringAxis) / toward; // along l to the rings' plane
    if (!(u_ringOuter > 0.0) || !(abs(toward) > 1e-4) || !(t > 0.0)) return 1.0;
    const float mu = abs(toward);
    // The sun's disc, t away along the light, spans 2 t u_sunRadius across it: 1 / mu times
    // that along the plane in the light's direction, the most of the radius it can span.
    return hfx_ring_transmittance(p + t * l, mu, 2.0 * t * u_sunRadius / mu);
}

// The area where two discs of radii a and b whose centres lie d apart overlap.
float hfx_disc_overlap(float a, float b, float d) {
    if (d >= a + b) return 0.0;
    if (d <= abs(a - b)) return HFX_RING_PI * min(a, b) * min(a, b);
    const float ca = clamp((d * d + a * a - b * b) / (2.0 * d * a), -1.0, 1.0);
    const float cb = clamp((d * d + b * b - a * a) / (2.0 * d * b), -1.0, 1.0);
    const float alpha = acos(ca), beta = acos(cb); // half the angles the chord spans at each centre
    return a * a * (alpha - ca * sqrt(1.0 - ca * ca)) + b * b * (beta - cb * sqrt(1.0 - cb * cb));
}

// The share of the sun's disc that the planet leaves uncovered, seen from world point q towards
// the sun l (unit): 1 in full light, 0 in the umbra.
float hfx_planet_sunlit(vec3 q, vec3 l) {
    const vec3 d = u_planetCentre - q;
    const float distance = length(d);
    if (!(dot(d, l) > 0.0) || !(distance > u_planetRadius)) return 1.0; // the planet is not sunward
    const float planet = asin(u_planetRadius / distance); // its angular radius
    const float apart = atan(length(cross(d, l)), dot(d, l)); // between its centre and the sun's
    const float sun = max(u_sunRadius, 1e-5);
    return 1.0 - hfx_disc_overlap(sun, planet, apart) / (HFX_RING_PI * sun * sun);
}

// The rings' light on the cloud tops at unit normal n (from the planet's centre), for light
// towards l, over the sun's own (a Lambert surface's irradiance as a share of the sun's, per
// colour): s_ringShine by latitude (sin, -1 to 1, up its rows) and by the longitude from the
// sun's meridian (0 to pi across its columns; the rings are symmetric about that meridian).
layout(binding = HFX_UNIT_RING_SHINE) uniform sampler2D s_ringShine;
vec3 hfx_ring_shine(vec3 n, vec3 l) {
    const float sinLatitude = dot(n, u_ringAxis);
    const vec3 across = n - sinLatitude * u_ringAxis, sun = l - dot(l, u_ringAxis) * u_ringAxis;
    const float c = dot(across, sun) * inversesqrt(max(dot(across, across) * dot(sun, sun), 1e-20));
    // (Level 0 by name: a shading may run where the flow has parted, a triplanar projection's.)
    return textureLod(s_ringShine, vec2(acos(clamp(c, -1.0, 1.0)) / HFX_RING_PI, 0.5 + 0.5 * sinLatitude), 0.0).rgb;
}
