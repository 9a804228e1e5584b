#pragma once
// An off-screen framebuffer: RGBA8 colour (fragment output 0), a 32-bit float depth texture, and
// optionally an RGBA32F "trace" attachment (output 1) where debug shader variants write values
// such as the final texcoords of a ray, and an RG32F "entry" attachment (output 2) where they
// write the texcoords the fragment's ray entered at (the rasteriser's interpolation, which is not
// the pixel centre's), for tests and accuracy benchmarks.
//
// Owns its framebuffer and attachments. Thread: the thread whose GL context is current.

#include "hfx/core/GlObject.h"
#include "hfx/core/Image.h"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <vector>

namespace hfx {

class RenderTarget {
public:
    RenderTarget(int width, int height, bool withTrace = false);

    void bind() const; ///< binds the framebuffer and sets the viewport to its size
    /// Clears the colour, the trace outputs and the depth: to 1, the far plane of GL's default
    /// depth; a reversed-Z view (Camera::reversedZ) clears it to 0.
    void clear(const glm::vec4& color = {0, 0, 0, 1}, const glm::vec4& trace = {0, 0, 0, 0}, float depth = 1.0f) const;

    int width() const { return width_; }
    int height() const { return height_; }
    GLuint framebuffer() const { return fbo_.id(); }

    Image readColor() const;               ///< RGB, top row first, ready for writeImage
    std::vector<glm::vec4> readTrace() const; ///< bottom row first (GL order)
    std::vector<glm::vec2> readEntry() const; ///< bottom row first (GL order)
    std::vector<float> readDepth() const;  ///< window-space depth, bottom row first

private:
    int width_, height_;
    bool withTrace_;
    GlFramebuffer fbo_;
    GlTexture color_, trace_, entry_, depth_;
};

} // namespace hfx
