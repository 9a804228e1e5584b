// The self-shadow a surface draw gives its point, after the tracer (trace/README.md): where the
// draw has the texel shadows (HFX_TEXEL_SHADOWS: hier's own walk at the field's samples for this
// light, drawn by hfx::TexelShadowPass) and they hold the ray's shadow (hfx_texel_shadow,
// surface/heights.glsl), their blend; else the tracer's hfx_shadow. The texel shadows are the
// renderer's cache of the walk, not part of the tracer contract.

// With HFX_DEFERRED_SHADOWS a ray the texel shadows do not hold is not walked here: it is appended
// for the pass after the draw (trace/hier/deferred.glsl), so that its warp does not wait for one
// lane's walk, with the pixel, its depth and the shadow's `fade` (the caller's factor on it);
// `slot` says where (the caller adds the pixel's colours there), and their blend is returned until
// the pass writes the pixel again. Past the buffer's capacity it is walked here.
float hfx_surface_shadow(HfxShadowRay ray, float fade, out int slot) {
    slot = -1;
#if defined(HFX_TEXEL_SHADOWS) && HFX_TEXEL_SHADOWS
    const float climb = 1.0 - ray.h0;
    float known;
    // The walk's own point (cell space), move per climb and penumbra (trace/hier.glsl).
    if (climb > 0.0 && hfx_texel_shadow(ray.uv * vec2(hfx_size()) - 0.5, ray.span / climb,
                                         1.0 / max(ray.sharpness, 1e-3), known))
        return known;
#if HFX_DEFERRED_SHADOWS
    if (climb > 0.0) {
        const uint at = atomicAdd(hfx_deferredCount, 1u);
        if (at < hfx_deferredCapacity) {
            slot = int(at);
            if (at % uint(HFX_DEFERRED_GROUP) == 0u) atomicAdd(hfx_deferredGroups, 1u); // a group begun
            const int i = HFX_DEFERRED_VEC4S * slot;
            // The pixel's centre: under sample-rate shading gl_FragCoord may be the sample's, and a
            // point drawn there would straddle two pixels. (The depth test keeps its samples.)
            hfx_deferredRays[i] = vec4(floor(gl_FragCoord.xy) + 0.5, gl_FragDepth, fade);
            hfx_deferredRays[i + 1] = vec4(ray.uv, ray.h0, ray.span.x);
            hfx_deferredRays[i + 2].x = ray.span.y;
            return known;
        }
    }
#endif
#endif
    return hfx_shadow(ray);
}
