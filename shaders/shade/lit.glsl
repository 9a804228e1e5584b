// Blinn-Phong of albedo and normal.
vec3 hfx_shade(HfxSurfacePoint p) {
    return p.albedo * u_ambient + p.lit * u_lightColor * (p.albedo * p.diffuse + u_specularStrength * p.specular);
}
