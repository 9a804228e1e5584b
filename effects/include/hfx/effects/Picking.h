#pragma once
// Picking on a displaced surface: a world-space ray (the camera's ray through the cursor) meets
// the height field that POM draws, found exactly by the bilinear ray/height-field intersection
// (HeightFieldTracer), so a click lands on the texel the user sees, not on the flat polygon.
//
// Owns nothing. Thread: any; pure CPU work.

#include "hfx/core/Camera.h"
#include "hfx/core/HeightFieldTracer.h"
#include "hfx/core/Mesh.h"

#include <glm/mat4x4.hpp>

#include <optional>

namespace hfx {

/// An affine patch of surface: the world position at texcoords (0, 0), dP/du, dP/dv and the unit
/// normal (the side the relief rises towards; h = 1 lies on the patch, h = 0 depthScale texture
/// units below it, as the shader traces).
struct SurfaceFrame {
    glm::dvec3 origin;
    glm::dvec3 tangent;
    glm::dvec3 bitangent;
    glm::dvec3 normal;
    /// The frame of a makePlane mesh drawn with `model`.
    static SurfaceFrame ofPlane(const PlaneConfig& plane, const glm::mat4& model = glm::mat4(1.0f));
};

struct SurfacePick {
    glm::dvec2 uv;     ///< texcoords of the hit (may lie outside [0,1) on a repeating plane)
    glm::dvec3 world;  ///< the displaced point in world space
    double height;     ///< h at the hit
};

/// The first point where `ray` meets the relief under `frame`, or nothing. `uvBounds`
/// (umin, vmin, umax, vmax) limits the patch: hits outside are misses. Throws hfx::Error naming
/// a ray or frame that is not finite, a ray of no direction, or a bad depthScale.
std::optional<SurfacePick> pickSurface(const Ray& ray, const SurfaceFrame& frame,
                                       const HeightFieldTracer& heights, double depthScale,
                                       glm::dvec4 uvBounds = {-1e30, -1e30, 1e30, 1e30});

} // namespace hfx
