// A planet: the sphere's own normal sets day and night (a soft terminator), the relief's normal
// the detail; an atmosphere brightens the lit limb.
vec3 hfx_shade(HfxSurfacePoint p) {
    const float day = smoothstep(-0.05, 0.3, dot(p.geometricNormal, p.lightDir));
    const float rim = 0.5 * pow(1.0 - p.cosView, 3.0) * day;
    return p.albedo * u_ambient + day * p.lit * u_lightColor * (p.albedo * p.diffuse + u_specularStrength * p.specular) +
           rim * vec3(0.35, 0.55, 1.0) * u_lightColor;
}
