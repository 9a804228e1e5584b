#pragma once
// Colours any float field (a height source's buffer, the gas's dye) through a ramp of colour
// stops into an 8-bit RGBA buffer on the device: simulation-driven albedo, uploaded each frame
// like the heights. The output buffer is host-visible so mapping it for GL costs no copy.
//
// Thread: the thread that owns the ClContext.

#include "hfx/compute/ClContext.h"

#include <glm/vec3.hpp>

#include <vector>

namespace hfx {

struct ColorStop {
    float position; ///< in [0,1], rising from stop to stop
    glm::vec3 color; ///< in [0,1]
};

class ColorRamp {
public:
    /// 2 to 64 stops; throws hfx::Error naming the stop that is out of range or out of order.
    ColorRamp(ClContext& cl, int width, int height, std::vector<ColorStop> stops);

    /// Enqueues the colouring of `field` (width x height floats); does not wait.
    void run(const cl::Buffer& field);
    void setStops(std::vector<ColorStop> stops);

    /// width x height RGBA8 texels, row 0 at v = 0.
    const cl::Buffer& output() const { return output_; }
    const std::vector<ColorStop>& stops() const { return stops_; }
    int width() const { return width_; }
    int height() const { return height_; }
    /// The stops packed as the kernel reads them: (position, r, g, b) each.
    static std::vector<float> pack(const std::vector<ColorStop>& stops);

private:
    ClContext& cl_;
    int width_, height_;
    std::vector<ColorStop> stops_;
    cl::Buffer output_, stopBuffer_;
    cl::Kernel kernel_;
};

} // namespace hfx
