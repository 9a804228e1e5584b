#pragma once
// What every generated height field is to the rest of the frame: a float buffer of
// width x height texels, row y at v = (y + 0.5) / height, h in [0,1], refreshed by step(dt).
// The Sobel filter, the height-bounds pyramid and the GL upload consume it as it is.
//
// Thread: the thread that owns the ClContext it was made with.

#include "hfx/compute/ClContext.h"

namespace hfx {

class HeightSource {
public:
    virtual ~HeightSource() = default;
    /// Advances by dt seconds (> 0, finite) and enqueues the new field; does not wait.
    virtual void step(double dt) = 0;
    virtual const cl::Buffer& buffer() const = 0;
    virtual int width() const = 0;
    virtual int height() const = 0;
    /// How the field continues beyond its edges: Wrap when it tiles, WrapU for a
    /// longitude-latitude grid, Clamp otherwise. Sobel, the pyramid and the textures follow it.
    virtual EdgeMode edges() const = 0;
};

} // namespace hfx
