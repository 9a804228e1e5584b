// Parallax mapping with offset limiting (Welsh 2004): one fetch, the offset the height there
// would give, limited to the height (the view vector's xy not divided by z), so grazing views do
// not swim. No search, so no self-shadows.
HfxHit hfx_trace(HfxRay ray) {
    const float depth = 1.0 - hfx_height(ray.uv, ray.level);
    return HfxHit(ray.uv - ray.parallax * ray.cosTheta * depth, depth);
}
float hfx_shadow(HfxShadowRay ray) { return 0.0; }
