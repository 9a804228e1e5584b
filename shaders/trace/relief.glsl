// Relief mapping (Policarpo 2005): the linear search, then six binary steps inside its bracket,
// keeping the bracket's middle; hard self-shadows.
HfxHit hfx_trace(HfxRay ray) {
    float t0, t1, d0, d1;
    if (!hfx_linear_search(ray, t0, t1, d0, d1)) return hfx_hit_at(ray, 1.0);
    if (t1 == t0) return hfx_hit_at(ray, t0); // met at the first sample
    for (int i = 0; i < 6; ++i) {
        const float mid = 0.5 * (t0 + t1);
        if (hfx_height(ray.uv - ray.parallax * mid, ray.level) >= 1.0 - mid) t1 = mid;
        else t0 = mid;
    }
    return hfx_hit_at(ray, 0.5 * (t0 + t1));
}
float hfx_shadow(HfxShadowRay ray) { return hfx_occlusion(ray) > 0.0 ? 1.0 : 0.0; }
