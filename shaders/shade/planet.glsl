// A planet: the sphere's own normal sets day and night (a soft terminator), the relief's normal
// the detail. The cloud deck darkens towards the limb by Minnaert's law, I = (N.L)^k (N.V)^(k-1)
// with k = 0.85 (gas giants' discs in visible light lie near 0.8 to 1; k = 1 is Lambert), and a
// haze scatters blue light along the lit limb.
vec3 hfx_shade(HfxSurfacePoint p) {
    const float day = smoothstep(-0.05, 0.3, dot(p.geometricNormal, p.lightDir));
    const float k = 0.85;
    const float limb = pow(max(dot(p.geometricNormal, p.viewDir), 0.05), k - 1.0) *
                       pow(max(dot(p.geometricNormal, p.lightDir), 0.0) + 1e-4, k - 1.0);
    const float diffuse = p.diffuse * min(limb, 4.0);
    const float haze = 0.5 * pow(1.0 - p.cosView, 3.0) * day;
    return p.albedo * u_ambient * p.occlusion +
           day * p.lit * u_lightColor * (p.albedo * diffuse + u_specularStrength * p.specular) +
           haze * vec3(0.35, 0.55, 1.0) * u_lightColor;
}
