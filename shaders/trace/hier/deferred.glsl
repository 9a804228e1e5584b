// The light walks a surface draw leaves to the pass after it (HFX_DEFERRED_SHADOWS, hfx::ExactTracer):
// a pixel whose texel shadows do not hold its shadow (the hard shadow's edge crosses its cell)
// would walk its light ray inside the draw, and its warp would wait for that one lane's walk; it
// appends the ray instead, with what its colour needs. A compute pass (trace/hier/deferred.comp)
// walks the rays packed one to a lane, and a draw of points (deferred.vert) writes those pixels
// again. The colour is affine in the light factor where the shading model adds it times its
// direct light (lit, planet: hfx::shadingAffineInLight; the water's highlights roll off, and its
// walks stay in the draw), so two shadings give it for any shadow the walk finds.
//
// The buffer: a glDrawArraysIndirect command (count = rays appended, possibly past capacity;
// 1 instance), the capacity in rays, a glDispatchComputeIndirect command (the groups of
// HFX_DEFERRED_GROUP rays within the capacity begun, 1, 1), then per ray four vec4s:
//   (pixel centre x, y in window coordinates, gl_FragDepth written, the shadow's fade)
//   (the ray's uv, h0, span.x)       (span.y, the colour's linear rgb with no direct light)
//   (the direct light's linear rgb at no shadow, 0), which deferred.comp overwrites with the
//   pixel's colour as written (gamma-encoded rgb, 1)
// A ray past the capacity is walked in the draw, as without the deferral.

// A stage that only reads it defines HFX_DEFERRED_ACCESS readonly first (deferred.vert: a vertex
// stage need not be able to write storage).
#ifndef HFX_DEFERRED_ACCESS
#define HFX_DEFERRED_ACCESS
#endif
layout(std430, binding = HFX_BUFFER_DEFERRED_SHADOWS) HFX_DEFERRED_ACCESS buffer HfxDeferredShadows {
    uint hfx_deferredCount;
    uint hfx_deferredInstances;
    uint hfx_deferredFirst;
    uint hfx_deferredBaseInstance;
    uint hfx_deferredCapacity;
    uint hfx_deferredGroups, hfx_deferredGroupsY, hfx_deferredGroupsZ;
    vec4 hfx_deferredRays[];
};
const int HFX_DEFERRED_VEC4S = 4; // per ray
#define HFX_DEFERRED_GROUP 64       // rays a compute group walks (deferred.comp)
