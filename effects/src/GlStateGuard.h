#pragma once
// Internal to hfx::effects: the GL state a surface pass changes, saved and put back; its uniform
// blocks written.
//
// Thread: the thread whose GL context is current.

#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"
#include "hfx/core/Gl.h"
#include "hfx/core/GlObject.h"
#include "hfx/effects/GlStatePolicy.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/effects/SurfaceUniforms.h"
#include "ModelMatrix.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <string>

namespace hfx {

/// Writes a uniform block's data into its buffer (made on first use) and binds it at `binding`.
template <typename Block>
void updateBlock(GlBuffer& buffer, GLuint binding, const Block& data) {
    if (!buffer) {
        buffer = GlBuffer::create();
        HFX_GL_CHECK(glNamedBufferStorage(buffer.id(), sizeof(Block), nullptr, GL_DYNAMIC_STORAGE_BIT));
    }
    HFX_GL_CHECK(glNamedBufferSubData(buffer.id(), 0, sizeof(Block), &data));
    glBindBufferBase(GL_UNIFORM_BUFFER, binding, buffer.id());
}

/// Throws hfx::Error unless GL's clip control and depth range are the ones the view's depth
/// convention draws with: GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE for GL's default depth and
/// GL_ZERO_TO_ONE for a reversed-Z camera (Camera::reversedZ), a depth range whose near lies below
/// its far. Any other is the caller's convention that this draw would get wrong: its traced
/// depths would be written for the other, and its depth test would face the wrong way.
inline void checkClipControl(bool reversedZ) {
    if (glStatePolicy() == GlStatePolicy::Defaults) return; // no queries: the caller vouches for it
    GLint origin = GL_LOWER_LEFT, depthMode = GL_NEGATIVE_ONE_TO_ONE;
    glGetIntegerv(GL_CLIP_ORIGIN, &origin);
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &depthMode);
    GLfloat range[2] = {0.0f, 1.0f};
    glGetFloatv(GL_DEPTH_RANGE, range);
    if (origin != GL_LOWER_LEFT)
        throw Error("the clip origin is GL_UPPER_LEFT (glClipControl); HFX draws with GL_LOWER_LEFT, whose window "
                    "y runs up as its texture coordinates and gl_FragCoord do");
    if (reversedZ && depthMode != GL_ZERO_TO_ONE)
        throw Error("the camera is reversed-Z (Camera::reversedZ), but the clip depth mode is GL_NEGATIVE_ONE_TO_ONE: "
                    "set glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE) for it");
    if (!reversedZ && depthMode != GL_NEGATIVE_ONE_TO_ONE)
        throw Error("the clip depth mode is GL_ZERO_TO_ONE (glClipControl), which HFX draws with for a reversed-Z "
                    "camera only: set Camera::reversedZ, or GL_NEGATIVE_ONE_TO_ONE for GL's default depth");
    if (!(range[0] < range[1]))
        throw Error(str("the depth range must have its near below its far (glDepthRange), got ", range[0], " and ",
                        range[1], "; a reversed-Z camera reverses its projection (Camera::reversedZ) instead"));
}

/// A draw buffer of the bound draw framebuffer (the first by default): float, or sRGB with GL
/// encoding what is written (GL_FRAMEBUFFER_SRGB enabled), and its components' type
/// (GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE). None where there is nothing to draw into (GL_NONE,
/// no buffer).
struct ColorTarget {
    bool isFloat = false, encodesSrgb = false;
    GLint componentType = GL_NONE;
};
inline ColorTarget boundColorTarget(GLuint drawBuffer = 0) {
    GLint framebuffer = 0, buffer = GL_NONE;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    glGetIntegerv(GLenum(GL_DRAW_BUFFER0 + drawBuffer), &buffer);
    if (buffer == GL_NONE) return {};
    GLenum attachment = GLenum(buffer);
    if (framebuffer == 0 && buffer == GL_BACK) attachment = GL_BACK_LEFT; // the default framebuffer's names
    if (framebuffer == 0 && buffer == GL_FRONT) attachment = GL_FRONT_LEFT;
    const GLuint id = GLuint(framebuffer);
    GLint object = GL_NONE, type = GL_NONE, encoding = GL_LINEAR;
    glGetNamedFramebufferAttachmentParameteriv(id, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &object);
    if (object == GL_NONE) return {}; // (asking its type would be an error)
    glGetNamedFramebufferAttachmentParameteriv(id, attachment, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
    glGetNamedFramebufferAttachmentParameteriv(id, attachment, GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING, &encoding);
    return {.isFloat = type == GL_FLOAT,
            .encodesSrgb = encoding == GL_SRGB && glIsEnabled(GL_FRAMEBUFFER_SRGB),
            .componentType = type};
}

/// What an output needs its draw buffer's target to hold.
enum class TargetHolds {
    Negatives, ///< values below 0 (a motion, a normal): a float or signed normalized target
    OverOne,   ///< values above 1 (emitted light): a float target
};

/// Throws hfx::Error where draw buffer `drawBuffer` of the bound framebuffer, which `what` (the
/// motion, the normal, the emission) goes to, cannot hold what it `needs`: a normalized target
/// clamps (an unsigned one below 0, either above 1), an integer one takes no float. With nothing
/// there (GL_NONE) nothing is written; 0: no output. Not checked under GlStatePolicy::Defaults.
inline void checkOutputTarget(int drawBuffer, const char* what, TargetHolds needs) {
    if (drawBuffer <= 0 || glStatePolicy() == GlStatePolicy::Defaults) return;
    const GLint type = boundColorTarget(GLuint(drawBuffer)).componentType;
    const bool overOne = needs == TargetHolds::OverOne;
    if (type == GL_NONE || type == GL_FLOAT || (!overOne && type == GL_SIGNED_NORMALIZED)) return;
    const bool normalized = type == GL_UNSIGNED_NORMALIZED || type == GL_SIGNED_NORMALIZED;
    throw Error(str(what, " goes to draw buffer ", drawBuffer, " of the bound framebuffer, whose target is ",
                    !normalized ? "an integer one: it takes no float values"
                    : overOne   ? "normalized: its values over 1 would clamp"
                                : "unsigned normalized: its negative values would clamp to 0",
                    overOne ? "; attach a float one there (RGBA16F, R11F_G11F_B10F)"
                            : "; attach a float (RG16F, RGBA16F) or signed normalized one there"));
}

/// GL 4.5 promises at least 8 draw buffers; the masks of the first 8 are saved and set (without
/// asking the context its count).
inline constexpr GLuint kDrawBuffers = 8;

/// Throws hfx::Error naming `what` (a setter's output) unless `drawBuffer` is one a draw can write
/// besides the colour's: 1 to 7, or 0 for none.
inline void checkDrawBuffer(const char* what, int drawBuffer) {
    if (drawBuffer < 0 || drawBuffer >= int(kDrawBuffers))
        throw Error(str(what, ": the draw buffer must be 1 to ", kDrawBuffers - 1,
                        " (colour buffer 0 is the colour's), or 0 for none, got ", drawBuffer));
}

/// The motion's uniforms: this frame's world to the previous frame's clip space (the camera's
/// previous view-projection, or its own without jitter; the mesh carried from `model` back to
/// `previousModel`), and the jitter to leave out.
inline void setMotion(SurfaceUniforms& u, const Camera& camera, const glm::mat4& model,
                      const std::optional<glm::mat4>& previousModel) {
    const glm::mat4 previous = camera.previousViewProjection ? *camera.previousViewProjection : camera.unjitteredViewProjection();
    u.previousFromWorld = previousModel ? previous * *previousModel * glm::inverse(model) : previous;
    u.jitter = camera.jitter;
}

/// Whether a draw into the bound draw framebuffer writes linear colours (ColorOutput): as asked,
/// or for Auto, where its colour buffer is a float one or an sRGB one that GL encodes.
inline bool writesLinear(ColorOutput output) {
    if (output != ColorOutput::Auto) return output == ColorOutput::Linear;
    const ColorTarget target = boundColorTarget();
    return target.isFloat || target.encodesSrgb;
}

/// Fills a surface block's transforms: the mesh's model matrix, the view-projection it is seen
/// with, and the normals' matrix.
inline void setTransform(SurfaceUniforms& u, const glm::mat4& model, const glm::mat4& viewProj) {
    u.model = model;
    u.viewProj = viewProj;
    u.normalMatrix = glm::mat4(glm::transpose(glm::inverse(glm::mat3(model))));
}

/// A camera's eye in a surface block: its position, and for an orthographic camera the one
/// direction towards it (hfx_to_eye).
inline void setEye(SurfaceUniforms& u, const Camera& camera) {
    u.cameraPos = camera.position;
    u.orthographic = camera.orthographic() ? 1 : 0;
    u.towardsEye = u.orthographic ? -glm::vec3(camera.rayThroughPixel(1.0, 1.0, 2, 2).direction) : glm::vec3(0.0f);
}

/// Saves what a surface draw or pass changes and puts it back, so the caller's state survives.
/// Under GlStatePolicy::Defaults it saves nothing and puts back GL's defaults (what the members
/// start as), except inside another guard (a pass a draw runs, the texel shadows), where what it
/// puts back is what that draw had bound.
class GlStateGuard {
public:
    GlStateGuard() {
        const bool nested = depth()++ > 0;
        if (glStatePolicy() == GlStatePolicy::Defaults && !nested) return;
        depthTest_ = glIsEnabled(GL_DEPTH_TEST);
        cullFace_ = glIsEnabled(GL_CULL_FACE);
        glGetIntegerv(GL_CULL_FACE_MODE, &cullMode_);
        glGetIntegerv(GL_FRONT_FACE, &frontFace_);
        glGetIntegerv(GL_DEPTH_FUNC, &depthFunc_);
        glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask_);
        programPointSize_ = glIsEnabled(GL_PROGRAM_POINT_SIZE);
        glGetIntegerv(GL_DRAW_INDIRECT_BUFFER_BINDING, &indirect_);
        glGetIntegerv(GL_DISPATCH_INDIRECT_BUFFER_BINDING, &dispatch_);
        for (GLuint index = 0; index < kStorage; ++index) {
            glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, index, &storage_[index]);
            glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, index, &storageStart_[index]);
            glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, index, &storageSize_[index]);
        }
        glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
        glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture_);
        for (int unit = 0; unit < kUnits; ++unit) {
            glActiveTexture(GL_TEXTURE0 + unit);
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &textures_[unit]);
        }
        // The shadow maps' unit may get an array texture and a sampler (an engine's cascades).
        glActiveTexture(GL_TEXTURE0 + HFX_UNIT_SHADOW_MAP);
        glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &shadowArray_);
        glGetIntegerv(GL_SAMPLER_BINDING, &shadowSampler_);
        for (GLuint unit = 0; unit < kImages; ++unit) {
            Image& i = images_[unit];
            glGetIntegeri_v(GL_IMAGE_BINDING_NAME, unit, &i.name);
            glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, unit, &i.level);
            glGetIntegeri_v(GL_IMAGE_BINDING_LAYERED, unit, &i.layered);
            glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, unit, &i.layer);
            glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, unit, &i.access);
            glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, unit, &i.format);
        }
        for (GLuint index = 0; index < kBlocks; ++index) {
            glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, index, &blocks_[index]);
            glGetInteger64i_v(GL_UNIFORM_BUFFER_START, index, &blockStart_[index]);
            glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, index, &blockSize_[index]);
        }
    }
    ~GlStateGuard() {
        --depth();
        (depthTest_ ? glEnable : glDisable)(GL_DEPTH_TEST);
        (cullFace_ ? glEnable : glDisable)(GL_CULL_FACE);
        glCullFace(GLenum(cullMode_));
        glFrontFace(GLenum(frontFace_));
        glDepthFunc(static_cast<GLenum>(depthFunc_));
        glDepthMask(depthMask_);
        (programPointSize_ ? glEnable : glDisable)(GL_PROGRAM_POINT_SIZE);
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, GLuint(indirect_));
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, GLuint(dispatch_));
        for (GLuint index = 0; index < kStorage; ++index) {
            if (storage_[index] != 0 && storageSize_[index] > 0)
                glBindBufferRange(GL_SHADER_STORAGE_BUFFER, index, GLuint(storage_[index]), storageStart_[index],
                                  storageSize_[index]);
            else
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, index, GLuint(storage_[index]));
        }
        // A program the caller deleted while it was current lives only while it stays current:
        // once the guarded pass has used another, its name is gone, and the caller has none.
        glUseProgram(program_ != 0 && glIsProgram(GLuint(program_)) ? GLuint(program_) : 0);
        glBindVertexArray(static_cast<GLuint>(vao_));
        for (int unit = 0; unit < kUnits; ++unit) glBindTextureUnit(unit, static_cast<GLuint>(textures_[unit]));
        // (After the unit's 2D binding: binding 0 there unbinds every target of the unit.)
        if (shadowArray_ != 0) glBindTextureUnit(HFX_UNIT_SHADOW_MAP, GLuint(shadowArray_));
        glBindSampler(HFX_UNIT_SHADOW_MAP, GLuint(shadowSampler_));
        glActiveTexture(static_cast<GLenum>(activeTexture_));
        for (GLuint unit = 0; unit < kImages; ++unit) {
            const Image& i = images_[unit];
            glBindImageTexture(unit, GLuint(i.name), i.level, GLboolean(i.layered), i.layer, GLenum(i.access),
                               GLenum(i.format));
        }
        for (GLuint index = 0; index < kBlocks; ++index) {
            if (blocks_[index] != 0 && blockSize_[index] > 0)
                glBindBufferRange(GL_UNIFORM_BUFFER, index, GLuint(blocks_[index]), blockStart_[index], blockSize_[index]);
            else
                glBindBufferBase(GL_UNIFORM_BUFFER, index, GLuint(blocks_[index]));
        }
    }
    GlStateGuard(const GlStateGuard&) = delete;
    GlStateGuard& operator=(const GlStateGuard&) = delete;

private:
    /// How many guards this thread is inside.
    static int& depth() {
        thread_local int guards = 0;
        return guards;
    }
    GLboolean depthTest_ = GL_FALSE, depthMask_ = GL_TRUE, programPointSize_ = GL_FALSE, cullFace_ = GL_FALSE;
    GLint cullMode_ = GL_BACK, frontFace_ = GL_CCW; // a closed mesh's back faces culled, a mirrored model's winding
    GLint indirect_ = 0, dispatch_ = 0; // the deferred walks' indirect buffers (ExactTracer)
    // the storage buffers of hfx/core/Bindings.h: the deferred walks', the computed walks' three
    static constexpr GLuint kStorage = HFX_BUFFER_TRACE_LIGHTS + 1;
    static_assert(HFX_BUFFER_DEFERRED_SHADOWS < kStorage && HFX_BUFFER_TRACE_RAYS < kStorage &&
                      HFX_BUFFER_TRACE_INFO < kStorage,
                  "hfx/core/Bindings.h: the guard saves every storage binding");
    GLint storage_[kStorage] = {};
    GLint64 storageStart_[kStorage] = {}, storageSize_[kStorage] = {};
    // every unit of hfx/core/Bindings.h
    static constexpr int kUnits = HFX_TEXTURE_UNITS;
    // every image unit of hfx/core/Bindings.h: the atlas pyramids of layers 0-3 (HeightBounds::bind),
    // layer 0's cells, the passes' output (the bounds level, texel shadows, beam start), the bounds
    // pass's finer level, the rings' light's pass. GL 4.5 promises no more than HFX_IMAGE_UNITS (NVIDIA
    // has no more), and querying a unit past a context's last is GL_INVALID_VALUE.
    static constexpr GLuint kImages = HFX_IMAGE_UNITS;
    static_assert(HFX_IMAGE_UNITS <= 8, "hfx/core/Bindings.h: GL 4.5 promises 8 image units");
    static_assert(HFX_IMAGE_PYRAMID + 3 < kImages && HFX_IMAGE_CELLS < kImages && HFX_IMAGE_PASS_OUTPUT < kImages &&
                      HFX_IMAGE_BOUNDS_FINER < kImages && HFX_IMAGE_BOUNDS < kImages && HFX_IMAGE_RING_SHINE < kImages,
                  "hfx/core/Bindings.h: every image unit is one of GL 4.5's 8, and the guard saves it");
    struct Image {
        GLint name = 0, level = 0, layered = GL_FALSE, layer = 0, access = GL_READ_ONLY, format = GL_R8;
    };
    Image images_[kImages];
    static constexpr GLuint kBlocks = HFX_BLOCK_SHADOWS + 1; // surface, water, water rings, planet, shadows
    GLint depthFunc_ = GL_LESS, program_ = 0, vao_ = 0, activeTexture_ = GL_TEXTURE0, textures_[kUnits] = {},
          blocks_[kBlocks] = {};
    GLint shadowArray_ = 0, shadowSampler_ = 0;
    GLint64 blockStart_[kBlocks] = {}, blockSize_[kBlocks] = {};
};

/// For its scope a draw into the caller's framebuffer writes only the draw buffers it has
/// outputs for (`written`: a bit per buffer; 0, none: a shadow caster's): GL leaves a buffer with no
/// fragment output undefined, and llvmpipe writes output 0's colour there, over an engine's
/// other targets (its normals, its motion: EngineOutputsTest). The caller's own masks are kept
/// on the buffers written, and put back on the others when it ends (GL's default, every channel
/// written, under GlStatePolicy::Defaults, except inside another of these: the deferred walks'
/// points inside the draw).
class DrawBuffersWritten {
public:
    explicit DrawBuffersWritten(unsigned written)
        : first_(written & 1u), written_(written), counted_(glStatePolicy() == GlStatePolicy::Defaults) {
        queried_ = !counted_ || depth()++ > 0;
        for (GLuint i = first_; i < kDrawBuffers; ++i) {
            std::fill_n(masks_[i], 4, GLboolean(GL_TRUE));
            if (queried_) glGetBooleani_v(GL_COLOR_WRITEMASK, i, masks_[i]);
            if (!(written >> i & 1u)) glColorMaski(i, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        }
    }
    ~DrawBuffersWritten() {
        if (counted_) --depth();
        for (GLuint i = first_; i < kDrawBuffers; ++i) glColorMaski(i, masks_[i][0], masks_[i][1], masks_[i][2], masks_[i][3]);
    }
    DrawBuffersWritten(const DrawBuffersWritten&) = delete;
    DrawBuffersWritten& operator=(const DrawBuffersWritten&) = delete;

    /// Whether the caller's state is GL's defaults, not asked for (GlStatePolicy::Defaults, outside
    /// another of these): every mask on, the depth's among them.
    bool atDefaults() const { return !queried_; }
    /// The colour masks in effect inside this scope: the caller's on the buffers written, none on
    /// the others. Buffer 0, which a scope that writes it leaves alone, is asked for unless
    /// atDefaults().
    void inEffect(GLboolean (&masks)[kDrawBuffers][4]) const {
        for (GLuint i = 0; i < kDrawBuffers; ++i) {
            if (i < first_) {
                std::fill_n(masks[i], 4, GLboolean(GL_TRUE));
                if (queried_) glGetBooleani_v(GL_COLOR_WRITEMASK, i, masks[i]);
            } else {
                for (int c = 0; c < 4; ++c) masks[i][c] = (written_ >> i & 1u) ? masks_[i][c] : GLboolean(GL_FALSE);
            }
        }
    }

private:
    /// How many of these this thread is inside, counted under GlStatePolicy::Defaults.
    static int& depth() {
        thread_local int scopes = 0;
        return scopes;
    }
    GLuint first_;     ///< buffer 0 is masked only where the draw writes no colour at all
    unsigned written_; ///< the buffers written, a bit each
    bool counted_;     ///< made under GlStatePolicy::Defaults, and counted in depth()
    bool queried_ = true; ///< the caller's masks were asked for (not known to be GL's defaults)
    GLboolean masks_[kDrawBuffers][4] = {}; ///< what to put back
};

/// For its scope a draw writes no colour to any draw buffer and no depth (ExactTracer's rays draw,
/// whose fragments only store their rays), inside the draw's DrawBuffersWritten; puts back the
/// masks that scope has in effect when it ends (the draw that follows writes with them): the
/// scope knows them, so only buffer 0's and the depth's are asked for, and under
/// GlStatePolicy::Defaults none.
class NoFramebufferWrites {
public:
    explicit NoFramebufferWrites(const DrawBuffersWritten& scope) {
        scope.inEffect(masks_);
        if (!scope.atDefaults()) glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDepthMask(GL_FALSE);
    }
    ~NoFramebufferWrites() {
        for (GLuint i = 0; i < kDrawBuffers; ++i) glColorMaski(i, masks_[i][0], masks_[i][1], masks_[i][2], masks_[i][3]);
        glDepthMask(depth_);
    }
    NoFramebufferWrites(const NoFramebufferWrites&) = delete;
    NoFramebufferWrites& operator=(const NoFramebufferWrites&) = delete;

private:
    // (glColorMask sets every buffer's mask: the first kDrawBuffers are put back.)
    GLboolean masks_[kDrawBuffers][4] = {}, depth_ = GL_TRUE;
};

} // namespace hfx
