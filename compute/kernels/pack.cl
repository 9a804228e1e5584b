/* Packs float4 (normal.xyz, height) texels into a smaller surface format, so the transfer to GL
   moves half or a quarter of the bytes and the driver converts nothing.
   vstore_half is core OpenCL C (no cl_khr_fp16 needed); _rte rounds to nearest even, as GL's
   float-to-half conversion and C++'s _Float16 do. */
/* No fused multiply-adds: the C++ encoders round each step, and so must this. */
#pragma OPENCL FP_CONTRACT OFF

__kernel void pack_half(__global const float4* in, __global half* out, int count) {
    const int i = get_global_id(0);
    if (i >= count) return;
    vstore_half4_rte(in[i], i, out);
}

/* n/2 + 1/2 and h, to 8 bits rounded to nearest; the saturating conversion maps NaN to 0, like the
   C++ encoder in SurfaceTextures::upload. */
__kernel void pack_unorm8(__global const float4* in, __global uchar4* out, int count) {
    const int i = get_global_id(0);
    if (i >= count) return;
    const float4 t = in[i];
    const float4 e = clamp((float4)(t.xyz * 0.5f + 0.5f, t.w), 0.0f, 1.0f);
    out[i] = convert_uchar4_sat(e * 255.0f + 0.5f);
}
