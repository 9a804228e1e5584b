#include "hfx/core/RenderTarget.h"

#include "hfx/core/Error.h"

namespace hfx {

RenderTarget::RenderTarget(int width, int height, bool withTrace)
    : width_(width), height_(height), withTrace_(withTrace), fbo_(GlFramebuffer::create()) {
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        throw Error(str("render target size must be in 1..16384, got ", width, "x", height));
    auto texture = [&](GLenum format) {
        GlTexture t = GlTexture::create();
        glTextureStorage2D(t.id(), 1, format, width, height);
        glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        return t;
    };
    color_ = texture(GL_RGBA8);
    depth_ = texture(GL_DEPTH_COMPONENT32F);
    glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, color_.id(), 0);
    glNamedFramebufferTexture(fbo_.id(), GL_DEPTH_ATTACHMENT, depth_.id(), 0);
    if (withTrace) {
        trace_ = texture(GL_RGBA32F);
        entry_ = texture(GL_RG32F);
        glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT1, trace_.id(), 0);
        glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT2, entry_.id(), 0);
        const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
        glNamedFramebufferDrawBuffers(fbo_.id(), 3, buffers);
    }
    const GLenum status = glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(str("render target ", width, "x", height, " is incomplete (status 0x",
                        std::hex, status, ")"));
}

void RenderTarget::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, width_, height_);
}

void RenderTarget::clear(const glm::vec4& color, const glm::vec4& trace, float depth) const {
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, &color.x);
    if (withTrace_) {
        glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 1, &trace.x);
        const float zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 2, zero);
    }
    glClearNamedFramebufferfv(fbo_.id(), GL_DEPTH, 0, &depth);
}

Image RenderTarget::readColor() const {
    std::vector<unsigned char> rgba(static_cast<size_t>(width_) * height_ * 4);
    glGetTextureImage(color_.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(rgba.size()),
                      rgba.data());
    Image image{width_, height_, 3, {}};
    image.pixels.resize(static_cast<size_t>(width_) * height_ * 3);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x)
            for (int c = 0; c < 3; ++c)
                image.at(x, height_ - 1 - y, c) =
                    rgba[(static_cast<size_t>(y) * width_ + x) * 4 + c] / 255.0f;
    return image;
}

std::vector<glm::vec4> RenderTarget::readTrace() const {
    if (!withTrace_) throw Error("render target was created without a trace attachment");
    std::vector<glm::vec4> out(static_cast<size_t>(width_) * height_);
    glGetTextureImage(trace_.id(), 0, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(out.size() * sizeof(glm::vec4)), out.data());
    return out;
}

std::vector<glm::vec2> RenderTarget::readEntry() const {
    if (!withTrace_) throw Error("render target was created without a trace attachment");
    std::vector<glm::vec2> out(static_cast<size_t>(width_) * height_);
    glGetTextureImage(entry_.id(), 0, GL_RG, GL_FLOAT, static_cast<GLsizei>(out.size() * sizeof(glm::vec2)), out.data());
    return out;
}

std::vector<float> RenderTarget::readDepth() const {
    std::vector<float> out(static_cast<size_t>(width_) * height_);
    glGetTextureImage(depth_.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      static_cast<GLsizei>(out.size() * sizeof(float)), out.data());
    return out;
}

} // namespace hfx
