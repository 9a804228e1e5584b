#include "hfx/effects/ShadowMap.h"

#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace hfx {

ShadowMap::ShadowMap(int size) : size_(size) {
    if (size < 16 || size > 16384) throw Error(str("ShadowMap size must be in 16..16384, got ", size));
    fbo_ = GlFramebuffer::create();
    depth_ = GlTexture::create();
    glTextureStorage2D(depth_.id(), 1, GL_DEPTH_COMPONENT32F, size, size);
    // Hardware comparison with bilinear weights: each lookup is a 2x2 percentage-closer filter.
    glTextureParameteri(depth_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(depth_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(depth_.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(depth_.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    // Outside the map nothing casts: the border is the far plane.
    glTextureParameteri(depth_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTextureParameteri(depth_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    const float far[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glTextureParameterfv(depth_.id(), GL_TEXTURE_BORDER_COLOR, far);
    glNamedFramebufferTexture(fbo_.id(), GL_DEPTH_ATTACHMENT, depth_.id(), 0);
    glNamedFramebufferDrawBuffer(fbo_.id(), GL_NONE);
    glNamedFramebufferReadBuffer(fbo_.id(), GL_NONE);
    const GLenum status = glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(str("shadow map ", size, "x", size, " is incomplete (status 0x", std::hex, status, ")"));
}

void ShadowMap::fit(glm::vec3 towardsLight, glm::vec3 centre, float radius) {
    const float length = glm::length(towardsLight);
    if (!(length > 0.0f) || !std::isfinite(length))
        throw Error(str("ShadowMap::fit: the direction towards the light must be finite and non-zero, got ",
                        text(towardsLight)));
    if (!isFinite(centre)) throw Error(str("ShadowMap::fit: the centre must be finite, got ", text(centre)));
    if (!(radius > 0.0f) || !std::isfinite(radius))
        throw Error(str("ShadowMap::fit: radius must be positive, got ", radius));
    towardsLight_ = towardsLight / length;
    radius_ = radius;
    // The eye two radii out along the light; depth spans the sphere with a radius to spare
    // behind it (depthPerWorld: window depth 0..1 over 4 radii).
    const glm::vec3 up = std::abs(towardsLight_.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    const glm::mat4 view = glm::lookAt(centre + towardsLight_ * (2.0f * radius), centre, up);
    const glm::mat4 projection = glm::ortho(-radius, radius, -radius, radius, 0.0f, 4.0f * radius);
    viewProj_ = projection * view;
    lightView_ = Camera::fromMatrices(view, projection);
    cascade_.viewProj = viewProj_;
    fitted_ = true;
}

void ShadowMap::begin() {
    if (begun_) throw Error("ShadowMap::begin: the map is already begun (end() puts back the caller's state first)");
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &savedDraw_);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &savedRead_);
    glGetIntegerv(GL_VIEWPORT, savedViewport_);
    savedScissor_ = glIsEnabled(GL_SCISSOR_TEST);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &savedDepthMask_);
    glGetIntegerv(GL_CLIP_ORIGIN, &savedClipOrigin_);
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &savedClipDepth_);
    glGetDoublev(GL_DEPTH_RANGE, savedDepthRange_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, size_, size_);
    // The clear and the casters write the whole map, whatever scissor or depth mask the caller left.
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    // The map's depth is GL's default, [-1, 1] clip depth onto [0, 1] (the light's projection and
    // the receivers' lookups), under a caller's reversed-Z state too.
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDepthRange(0.0, 1.0);
    const float one = 1.0f;
    glClearNamedFramebufferfv(fbo_.id(), GL_DEPTH, 0, &one);
    begun_ = true;
}

void ShadowMap::end() {
    if (!begun_) throw Error("ShadowMap::end: the map was not begun");
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(savedDraw_));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(savedRead_));
    glViewport(savedViewport_[0], savedViewport_[1], savedViewport_[2], savedViewport_[3]);
    (savedScissor_ ? glEnable : glDisable)(GL_SCISSOR_TEST);
    glDepthMask(savedDepthMask_);
    glClipControl(GLenum(savedClipOrigin_), GLenum(savedClipDepth_));
    glDepthRange(savedDepthRange_[0], savedDepthRange_[1]);
    begun_ = false;
}

} // namespace hfx
