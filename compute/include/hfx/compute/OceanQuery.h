#pragma once
// The ocean's surface on the CPU, for buoyancy and gameplay: the height of the sea the renderer
// draws at any point and any time, without reading the device back or stepping through frames.
//
// An OceanQuery is a snapshot of an OceanField's spectra (h0, the wind change in progress, the
// frequencies, the cascades' lengths and choppiness). At time t it does what the device does,
// with the same float math (OceanMath.h, shared with ocean.cl): per cascade the spectra of h, Dx
// and Dy at t, their inverse transforms (FFTW, single precision), the packed grid of the
// displacement and its gradient (hfx_ocean_pack);
// then, at the four texels around each point, the Lagrangian point x0 displaced onto the texel
// by the same Newton steps and h(x0), blended bilinearly. The cascades' heights add up: the
// result is the surface the renderer traces (each cascade's OceanCascade::meters, filtered
// bilinearly) in metres above the mean sea level, to float rounding (tested: 1e-5 m on 2 m
// waves), so a buoy placed with it sits on the water drawn. (Newton at the point itself would
// be the continuous surface rather than the drawn one: up to 3 cm off it at sharp crests.)
//
// Points are metres in the ocean's plane, from the patch origin: u along the wave vectors' x,
// v along y (the texcoords times OceanField::config().patchMeters). Any point: the sea is
// periodic, and each point is reduced to each cascade's patch in double first, so points
// kilometres away keep their precision.
//
// Cost: the grids at a new t take 3 transforms per cascade (about 5 ms for four 256^2 cascades
// on one core; docs/history/tuning.md); the query keeps them, so every batch at the same t costs only
// the points (microseconds each). After OceanField::setWind or setAmplitudes, update() takes the
// new spectra.
//
// Thread: any, independent of the ClContext; one query is used by one thread at a time (it
// caches the grids of the last t). Several queries may run on several threads.

#include "hfx/compute/OceanField.h"

#include <glm/vec2.hpp>

#include <memory>
#include <span>
#include <vector>

namespace hfx {

class OceanQuery {
public:
    explicit OceanQuery(const OceanField& ocean);
    ~OceanQuery();
    OceanQuery(OceanQuery&&) noexcept;
    OceanQuery& operator=(OceanQuery&&) noexcept;

    /// Takes the field's spectra again (after setWind, setAmplitudes); the field must have the
    /// same size and cascade count, or this throws and changes nothing.
    void update(const OceanField& ocean);

    /// The sea's height (m) at each point (m) at time t (s, finite). Throws on a non-finite
    /// time or point, naming it; `out` must hold points.size() values.
    void heights(std::span<const glm::vec2> points, double t, std::span<float> out);
    std::vector<float> heights(std::span<const glm::vec2> points, double t);
    /// One cascade's share of the height (its OceanCascade::meters, filtered bilinearly).
    std::vector<float> cascadeHeights(int cascade, std::span<const glm::vec2> points, double t);

    int cascadeCount() const;

private:
    struct Grids;
    void prepare(double t);
    float cascadeHeight(int cascade, glm::vec2 point) const;
    void check(std::span<const glm::vec2> points, double t) const;

    std::unique_ptr<Grids> grids_;
};

} // namespace hfx
