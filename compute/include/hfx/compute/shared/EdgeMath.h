#ifndef HFX_EDGE_MATH_H
#define HFX_EDGE_MATH_H
#include "ClPrelude.h"

/* Reading beyond a field's edges (hfx::EdgeMode). Kernels are built with -DHFX_WRAP_U=0|1 and
   -DHFX_WRAP_V=0|1 (hfx::edgeOptions), and pass them as `wrap`; the C++ references pass the
   mode's wrapsU / wrapsV. `i` lies at most one period outside [0, n): a select, not a modulo. */
HFX_FN int hfx_edge_index(int i, int n, int wrap) {
    if (wrap) return i < 0 ? i + n : (i >= n ? i - n : i);
    return i < 0 ? 0 : (i > n - 1 ? n - 1 : i);
}
/* The index after i in [0, n): one compare where hfx_edge_index needs two, for the pyramid's
   cell corners (the difference shows in BM_Pyramid, docs/history/tuning.md). */
HFX_FN int hfx_edge_next(int i, int n, int wrap) { return i + 1 < n ? i + 1 : (wrap ? 0 : n - 1); }
#endif
