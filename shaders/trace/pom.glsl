// Parallax occlusion mapping (Tatarchuk 2006): the linear search, then the ray meets the line
// segment between the last two samples (the piecewise-linear height profile) rather than taking
// the nearest sample; soft self-shadows weighted by blocker distance.
HfxHit hfx_trace(HfxRay ray) {
    float t0, t1, d0, d1;
    if (!hfx_linear_search(ray, t0, t1, d0, d1)) return hfx_hit_at(ray, 1.0);
    if (t1 == t0) return hfx_hit_at(ray, t0); // met at the first sample
    return hfx_hit_at(ray, t0 + (t1 - t0) * d0 / (d0 - d1));
}
float hfx_shadow(HfxShadowRay ray) { return clamp(hfx_occlusion(ray) * ray.sharpness, 0.0, 1.0); }
