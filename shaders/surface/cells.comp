#version 450 core
// The level-0 cells' samples for the exact tracer's patch solve (SurfaceTextures::cells): per
// cell (i, j) the heights of its four corner samples, in textureGather's order (x: (i, j+1),
// y: (i+1, j+1), z: (i+1, j), w: (i, j)); across an edge that wraps the first sample, across one
// that clamps the last again, as the pyramid's level 0 bounds them. One imageLoad in the walk
// instead of a gather: on llvmpipe a gather costs about 2.2x an RGBA32F imageLoad. Built from the stored texels whenever they change
// (CellsPass), so the solve reads exactly what a gather would.
layout(local_size_x = 8, local_size_y = 8) in;
#include "bindings.glsl"
layout(binding = HFX_UNIT_SURFACE) uniform sampler2D s_surface;
layout(rgba32f, binding = HFX_IMAGE_CELLS) writeonly uniform image2D i_cells;
uniform ivec2 u_wrap;

void main() {
    const ivec2 size = textureSize(s_surface, 0), c = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(c, size))) return;
    const ivec2 last = size - 1, n = mix(min(c + 1, last), (c + 1) & last, bvec2(u_wrap)); // power-of-two sizes
    imageStore(i_cells, c,
               vec4(texelFetch(s_surface, ivec2(c.x, n.y), 0).w, texelFetch(s_surface, n, 0).w,
                    texelFetch(s_surface, ivec2(n.x, c.y), 0).w, texelFetch(s_surface, c, 0).w));
}
