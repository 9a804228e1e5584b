// Blinn-Phong of albedo and normal; the ambient light is occluded by the shading channels'
// occlusion, and their roughness has already widened and dimmed the lobe (surface.frag).
vec3 hfx_shade(HfxSurfacePoint p) {
    return p.albedo * u_ambient * p.occlusion +
           p.lit * u_lightColor * (p.albedo * p.diffuse + u_specularStrength * p.specular);
}
