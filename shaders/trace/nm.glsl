// Normal mapping: no parallax; the surface is shaded where the view ray meets the polygon.
HfxHit hfx_trace(HfxRay ray) { return HfxHit(ray.uv, 0.0); }
float hfx_shadow(HfxShadowRay ray) { return 0.0; }
