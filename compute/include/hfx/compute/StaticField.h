#pragma once
// Heights that do not change: a height map from an image file (heightsFromImage), or any
// heights a tool generates. As a HeightSource it goes down the same surface pipeline as the
// generated fields (Sobel normals, pyramid, every surface format and transfer path); step(dt)
// only checks dt.
//
// Owns its device buffer. Thread: the thread that owns the ClContext.

#include "hfx/compute/HeightSource.h"

#include <vector>

namespace hfx {

class StaticField final : public HeightSource {
public:
    /// heights: width*height values in [0,1], row 0 at v = 0; refused (naming the first bad
    /// value and where it lies) when the count does not match or a value is outside [0,1].
    StaticField(ClContext& cl, int width, int height, EdgeMode edges, const std::vector<float>& heights);

    void step(double dt) override; ///< checks dt (positive, finite); nothing changes
    const cl::Buffer& buffer() const override { return height_; }
    int width() const override { return width_; }
    int height() const override { return rows_; }
    EdgeMode edges() const override { return edges_; }

private:
    int width_, rows_;
    EdgeMode edges_;
    cl::Buffer height_;
};

} // namespace hfx
