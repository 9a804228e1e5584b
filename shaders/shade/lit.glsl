// The light a glowing point emits (linear RGB) at heat t, 0 to 1: embers, dark red through orange
// to a yellow white, their radiance growing as t^2 (a rough blackbody ramp: red shows first,
// blue last).
vec3 hfx_ember(float t) {
    const float t2 = t * t;
    return 2.5 * t2 * vec3(1.0, 0.12 + 0.6 * t2, 0.02 + 0.4 * t2 * t2);
}

// What the point emits itself, lit or not (the shading channels' heat as embers; a deferred
// engine's emission output, hfx::SurfaceOutputs::emission).
vec3 hfx_emission(HfxSurfacePoint p) { return hfx_ember(p.glow); }

// Blinn-Phong of albedo and normal; the ambient light is occluded by the shading channels'
// occlusion, and their roughness has already widened and dimmed the lobe (surface.frag); and what
// the point emits.
vec3 hfx_shade(HfxSurfacePoint p) {
    return p.albedo * u_ambient * p.occlusion +
           p.lit * u_lightColor * (p.albedo * p.diffuse + u_specularStrength * p.specular) + hfx_emission(p);
}
