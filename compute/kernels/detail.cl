/* Adds the relief that a field gained since `base` to an artist's normal map: in slope space
   (x/z, y/z), where heights add, out = detail + (current - base). Where nothing changed the
   detail normal comes through exactly; `current` and `base` are the Sobel normals (sobel.cl) of
   the changed and the original heights, made for the same depth, `detail` the normal map (xyz)
   in the same layout. Writes `current` in place, keeping its height (w). */
__kernel void add_detail(__global float4* current, __global const float4* base,
                         __global const float4* detail, int n) {
    int k = get_global_id(0);
    if (k >= n) return;
    float4 c = current[k], b = base[k], d = detail[k];
    if (c.x == b.x && c.y == b.y && c.z == b.z) {
        current[k] = (float4)(d.x, d.y, d.z, c.w);
        return;
    }
    float dz = fmax(d.z, 0.05f);
    float sx = d.x / dz + (c.x / c.z - b.x / b.z);
    float sy = d.y / dz + (c.y / c.z - b.y / b.z);
    float inv = rsqrt(sx * sx + sy * sy + 1.0f);
    current[k] = (float4)(sx * inv, sy * inv, inv, c.w);
}
