// Steep parallax mapping (McGuire 2005): the linear search's first sample under the surface;
// hard self-shadows (any blocker on the light ray: dark).
HfxHit hfx_trace(HfxRay ray) {
    float t0, t1, d0, d1;
    if (!hfx_linear_search(ray, t0, t1, d0, d1)) return hfx_hit_at(ray, 1.0);
    return hfx_hit_at(ray, t1);
}
float hfx_shadow(HfxShadowRay ray) { return hfx_occlusion(ray) > 0.0 ? 1.0 : 0.0; }
