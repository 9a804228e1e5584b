#include "hfx/effects/RingShine.h"

#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/GpuTimer.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <algorithm>
#include <cmath>

namespace hfx {

GLuint RingShine::texture(GLuint profile, float inner, float outer, float sinElevation) {
    const Key key{.profile = profile, .inner = inner, .outer = outer, .sinElevation = std::clamp(sinElevation, -1.0f, 1.0f)};
    const auto kept = std::ranges::find_if(tables_, [&](const Table& t) { return t.used != 0 && t.key == key; });
    if (kept != tables_.end()) {
        kept->used = ++clock_;
        return kept->texture.id();
    }
    Table& table = *std::ranges::min_element(tables_, {}, &Table::used); // a free one's is 0
    if (!table.texture) {
        table.texture = GlTexture::create();
        const GLuint t = table.texture.id();
        HFX_GL_CHECK(glTextureStorage2D(t, 1, GL_RGBA16F, kLongitudes, kLatitudes));
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    table.used = 0; // until it holds the new key's light
    if (!program_) program_ = ShaderProgram::compute(surfaceStage("shade/ringshine.comp"));
    GLint texels = 1;
    glGetTextureLevelParameteriv(profile, 0, GL_TEXTURE_WIDTH, &texels);
    const GpuScope scope("ring shine");
    const ShaderProgram& p = *program_;
    p.use();
    p.set("u_size", glm::ivec2(kLongitudes, kLatitudes));
    p.set("u_inner", key.inner);
    p.set("u_outer", key.outer);
    p.set("u_sun", glm::vec2(std::sqrt(1.0f - key.sinElevation * key.sinElevation), key.sinElevation));
    p.set("u_profileLevel", std::max(std::log2(float(texels) / float(kRadial)), 0.0f));
    p.set("u_radial", kRadial);
    p.set("u_around", kAround);
    glBindTextureUnit(HFX_UNIT_RING_PROFILE, profile);
    HFX_GL_CHECK(glBindImageTexture(HFX_IMAGE_RING_SHINE, table.texture.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F));
    p.dispatchOver(kLongitudes, kLatitudes);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT); // the planet's draw samples it
    glUseProgram(0);
    table.key = key;
    table.used = ++clock_;
    return table.texture.id();
}

} // namespace hfx
