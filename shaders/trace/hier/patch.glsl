// A flat patch (hfx::FlatPatch) as a draw places it, seen from the screen (ExactTracer's
// PatchRays): what the compute pass (trace.comp, HFX_TRACE_PATCH) and the beam prepass
// (beam.comp) find a ray from, in place of a rasteriser's fragment. Its texcoords are a projective
// map of the screen: with c(u, v) = the clip coordinates of the patch's point at (u, v), (x, y, w)
// of c is a 3x3 matrix times (u, v, 1), and its inverse, u_patchFromScreen, takes a point's (x, y)
// in clip space over w, with a 1, to (u, v, 1) / w: the entry there, and the clip w that says it
// lies ahead of the eye. A rasteriser's perspective-correct interpolation is the same map.
// u_patchEye: the eye in the patch's texture space (surface.frag's hfx_texture_from_world of the
// frame, about its point at (0, 0)), or an orthographic eye's direction in it (u_orthographic).
// u_patchBox: the box of its texcoords (umin, vmin, umax, vmax).
// Needs surface/uniforms.glsl.

#ifndef HFX_PATCH_GLSL
#define HFX_PATCH_GLSL

uniform mat3 u_patchFromScreen;
uniform vec3 u_patchEye;
uniform vec4 u_patchBox;

// The patch's point seen at `ndc` (the screen's x and y in [-1, 1]): its texcoords and its clip w,
// and true; false (both 0) where it lies behind the eye or at infinity.
bool hfx_patch_point(vec2 ndc, out vec2 uv, out float w) {
    const vec3 h = u_patchFromScreen * vec3(ndc, 1.0);
    uv = vec2(0.0);
    w = 0.0;
    if (!(h.z > 0.0)) return false;
    w = 1.0 / h.z;
    uv = h.xy * w;
    return true;
}

// The view ray at the patch's texcoords `uv`, towards the eye, in its texture space (z > 0 where
// the eye is above the patch).
vec3 hfx_patch_view(vec2 uv) { return u_orthographic != 0 ? u_patchEye : u_patchEye - vec3(uv, 0.0); }

#endif
