#include "hfx/core/SurfaceTextures.h"

#include "hfx/core/Error.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <vector>

namespace hfx {

void SurfaceTexturesConfig::validate() const {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw Error(str("surface size must be in 1..16384, got ", width, "x", height));
    if (!(normalDepth > 0.0f) || !std::isfinite(normalDepth))
        throw Error(str("SurfaceTexturesConfig.normalDepth must be positive and finite, got ", normalDepth));
    if (format == SurfaceFormat::Auto)
        throw Error("SurfaceTexturesConfig.format is auto: textures store a chosen format (float32, float16, unorm8; "
                    "SurfacePipeline chooses the device's with chooseSurfaceFormat)");
}

namespace {
GLenum internalFormat(SurfaceFormat f) {
    return f == SurfaceFormat::Float32 ? GL_RGBA32F : f == SurfaceFormat::Float16 ? GL_RGBA16F : GL_RGBA8;
}
GLenum texelType(SurfaceFormat f) {
    return f == SurfaceFormat::Float32 ? GL_FLOAT : f == SurfaceFormat::Float16 ? GL_HALF_FLOAT : GL_UNSIGNED_BYTE;
}

/// A flat surface at the polygon (normal +z, h = 1), in the format's layout, width*height texels.
std::vector<unsigned char> flatTexels(SurfaceFormat format, size_t count) {
    std::vector<unsigned char> one(texelBytes(format));
    if (format == SurfaceFormat::Float32) {
        const float t[4] = {0.0f, 0.0f, 1.0f, 1.0f};
        std::memcpy(one.data(), t, sizeof t);
    } else if (format == SurfaceFormat::Float16) {
        const std::uint16_t t[4] = {0, 0, 0x3c00, 0x3c00}; // IEEE half 0 and 1
        std::memcpy(one.data(), t, sizeof t);
    } else {
        one = {128, 128, 255, 255}; // n/2 + 1/2 of (0, 0, 1), rounded to nearest, and h = 1
    }
    std::vector<unsigned char> texels(one.size() * count);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = one[i % one.size()];
    return texels;
}
} // namespace

SurfaceTextures::SurfaceTextures(const SurfaceTexturesConfig& config)
    : config_(config), surface_(GlTexture::create()), albedo_(GlTexture::create()),
      channels_(GlTexture::create()) {
    config_.validate();
    levels_ = config.mipmaps
                  ? static_cast<int>(std::bit_width(static_cast<unsigned>(
                        std::max(config.width, config.height))))
                  : 1;
    const GLenum wrapS = wrapsU(config.edges) ? GL_REPEAT : GL_CLAMP_TO_EDGE;
    const GLenum wrapT = wrapsV(config.edges) ? GL_REPEAT : GL_CLAMP_TO_EDGE;
    for (const GlTexture* t : {&surface_, &albedo_, &channels_}) {
        glTextureParameteri(t->id(), GL_TEXTURE_WRAP_S, wrapS);
        glTextureParameteri(t->id(), GL_TEXTURE_WRAP_T, wrapT);
        glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER,
                            levels_ > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    }
    HFX_GL_CHECK(glTextureStorage2D(surface_.id(), levels_, internalFormat(config.format), config.width, config.height));
    HFX_GL_CHECK(glTextureStorage2D(albedo_.id(), levels_, GL_RGBA8, config.width, config.height));
    setAlbedo(Image{1, 1, 3, {0.8f, 0.8f, 0.8f}});
    HFX_GL_CHECK(glTextureStorage2D(channels_.id(), levels_, GL_RGBA8, config.width, config.height));
    const GLubyte open[4] = {0, 255, 0, 0}; // no added roughness, no occlusion, no heat
    for (int level = 0; level < levels_; ++level)
        HFX_GL_CHECK(glClearTexImage(channels_.id(), level, GL_RGBA, GL_UNSIGNED_BYTE, open));
    uploadTexels(flatTexels(config.format, static_cast<size_t>(config.width) * config.height).data());
}

void SurfaceTextures::uploadTexels(const void* texels) {
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    HFX_GL_CHECK(glTextureSubImage2D(surface_.id(), 0, 0, 0, config_.width, config_.height, GL_RGBA,
                        texelType(config_.format), texels));
    if (levels_ > 1) HFX_GL_CHECK(glGenerateTextureMipmap(surface_.id()));
    ++texelsVersion_; // whatever was derived from the texels is stale
}

void SurfaceTextures::uploadAlbedo(const unsigned char* rgba) {
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    HFX_GL_CHECK(glTextureSubImage2D(albedo_.id(), 0, 0, 0, config_.width, config_.height, GL_RGBA,
                        GL_UNSIGNED_BYTE, rgba));
    if (levels_ > 1) HFX_GL_CHECK(glGenerateTextureMipmap(albedo_.id()));
}

void SurfaceTextures::uploadChannels(const unsigned char* rgba) {
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    HFX_GL_CHECK(glTextureSubImage2D(channels_.id(), 0, 0, 0, config_.width, config_.height, GL_RGBA,
                        GL_UNSIGNED_BYTE, rgba));
    if (levels_ > 1) HFX_GL_CHECK(glGenerateTextureMipmap(channels_.id()));
}

void SurfaceTextures::setAlbedo(const Image& albedo) {
    const bool solid = albedo.width == 1 && albedo.height == 1;
    if (!solid && (albedo.width != config_.width || albedo.height != config_.height))
        throw Error(str("albedo is ", albedo.width, "x", albedo.height, " but the surface is ",
                        config_.width, "x", config_.height));
    if (albedo.channels < 1 || albedo.channels > 4 || albedo.empty())
        throw Error(str("albedo needs 1 to 4 channels, got ", albedo.channels));
    std::vector<unsigned char> rgba(static_cast<size_t>(config_.width) * config_.height * 4);
    for (int y = 0; y < config_.height; ++y)
        for (int x = 0; x < config_.width; ++x) {
            // Files store the top row first; texture row 0 is v = 0, the bottom.
            const int sx = solid ? 0 : x, sy = solid ? 0 : albedo.height - 1 - y;
            for (int c = 0; c < 4; ++c) {
                float v = c < 3 ? albedo.at(sx, sy, std::min(c, albedo.channels - 1))
                                : (albedo.channels == 4 ? albedo.at(sx, sy, 3) : 1.0f);
                if (albedo.channels == 2 && c < 3) v = albedo.at(sx, sy, 0);
                rgba[(static_cast<size_t>(y) * config_.width + x) * 4 + c] =
                    static_cast<unsigned char>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
            }
        }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    HFX_GL_CHECK(glTextureSubImage2D(albedo_.id(), 0, 0, 0, config_.width, config_.height, GL_RGBA,
                        GL_UNSIGNED_BYTE, rgba.data()));
    if (levels_ > 1) HFX_GL_CHECK(glGenerateTextureMipmap(albedo_.id()));
}

} // namespace hfx
