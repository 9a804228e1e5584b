#pragma once
// The polar filter of a longitude-latitude field: each row is averaged along the longitude, round
// the planet, over a box that widens towards the poles. A texel's longitude spans cos(latitude)
// of the distance its latitude spans, so detail of a few texels, round on the map, is drawn near
// a pole as a thin wedge along the meridian; all the rows' wedges meet at the pole in a
// starburst. The box removes what is that much narrower across than along. As the models of the
// atmosphere on such grids filter their polar rows (Arakawa & Lamb 1977), a gas on a sphere's map
// filters its dye with it every step, a box of 1 / cos(latitude) - 1 cells (gasPolarWidths, each
// row's width given); a flat gas's planet may filter its drawn heights (smoothing: a box
// `smoothing` degrees of longitude wide at 60 degrees of latitude, growing as (1 / cos(latitude)
// - 1)^2, 0.09 of it at 40 degrees, 3.7 times it at 70, 23 times at 80; 0.75 spans the whole row
// within 2.5 degrees of a pole), so the low and middle latitudes keep their detail, and the
// polar caps keep their bands as rings and the coarse spirals about them. A row's mean is kept;
// rows whose box is at most a texel wide come through bit for bit.
//
// Owns its prefix sums, its output (made when first run into it) and its kernels. Thread: the
// thread that owns the ClContext.

#include "hfx/compute/ClContext.h"

#include <vector>

namespace hfx {

class PolarFilter {
public:
    /// width x height floats, row y at latitude ((y + 0.5) / height - 0.5) * 180 degrees;
    /// smoothing in [0, 60] degrees of longitude (0: every row copied). Throws hfx::Error naming
    /// a size or a smoothing out of range.
    PolarFilter(ClContext& cl, int width, int height, float smoothing);
    /// The same filter with each row's box width given (texels, `height` of them, each finite
    /// and >= 0; at most 1 copies the row): smoothing() is then 0. Throws hfx::Error naming a
    /// bad width.
    PolarFilter(ClContext& cl, int width, int height, const std::vector<float>& rowWidths);

    /// Enqueues the filtered `field` (width x height floats) into output() (made on the first
    /// run); does not wait.
    void run(const cl::Buffer& field);
    /// The same into `out` (width x height floats, not `field`): a caller that keeps its own
    /// buffers (a gas filtering its dye each step swaps them) needs no copy of output().
    void run(const cl::Buffer& field, const cl::Buffer& out);
    const cl::Buffer& output() const { return output_; }
    int width() const { return width_; }
    int height() const { return height_; }
    float smoothing() const { return smoothing_; }

    /// Row y's box width in texels (at most the row's width); a row of at most 1 is copied.
    static float rowWidth(int y, int width, int height, float smoothing);
    /// The filter on the host, in double precision (tests' reference): `field` row by row.
    static std::vector<float> reference(const std::vector<float>& field, int width, int height, float smoothing);
    /// The same with each row's box width given.
    static std::vector<float> reference(const std::vector<float>& field, int width, int height,
                                        const std::vector<float>& rowWidths);

private:
    ClContext& cl_;
    int width_, height_;
    float smoothing_;
    cl::Buffer prefix_, widths_, output_;
    cl::Kernel sums_, filter_;
};

} // namespace hfx
