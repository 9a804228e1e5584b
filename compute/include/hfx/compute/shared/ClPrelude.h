#ifndef HFX_CL_PRELUDE_H
#define HFX_CL_PRELUDE_H
/* Lets one header hold math that compiles both as C++ (the CPU references) and as OpenCL C
   (the kernels), so the reference cannot drift from the kernel. */
#ifdef __OPENCL_VERSION__
/* No fused multiply-add behind our back: the kernels must round as the C++ references do. */
#pragma OPENCL FP_CONTRACT OFF
#define HFX_FN
/* Forced inline, for math that a kernel calls several times per work-item: PoCL vectorises a
   kernel across its work-items only when no call is left (the gas's advection spent much of its
   time in an out-of-line hfx_gas_sample). Not the default: the noise kernels ran slower inlined.
   The figures: BM_Gas and BM_Noise in docs/history/tuning.md. */
#define HFX_FN_INLINE static inline __attribute__((always_inline))
#define HFX_CONSTANT __constant
#define HFX_GLOBAL __global
#define HFX_MIN fmin
#define HFX_MAX fmax
#define HFX_COS cos
#define HFX_FABS fabs
#define HFX_SQRT sqrt
#define HFX_SIN sin
#define HFX_POW pow
#define HFX_LOG2 log2
#define HFX_FLOOR floor
#define HFX_CEIL ceil
#define HFX_ATAN2 atan2
#else
#include <cmath>
#define HFX_FN inline
#define HFX_FN_INLINE inline
#define HFX_CONSTANT inline constexpr
#define HFX_GLOBAL
#define HFX_MIN std::fmin
#define HFX_MAX std::fmax
#define HFX_COS std::cos
#define HFX_FABS std::fabs
#define HFX_SQRT std::sqrt
#define HFX_SIN std::sin
#define HFX_POW std::pow
#define HFX_LOG2 std::log2
#define HFX_FLOOR std::floor
#define HFX_CEIL std::ceil
#define HFX_ATAN2 std::atan2
#endif
#define HFX_TWO_PI 6.28318530717958647692f
#endif
