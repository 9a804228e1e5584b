#pragma once
// Per bilinear cell of a height field, the climb past which the exact shadow walk
// (shaders/trace/hier.glsl, hfx_shadow) can stop for one directional light: beyond it a light
// ray from anywhere in the cell stays above its penumbra's cone edge, so nothing further can
// darken the point. Zero where nothing near the cell rises to the cone, which skips the walk.
// Built on the device from the heights and their BoundsPyramid each frame the field or the
// light changes (compute/kernels/clearance.cl says how); the walk's result is the same with the
// map as without, only shorter. One float per cell, width x height.
//
// Owns its buffer and kernel. Thread: the thread that owns the ClContext.

#include "hfx/compute/BoundsPyramid.h"
#include "hfx/compute/ClContext.h"
#include "hfx/core/ClearanceLight.h"

namespace hfx {

class ClearanceMap {
public:
    /// Power-of-two sizes, as the pyramid's (the walk wraps cells with a bitwise and).
    ClearanceMap(ClContext& cl, int width, int height, EdgeMode edges);

    /// Enqueues the map of `heights` (width x height floats) for `light`; `pyramid` must be
    /// built from the same heights first (its levels are read). Does not wait.
    void build(const cl::Buffer& heights, const BoundsPyramid& pyramid, const ClearanceLight& light);

    const cl::Buffer& buffer() const { return buffer_; }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    ClContext& cl_;
    int width_, height_;
    cl::Buffer buffer_;
    cl::Buffer offsets_; ///< the pyramid's level offsets (texels), made by the first build
    cl::Kernel kernel_;
};

} // namespace hfx
