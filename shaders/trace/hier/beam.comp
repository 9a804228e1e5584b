#version 450 core
// The exact tracer's beam start (hfx::ExactTracer, before a hier draw of a flat patch, seen by a
// camera or, casting into a shadow map, by the light): a lane per block of HFX_BEAM_BLOCK x
// HFX_BEAM_BLOCK pixels of the window (texel (i, j) covers the pixels [B i, B i + B) x
// [B j, B j + B)), writing the depth fraction from which on every view ray of the block may meet
// the relief (trace/hier.glsl, hfx_beam_depth); the draw's rays start there (HfxRay.start). 0 (no
// start) where the block's centre sees no point of the patch's texcoord box, as where a rasteriser
// would give the block no fragment.
//
// The block's rays are found from the screen through the patch's projective map, as trace.comp's
// hfx_patch_ray finds a pixel's (trace/hier/patch.glsl): the draw's rays to a rounding (the
// frame is surface.frag's, hfx_world_from_texture, made on the host in doubles). At
// any depth the points of the block's rays lie in the quadrilateral of its corner rays' (the
// screen maps to each plane of constant depth projectively, keeping the block's convex outline),
// so no ray strays from the centre's further than a corner does, and a corner's offset from the
// centre is linear in the depth: the larger of its offsets at the polygon and at the bottom
// bounds it. That bound, plus a margin for the rounding of this pass and the draw's, is the
// beam's reach.

#include "bindings.glsl"
#include "surface/uniforms.glsl"
#include "surface/heights.glsl"
#include "trace/common.glsl"
#include "trace/hier.glsl"
#include "trace/hier/patch.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = HFX_IMAGE_PASS_OUTPUT, r32f) uniform writeonly image2D i_beamStart;
uniform vec4 u_beamViewport; // the draw's viewport (x, y, width, height, window pixels)
uniform ivec2 u_beamBlocks;  // the blocks this draw's window holds

// The ray through the window point `window`: its entry's texcoords (uv) and where it runs in cell
// space (uv * size - 0.5) at the polygon (xy) and at the bottom of the relief (zw). False where it
// does not come down onto the patch's plane from the side its normal faces.
bool hfx_block_ray(vec2 window, out vec2 uv, out vec4 cells) {
    cells = vec4(0.0);
    float w;
    if (!hfx_patch_point((window - u_beamViewport.xy) / u_beamViewport.zw * 2.0 - 1.0, uv, w)) return false;
    const vec3 viewTS = hfx_patch_view(uv);
    if (!(viewTS.z > 0.0)) return false;
    const vec2 size = vec2(hfx_size());
    const vec2 top = uv * size - 0.5;
    cells = vec4(top, top - viewTS.xy / viewTS.z * u_depthScale * size);
    return true;
}

void main() {
    const ivec2 block = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(block, u_beamBlocks))) return;
    const vec2 centre = (vec2(block) + 0.5) * float(HFX_BEAM_BLOCK);
    vec2 uv;
    vec4 ray, corner;
    bool ok = hfx_block_ray(centre, uv, ray) && all(greaterThanEqual(uv, u_patchBox.xy)) &&
              all(lessThanEqual(uv, u_patchBox.zw));
    vec2 reach = vec2(0.0);
    for (int c = 0; c < 4; ++c) {
        const vec2 side = vec2(c & 1, c >> 1) - 0.5;
        vec2 cornerUv;
        ok = ok && hfx_block_ray(centre + side * float(HFX_BEAM_BLOCK), cornerUv, corner);
        const vec4 off = abs(corner - ray);
        reach = max(reach, max(off.xy, off.zw));
    }
    // The margin: a thousandth of a texel and 1% for the rounding of this pass's rays and of the
    // draw's interpolated ones (texcoords of a few hundred texels round to 1e-4).
    const float r = max(reach.x, reach.y) * 1.01 + 1e-3;
    imageStore(i_beamStart, block, vec4(ok ? hfx_beam_depth(ray.xy, ray.zw - ray.xy, r) : 0.0));
}
