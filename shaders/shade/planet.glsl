// A planet: the sphere's own normal sets day and night, the relief's normal the detail. The
// cloud deck darkens towards the limb by Minnaert's law, I = mu0^k mu^(k-1) with k = 0.85 (gas
// giants' discs in visible light lie near 0.8 to 1; k = 1 is Lambert), and a haze scatters blue
// light along the lit limb. The upper haze also carries sunlight a little past the terminator:
// the sun's cosine mu0 is replaced by a twilight that joins it at mu0 = w with the same value and
// slope and fades past it exponentially (w e^((mu0 - w) / w)), so the light leaves the disc
// without a kink. The night side gets only a faint skylight: the ambient light fades to
// HFX_NIGHT_SKY of itself across the terminator. The same haze scatters the sunlight that crosses
// it: of the light reaching the cloud tops the share e^(-tau / mu0) comes straight from the sun
// (tau the haze's optical depth, mu0 the sun's elevation over the sphere) and casts the relief's
// shadows; the rest arrives diffuse and fills them. So low suns, whose straight light crosses
// the most haze, cast the palest shadows, where bare relief at grazing light would speckle the
// terminator's side with black. Where the planet has rings, their shadow (shade/rings.glsl)
// dims the sunlight before it reaches the haze: the straight light, its glint and the limb's glow;
// and the sunlight they scatter lights it in turn (ring shine: hfx_ring_shine, a fill from a
// large part of its sky, so it casts no relief shadows), the night side under their lit face most.

#include "shade/rings.glsl"

const float HFX_TWILIGHT = 0.1;   // w: about 6 degrees of the sun's elevation
const float HFX_NIGHT_SKY = 0.05; // the night side's share of the ambient light
const float HFX_HAZE_DEPTH = 0.1; // tau: 37% of the light straight at 6 degrees, 90% overhead

float hfx_twilight(float mu) {
    return mu >= HFX_TWILIGHT ? mu : HFX_TWILIGHT * exp((mu - HFX_TWILIGHT) / HFX_TWILIGHT);
}

// The cloud tops emit no light of their own.
vec3 hfx_emission(HfxSurfacePoint p) { return vec3(0.0); }

vec3 hfx_shade(HfxSurfacePoint p) {
    const float muSphere = dot(p.geometricNormal, p.lightDir);
    const float k = 0.85;
    // Minnaert with the relief's mu0 for the detail: mu0 * (mu0 mu)^(k-1), the sphere's mu0 in
    // the second factor (which is bounded: a twilight is never 0).
    const float limb = pow(max(dot(p.geometricNormal, p.viewDir), 0.05), k - 1.0) *
                       pow(hfx_twilight(muSphere), k - 1.0);
    const float diffuse = hfx_twilight(dot(p.normal, p.lightDir)) * min(limb, 4.0);
    const float day = 1.0 / (1.0 + exp(-2.0 * muSphere / HFX_TWILIGHT)); // 0.5 at the terminator
    const float sky = mix(HFX_NIGHT_SKY, 1.0, day);
    const float haze = 0.5 * pow(1.0 - p.cosView, 3.0) * day;
    const float straight = exp(-HFX_HAZE_DEPTH / max(muSphere, 1e-3));
    const float lit = 1.0 - straight * (1.0 - p.lit);
    const float rings = hfx_ring_shadow(p.position, p.lightDir);
    const vec3 shine = u_ringShine > 0.0 ? hfx_ring_shine(p.geometricNormal, p.lightDir) : vec3(0.0);
    return p.albedo * p.occlusion * (u_ambient * sky + u_lightColor * shine) +
           rings * u_lightColor *
               (lit * (p.albedo * diffuse + day * u_specularStrength * p.specular) + haze * vec3(0.35, 0.55, 1.0));
}
