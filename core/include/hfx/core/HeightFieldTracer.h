#pragma once
// Exact ray intersection with the bilinearly interpolated height field, in double precision:
// the ground truth for POM's search. Inside one texel cell the bilinear height along a ray is a
// quadratic in the ray parameter, so the first hit is the smallest root in the cell, found while
// walking the cells the ray crosses (2D DDA). Same sampling conventions as GL_LINEAR: texel
// centres at (i + 0.5) / width, edges wrapped (GL_REPEAT) or clamped (GL_CLAMP_TO_EDGE).
//
// Thread: const methods may be called from any number of threads at once.

#include "hfx/core/EdgeMode.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <vector>

namespace hfx {

struct HeightFieldHit {
    double t;        ///< ray parameter at the hit
    glm::dvec2 uv;   ///< texcoords of the hit (not wrapped into [0,1))
    double height;   ///< surface height there, in [0,1]
};

class HeightFieldTracer {
public:
    /// heights: width * height samples, row 0 at v = 0 (the layout of compute buffers).
    HeightFieldTracer(std::vector<float> heights, int width, int height, EdgeMode edges);

    /// Bilinear height at texcoords (u, v), as the GPU's linear filter (at full precision) sees it.
    double heightAt(glm::dvec2 uv) const;

    /// First point where the ray origin + t * direction reaches the surface (height >= ray
    /// height), for t in [0, tMax]. Positions are (u, v, h): texcoords and height units. A ray
    /// that starts at or below the surface hits at t = 0.
    std::optional<HeightFieldHit> intersect(glm::dvec3 origin, glm::dvec3 direction,
                                            double tMax) const;

    /// The ray POM traces: it enters the top (h = 1) at uv0 and travels against `toEye`, a
    /// texture-space vector (u, v, along the normal, in texture units) pointing to the eye;
    /// `depthScale` texture units separate h = 1 and h = 0. t is the depth fraction 1 - h of
    /// the ray, as the shader's trace output reports it.
    std::optional<HeightFieldHit> traceView(glm::dvec2 uv0, glm::dvec3 toEye, double depthScale) const;

    int width() const { return width_; }
    int height() const { return height_; }

private:
    double sample(long long i, long long j) const;

    std::vector<float> heights_;
    int width_, height_;
    EdgeMode edges_;
};

} // namespace hfx
