// The self-shadow a surface draw gives its point, after the tracer (trace/README.md): where the
// draw has the texel shadows (HFX_TEXEL_SHADOWS: hier's own walk at the field's samples for this
// light, drawn by hfx::TexelShadowPass) and they hold the ray's shadow (hfx_texel_shadow,
// surface/heights.glsl), their blend; else the tracer's hfx_shadow. The texel shadows are the
// renderer's cache of the walk, not part of the tracer contract.

float hfx_surface_shadow(HfxShadowRay ray) {
#if defined(HFX_TEXEL_SHADOWS) && HFX_TEXEL_SHADOWS
    const float climb = 1.0 - ray.h0;
    float known;
    // The walk's own point (cell space), move per climb and penumbra (trace/hier.glsl).
    if (climb > 0.0 && hfx_texel_shadow(ray.uv * vec2(hfx_size()) - 0.5, ray.span / climb,
                                         1.0 / max(ray.sharpness, 1e-3), known))
        return known;
#endif
    return hfx_shadow(ray);
}
