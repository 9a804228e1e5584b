#pragma once
// Height fields with known truth, and the CPU side of the render tests.

#include "hfx/core/Camera.h"
#include "hfx/core/HeightFieldTracer.h"
#include "hfx/core/SurfaceTextures.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <vector>

namespace hfx::test {

/// h(x, y) = 0.5 + sum_k a_k sin(2 pi (m_k x + n_k y) / N + phi_k) at texel (x, y), periodic.
struct SineTerm {
    double amplitude, m, n, phase;
};
std::vector<float> sumOfSines(int size, const std::vector<SineTerm>& terms);

/// The relief many render tests draw: two sines on a wrapped field of field² texels (no mip maps),
/// its Sobel normals for the depth, grey. Needs a GL context.
struct SineRelief {
    SineRelief(int field, float depthScale);
    std::vector<float> heights;
    SurfaceTextures textures;
};

/// A field with sharp-edged features: raised square blocks on a floor (mortar at h = 0).
std::vector<float> blocks(int size, int blocksPerEdge);

/// The plane of the render tests: edge `planeSize` world units, texcoords 0..1, normal +Y.
struct PlaneView {
    float planeSize = 2.0f;
    Camera camera;
    /// Entry texcoords and texture-space vector towards the eye of the pixel (x, y) from the
    /// bottom; false when the pixel's ray misses the plane.
    bool pixelRay(int x, int y, int width, int height, glm::dvec2& uv0, glm::dvec3& toEye) const;
};

/// A camera looking at the plane's centre from `angleDegrees` off its normal.
Camera cameraAtAngle(double angleDegrees, float distance, float aspect);

/// `projection` with its near plane moved onto `plane` (view space, (n, d): n . p + d = 0; kept
/// where positive, the eye on the other side), the far plane tilted to keep the view's volume:
/// Lengyel's oblique near-plane clipping, as an engine's planar reflection clips at the water.
glm::mat4 obliqueNearPlane(glm::mat4 projection, const glm::vec4& plane);

/// What an 8-bit target holds of a linear colour (hfx_output's display values): clamped to [0, 1],
/// gamma 2.2.
float displayValue(float linear);
glm::vec3 displayValue(glm::vec3 linear);
/// The water's roll-off of its display colours above a knee at 0.75 (shade/water.glsl).
float waterRollOff(float linear);
glm::vec3 waterRollOff(glm::vec3 linear);

struct ErrorStats {
    double mean = 0, p95 = 0, max = 0;
    size_t count = 0;
};
ErrorStats statistics(std::vector<double> errors);

} // namespace hfx::test
