#pragma once
// Internal to hfx::effects: the GL state a surface pass changes, saved and put back; its uniform
// blocks written.
//
// Thread: the thread whose GL context is current.

#include "hfx/core/Gl.h"
#include "hfx/core/GlObject.h"

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

/// Saves what a surface draw or pass changes and puts it back, so the caller's state survives.
class GlStateGuard {
public:
    GlStateGuard() {
        depthTest_ = glIsEnabled(GL_DEPTH_TEST);
        glGetIntegerv(GL_DEPTH_FUNC, &depthFunc_);
        glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
        glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture_);
        for (int unit = 0; unit < kUnits; ++unit) {
            glActiveTexture(GL_TEXTURE0 + unit);
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &textures_[unit]);
        }
        for (GLuint index = 0; index < kBlocks; ++index) {
            glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, index, &blocks_[index]);
            glGetInteger64i_v(GL_UNIFORM_BUFFER_START, index, &blockStart_[index]);
            glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, index, &blockSize_[index]);
        }
    }
    ~GlStateGuard() {
        (depthTest_ ? glEnable : glDisable)(GL_DEPTH_TEST);
        glDepthFunc(static_cast<GLenum>(depthFunc_));
        glUseProgram(static_cast<GLuint>(program_));
        glBindVertexArray(static_cast<GLuint>(vao_));
        for (int unit = 0; unit < kUnits; ++unit) glBindTextureUnit(unit, static_cast<GLuint>(textures_[unit]));
        glActiveTexture(static_cast<GLenum>(activeTexture_));
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
    GLboolean depthTest_;
    // surface, albedo, environment, pyramid, layers 1-3 (a single layer's texel shadows on 4, its beam
    // start on 5),
    // their albedos, shading channels, shadow map, the pyramids of layers 1-3, the clearance map
    static constexpr int kUnits = 16;
    static constexpr GLuint kBlocks = 3; // surface, water, rings
    GLint depthFunc_, program_, vao_, activeTexture_, textures_[kUnits], blocks_[kBlocks];
    GLint64 blockStart_[kBlocks], blockSize_[kBlocks];
};

} // namespace hfx
