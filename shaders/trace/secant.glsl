// The linear search refined by three secant steps inside its bracket, then the last secant
// estimate; soft self-shadows.
HfxHit hfx_trace(HfxRay ray) {
    float t0, t1, d0, d1;
    if (!hfx_linear_search(ray, t0, t1, d0, d1)) return hfx_hit_at(ray, 1.0);
    if (t1 == t0) return hfx_hit_at(ray, t0); // met at the first sample
    for (int i = 0; i < 3; ++i) {
        const float tm = t0 + (t1 - t0) * d0 / (d0 - d1);
        const float dm = hfx_height(ray.uv - ray.parallax * tm, ray.level) - (1.0 - tm);
        if (dm >= 0.0) { t1 = tm; d1 = dm; } else { t0 = tm; d0 = dm; }
    }
    return hfx_hit_at(ray, t0 + (t1 - t0) * d0 / (d0 - d1));
}
float hfx_shadow(HfxShadowRay ray) { return clamp(hfx_occlusion(ray) * ray.sharpness, 0.0, 1.0); }
