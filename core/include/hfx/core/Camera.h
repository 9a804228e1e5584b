#pragma once
// A perspective look-at camera (right-handed, OpenGL clip space).
//
// Owns nothing (a value type). Thread: any; no GL calls.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <span>

namespace hfx {

struct Ray {
    glm::dvec3 origin;
    glm::dvec3 direction; ///< unit length
};

struct Camera {
    glm::vec3 position{0.0f, 1.0f, 2.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovY = 0.8f; ///< radians
    float aspect = 16.0f / 9.0f;
    float nearPlane = 0.01f;
    float farPlane = 100.0f;
    /// Shifts the image by this much in normalised device coordinates (2 / width per pixel): a
    /// subpixel jitter, as temporal anti-aliasing uses; the accuracy tests move a render by a
    /// fraction of the rasteriser's subpixel grid with it.
    glm::vec2 jitter{0.0f};
    /// The depth convention. false (GL's default): the near plane at depth -1 and the far at 1 in
    /// clip space ([-1, 1]), depth tested with GL_LESS over a depth cleared to 1. true (reversed Z):
    /// the near plane at 1 and the far at 0, for GL's [0, 1] clip depth
    /// (glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)), depth tested with GL_GREATER over a depth
    /// cleared to 0; a float depth buffer then keeps its precision into the distance. The
    /// renderers draw a camera only under its own clip control and refuse the other by name.
    bool reversedZ = false;
    /// An engine's own projection in place of fovY, aspect, nearPlane and farPlane (jitter still
    /// moves it): an off-axis one (a VR eye's), an oblique near plane (a planar reflection's), an
    /// orthographic one (an editor's or a top-down game's view: parallel rays, all along the view
    /// axis). It must be a perspective projection in GL's clip space, w the distance in front of
    /// the eye (glm::frustum, glm::perspective and their _ZO forms), or an orthographic one, w 1
    /// (glm::ortho and its _ZO form), mapping depth the way reversedZ says.
    std::optional<glm::mat4> customProjection;
    /// A mirror's view: the image flipped left to right, view() lookAt's followed by a flip of the
    /// eye's x axis. An engine's planar reflection renders with its view times a reflection about
    /// the mirror's plane (a determinant of -1); fromMatrices sets this for such a view, and the
    /// renderers turn the front faces' winding with it.
    bool mirrored = false;
    /// The previous frame's view-projection without its jitter, for the screen motion the draws
    /// write (SurfaceRenderer::setMotionOutput, for an engine's temporal anti-aliasing or motion
    /// blur). Empty: this frame's, so that only a mesh's own motion shows
    /// (DrawOptions::previousModel). A jitter the engine puts in customProjection rather than in
    /// `jitter` shows in the motion.
    std::optional<glm::mat4> previousViewProjection;

    /// Throws hfx::Error naming the field: a position, target, up or jitter not finite, the
    /// position on the target (no view direction), an up along the view direction (no roll),
    /// fovY outside (0, pi), an aspect not positive, or not 0 < nearPlane < farPlane, all finite;
    /// a custom projection not finite, not invertible, neither a perspective nor an orthographic
    /// one, or mapping depth against reversedZ; a previousViewProjection not finite.
    /// What the renderers call before they draw: any of these makes the view matrix a NaN.
    void validate() const;

    /// A custom orthographic projection's camera: every pixel's ray runs along the view axis,
    /// from the near plane (rayThroughPixel), and the relief's parallax is the same everywhere.
    bool orthographic() const;

    glm::mat4 view() const;
    glm::mat4 projection() const;
    glm::mat4 viewProjection() const { return projection() * view(); }
    /// viewProjection() without the jitter: what previousViewProjection holds of the frame before.
    glm::mat4 unjitteredViewProjection() const;
    /// The ray through a point of the image, in pixels from the bottom-left corner
    /// (x + 0.5, y + 0.5 is a pixel's centre), in double precision for reference tracers: from
    /// the eye, or for an orthographic camera from the point on the near plane.
    Ray rayThroughPixel(double x, double y, int width, int height) const;

    /// How far from the eye the near plane reaches where it cuts the view (its farthest corner):
    /// a closed mesh farther than that from the eye shows no back face through the cut.
    float nearPlaneReach() const;

    /// A camera from an engine's view and projection matrices: the position, target and up from
    /// the view's inverse, mirrored where the view reflects (a planar reflection's), the
    /// projection as customProjection. Throws hfx::Error for a view that is not rigid (a rotation
    /// or a reflection, and a translation: no scale, shear or projection) or not finite, where the
    /// eye it gives would not be the one the view draws.
    static Camera fromMatrices(const glm::mat4& view, const glm::mat4& projection, bool reversedZ = false);

    /// Places the camera at `distance` from `target`, `elevation` radians above the XZ plane
    /// and `azimuth` radians around +Y.
    static Camera orbit(glm::vec3 target, float distance, float azimuth, float elevation);
};

/// The pixels of a width x height image that a convex planar polygon (world space, its corners
/// in order) covers under `viewProjection`: clipped at the image's edges and at -w <= z <= w, the
/// near and far planes of GL's default depth (of a reversed-Z projection, the near plane z = w, and
/// a little past its far one, z = 0), either side facing. 0 where it is behind the camera or off
/// the image.
double screenArea(std::span<const glm::vec3> polygon, const glm::mat4& viewProjection, int width, int height);

} // namespace hfx
