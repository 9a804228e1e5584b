#include "hfx/effects/tracer/HeightBounds.h"

#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/GlRenderer.h"

#include <algorithm>
#include <bit>

namespace hfx {

bool carriesBounds(const SurfaceTexturesConfig& config) {
    return std::has_single_bit(unsigned(config.width)) && std::has_single_bit(unsigned(config.height)) &&
           config.format != SurfaceFormat::Unorm8;
}

std::string boundsRefusal(const SurfaceTexturesConfig& config) {
    if (carriesBounds(config)) return {};
    if (!std::has_single_bit(unsigned(config.width)) || !std::has_single_bit(unsigned(config.height)))
        return str("height bounds need power-of-two sizes, got ", config.width, "x", config.height);
    if (config.format == SurfaceFormat::Unorm8)
        return "height bounds need a float format (float32 or float16): unorm8 heights round up to 1/510 above "
               "the bounds and the hierarchical tracer would miss";
    return {};
}

PyramidLayout resolvedLayout(PyramidLayout layout, const GlWorkarounds& device) {
    if (layout != PyramidLayout::Auto) return layout;
    return device.pyramidAtlas ? PyramidLayout::Atlas : PyramidLayout::MipChain;
}

PyramidLayout resolvedLayout(PyramidLayout layout) {
    return layout != PyramidLayout::Auto ? layout : resolvedLayout(layout, glWorkarounds(currentGlRenderer()));
}

HeightBounds::HeightBounds(int width, int height, EdgeMode edges, PyramidLayout layout)
    : width_(width), height_(height), edges_(edges) {
    if (width < 1 || height < 1 || !std::has_single_bit(unsigned(width)) || !std::has_single_bit(unsigned(height)))
        throw Error(str("height bounds need power-of-two sizes, got ", width, "x", height));
    levels_ = int(std::bit_width(unsigned(std::max(width, height))));
    layout_ = resolvedLayout(layout);
}

namespace {
const SurfaceTexturesConfig& boundable(const SurfaceTexturesConfig& config) {
    if (const std::string why = boundsRefusal(config); !why.empty()) throw Error(why);
    return config;
}
} // namespace

HeightBounds::HeightBounds(const SurfaceTexturesConfig& config, PyramidLayout layout)
    : HeightBounds(boundable(config).width, config.height, config.edges, layout) {}

bool HeightBounds::fits(const SurfaceTexturesConfig& config) const {
    return config.width == width_ && config.height == height_ && config.edges == edges_;
}

size_t HeightBounds::bytes() const {
    size_t texels = 0;
    if (pyramid_ && layout_ == PyramidLayout::Atlas) {
        const auto [w, h] = atlasSize(width_, height_);
        texels = size_t(w) * size_t(h);
    } else if (pyramid_) {
        for (int level = 0; level < levels_; ++level)
            texels += size_t(std::max(width_ >> level, 1)) * size_t(std::max(height_ >> level, 1));
    }
    return texels * 8 + (cells_ ? size_t(width_) * size_t(height_) * 16 : 0); // RG32F, RGBA32F
}

GLuint HeightBounds::pyramid() const {
    if (pyramid_) return pyramid_.id();
    GlTexture t = GlTexture::create();
    if (layout_ == PyramidLayout::Atlas) {
        const auto [w, h] = atlasSize(width_, height_);
        HFX_GL_CHECK(glTextureStorage2D(t.id(), 1, GL_RG32F, w, h));
    } else {
        HFX_GL_CHECK(glTextureStorage2D(t.id(), levels_, GL_RG32F, width_, height_));
        glTextureParameteri(t.id(), GL_TEXTURE_MAX_LEVEL, levels_ - 1);
    }
    // A mipmapped filter for the mip chain: a texelFetch past the base level is defined only on a
    // texture complete as a mip chain.
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER,
                        layout_ == PyramidLayout::MipChain ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    pyramid_ = std::move(t);
    return pyramid_.id();
}

GLuint HeightBounds::cells() const {
    if (layout_ != PyramidLayout::Atlas) return 0;
    if (!cells_) {
        GlTexture t = GlTexture::create();
        HFX_GL_CHECK(glTextureStorage2D(t.id(), 1, GL_RGBA32F, width_, height_));
        cells_ = std::move(t);
    }
    return cells_.id();
}

std::pair<int, int> HeightBounds::atlasOrigin(int width, int height, int level) {
    if (level == 0) return {0, 0};
    // Levels 1, 2, ... stacked in a column right of level 0: level k starts below levels 1..k-1,
    // whose heights are height >> 1, >> 2, ... and 1 each once the halving reaches 1.
    const int above = level - 1, halvings = std::countr_zero(static_cast<unsigned>(height));
    return {width, height - std::max(height >> above, 1) + std::max(0, above - halvings)};
}

std::pair<int, int> HeightBounds::atlasSize(int width, int height) {
    const int levels = static_cast<int>(std::bit_width(static_cast<unsigned>(std::max(width, height))));
    const auto [x, y] = atlasOrigin(width, height, levels - 1);
    return {width + std::max(width >> 1, 1), std::max(height, y + 1)};
}

GLuint HeightBounds::unit(int layer) {
    // heights.glsl's s_pyramid, s_pyramid1..3.
    static constexpr GLuint kUnits[] = {HFX_UNIT_PYRAMID, HFX_UNIT_PYRAMID1, HFX_UNIT_PYRAMID2, HFX_UNIT_PYRAMID3};
    if (layer < 0 || layer > 3) throw Error(str("HeightBounds::unit: layer must be 0 to 3, got ", layer));
    return kUnits[layer];
}

void HeightBounds::bind(int layer) const {
    if (built_ == Key{}) throw Error("HeightBounds::bind: the bounds were never built (BoundsPass::refresh builds them)");
    const GLuint texture = unit(layer); // checks the layer
    if (layout_ == PyramidLayout::MipChain)
        glBindTextureUnit(texture, pyramid());
    else
        HFX_GL_CHECK(glBindImageTexture(GLuint(HFX_IMAGE_PYRAMID + layer), pyramid(), 0, GL_FALSE, 0, GL_READ_ONLY,
                                        GL_RG32F));
}

void HeightBounds::upload(const void* levels, const SurfaceTextures& textures) {
    if (!fits(textures.config()))
        throw Error(str("HeightBounds::upload: the bounds are ", width_, "x", height_, ", the textures ",
                        textures.config().width, "x", textures.config().height, " (or their edges differ)"));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    const char* from = static_cast<const char*>(levels);
    size_t offset = 0;
    for (int level = 0; level < levels_; ++level) {
        const int w = std::max(width_ >> level, 1), h = std::max(height_ >> level, 1);
        const auto [x, y] = layout_ == PyramidLayout::Atlas ? atlasOrigin(width_, height_, level) : std::pair{0, 0};
        HFX_GL_CHECK(glTextureSubImage2D(pyramid(), layout_ == PyramidLayout::Atlas ? 0 : level, x, y, w, h, GL_RG,
                                         GL_FLOAT, from + offset));
        offset += 2 * sizeof(float) * static_cast<size_t>(w) * h;
    }
    built(textures);
}

} // namespace hfx
