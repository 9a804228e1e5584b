// The exact tracer's walks in a compute pass (HFX_COMPUTE_TRACE, hfx::ExactTracer, TracePass::Compute).
// On a GPU that gives graphics a few of its cores (an H100 or H200: ../docs/BENCHMARKS.md), the
// walks of a fragment stage run on those few, while a compute dispatch runs them on all; a
// fragment's warp also waits for its slowest lane among quads of one primitive, where a
// compute group packs 8x8 pixels. So the draw is split in three:
//   1. rays   (surface.frag, HFX_COMPUTE_TRACE 1): the mesh drawn with early depth tests and no
//             colour or depth written; each pixel's fragment stores its view ray in its slot;
//   2. walks  (trace/hier/trace.comp): a lane per pixel walks its view ray and then its light ray
//             (from the texel shadows where they hold it), and stores the hit and its shadow;
//   3. shade  (surface.frag, HFX_COMPUTE_TRACE 2): the mesh drawn as always, each fragment reading
//             its hit from its slot instead of walking.
// On a flat patch (HFX_TRACE_PATCH) there is no rays draw: its texcoords are a projective map of
// the screen, the one a rasteriser's perspective-correct interpolation computes, so the walks pass
// finds each pixel's ray as the rays draw's fragment had it and marks the slot; it walks the
// pixels a nearer surface hides too (their shading fragments fail the depth test), where a
// fragment pass costs what a GPU that draws with a few cores spends on any pass.
// The shading draw's fragments are among the rays draw's: a fragment writes the hit's depth, which
// lies behind the polygon's, under the same depth test, and nothing is drawn in between. A stamp
// per draw marks the slots it wrote. A fragment whose slot holds no ray of this draw's passed the
// depth test only by a rounding of its depth (its polygon failed it): it is discarded. A helper
// lane past the mesh's edge has none either: for the derivatives it takes a quad neighbour's
// depth along its own ray. So the shading draw holds no walk, and none of the walk's registers.
//
// The two draws meet each pixel at most once where the mesh is convex (Mesh::convex: a flat patch,
// a sphere): its front faces do not overlap on the screen. Only front faces store a ray; a back
// face's fragment (hidden behind a front face, or seen from inside) is normal mapped, as the
// draw's own test (the view below the polygon) has it.
// A triplanar mapping walks a ray for each projection the pixel weighs: each has its own plane
// of slots (its axis), and the walks pass a lane per slot of every plane.
//
// The buffers, a slot per pixel of the viewport in each plane (one, or a triplanar mapping's
// three), ((plane * u_traceHeight) + y - y0) * u_traceWidth + x - x0:
//   hfx_traceRays   rays: (the ray's uv, its parallax); walks: (the hit's uv, depth fraction, the
//                   self-shadow before the caller's fade, or -1 where no light ray is walked)
//   hfx_traceInfo   x: rays: the ray's tolerance (its float's bits), the sign bit set where the
//                   light ray is to be walked (the draw's test: the light above the polygon);
//                   walks: the fetches the walks made. y: the mark (hfx_trace_mark: the draw's
//                   stamp, and whether the pixel's ray is traced or normal mapped) in the high 16
//                   bits, the level-of-detail blend to the entry in the low 16 (unorm)
//   hfx_traceLights with HFX_TRACE_LIGHTS (the light is not one for the whole draw: a curved mesh,
//                   a silhouette fade): the light ray's texcoords per unit climbed; else every
//                   pixel's is u_shadowLight.xy (the flat patch's, ExactTracer)

#ifndef HFX_TRACE_ACCESS
#define HFX_TRACE_ACCESS
#endif
layout(std430, binding = HFX_BUFFER_TRACE_RAYS) HFX_TRACE_ACCESS buffer HfxTraceRays { vec4 hfx_traceRays[]; };
layout(std430, binding = HFX_BUFFER_TRACE_INFO) HFX_TRACE_ACCESS buffer HfxTraceInfo { uvec2 hfx_traceInfo[]; };
#ifndef HFX_TRACE_LIGHTS
#define HFX_TRACE_LIGHTS 0
#endif
#if HFX_TRACE_LIGHTS
layout(std430, binding = HFX_BUFFER_TRACE_LIGHTS) HFX_TRACE_ACCESS buffer HfxTraceLights { vec2 hfx_traceLights[]; };
#endif
// hfx_traceInfo's x: the tolerance's bits, its sign bit where the light ray is walked.
const uint HFX_TRACE_WALKS_LIGHT = 0x80000000u;

int hfx_trace_slot(ivec2 window, int plane) {
    return (plane * u_traceHeight + window.y - u_traceOrigin.y) * u_traceWidth + window.x - u_traceOrigin.x;
}
// A slot's mark for this draw (u_traceStamp: 1 to 32767): its stamp and whether its ray is traced.
uint hfx_trace_mark(bool traced) { return (u_traceStamp * 2u + uint(traced)) << 16; }
