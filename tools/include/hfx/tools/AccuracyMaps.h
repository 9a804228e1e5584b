#pragma once
// The four height maps issue 14's accuracy and cost targets are stated on, made the same way for
// the accuracy report (hfx-demo bench-accuracy), the tracer timing (hfx-demo bench-tracers) and
// the tests that hold the default tracer to those targets: smooth waves (three sines), bricks
// (the demo's wall), noise (5-octave fBm, contrast 0.9 about the middle) and a decal-damaged
// wall (the bricks with 40 bullet holes and an explosion's crater and debris). Heights in [0, 1],
// row-major, n x n, periodic where the map is.
//
// Thread: the thread that owns the ClContext.

#include "hfx/compute/ClContext.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace hfx {

struct AccuracyMap {
    std::string name; ///< "smooth waves", "bricks", "noise", "damaged wall"
    std::vector<float> heights;
};

/// The four maps at n x n texels (n a power of two from 16 up; the noise and decal kernels run on
/// `cl`); throws hfx::Error naming n otherwise.
std::vector<AccuracyMap> accuracyMaps(ClContext& cl, int n);

/// The first of them alone, made on the CPU: 0.5 plus three sines periodic on n texels.
std::vector<float> smoothWaves(int n);

/// The direction towards the light the accuracy figures, the tracer timing and their tests use,
/// for the plane whose normal is +Y: `degreesOffNormal` from it, its azimuth fixed ((0.8, 0.6) in
/// x and z, so shadows fall along neither texture axis). Unit length.
glm::vec3 accuracyLight(float degreesOffNormal = 60.0f);

} // namespace hfx
