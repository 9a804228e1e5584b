#pragma once
// The texel shadows of a flat surface under one light: the exact tracer's self-shadow (shaders/
// trace/hier.glsl's walk, run by shaders/trace/hier/texelshadows.comp) from every sample of the
// field at its own height, towards the light, into a texture of texel shadows. A shadow depends
// on the point, not on the pixel that sees it: where a texel covers many pixels, each pixel's
// walk repeats its neighbours'. The renderer then walks only the light rays from cells where the
// hard shadow's edge passes between the four samples, and blends the samples elsewhere
// (shaders/surface/shadow.glsl). ExactTracer runs it before a hier draw where its policy says
// the texel shadows pay, and keeps them while the heights and the light stay.
//
// Thread: the thread whose GL context is current.

#include "hfx/core/GlObject.h"
#include "hfx/core/ShaderProgram.h"
#include "hfx/core/ShadowLight.h"
#include "hfx/core/SurfaceTextures.h"
#include "hfx/effects/tracer/BoundsPass.h"

#include <cstdint>
#include <optional>

namespace hfx {

/// Whether drawing the texel shadows pays for a surface whose field has `texels` samples and
/// shows on `pixels` screen pixels (screenArea of its quad; a repeating surface counts every
/// copy): the pass walks every sample once, and each pixel then walks only where a hard shadow's
/// edge crosses its cell. On llvmpipe they broke even at about 1.6 pixels per texel (the decal
/// wall at 512²), paid at 1.8 and more and lost at 0.4-0.45 (the demo's scenes at 256² to 1024²,
/// docs/history/tuning.md): true from 1.75 pixels per texel. `drawing` is the last frame's answer:
/// once on, they stay on down to 1.5, so a camera near the line does not switch them (and the
/// frame's look, slightly) every frame.
bool texelShadowsPay(double pixels, double texels, bool drawing);

/// The texel shadows' stride for a width x height field shown on `pixels` screen pixels under a
/// pixel budget (SurfaceMaterial::pixelBudget, pixels): 1 where every sample pays
/// (texelShadowsPay); else the smallest power of two s dividing both sizes at which every s-th
/// sample on each axis pays (s^2 times fewer walks) while s samples stay within the budget on
/// the screen (s * sqrt(pixels / texels) pixels apart: a hard shadow finer than that may be
/// missed, as one finer than a texel is at stride 1); 0 where none does (walk every pixel's
/// light ray). `drawing`: the last frame's stride (0: none), held on as texelShadowsPay holds.
/// With no budget (0) this is texelShadowsPay's choice of 1 or 0.
int texelShadowStride(double pixels, int width, int height, float pixelBudget, int drawing);

/// Whether `stride` can space a width x height field's texel shadows: a power of two that
/// divides both sizes.
inline bool isTexelStride(int stride, int width, int height) {
    return stride >= 1 && (stride & (stride - 1)) == 0 && width % stride == 0 && height % stride == 0;
}

/// One surface's texel shadows (R32F: the exact self-shadow for one light at every stride-th
/// sample on each axis, width / stride x height / stride texels, wrapped or clamped as the
/// heights are) and what they were drawn from. TexelShadowPass draws them; the surface program
/// reads them at HFX_UNIT_TEXEL_SHADOWS for rays of their light.
class TexelShadows {
public:
    GLuint texture() const { return drawn_ ? texture_.id() : 0; } ///< 0 before the first draw
    int stride() const { return stride_; }
    /// The GL storage they hold, bytes (R32F, a texel per stride-th sample; 0 before the first draw).
    size_t bytes() const { return texture_ ? size_t(width_) * size_t(height_) * 4 : 0; }
    /// The light they hold the shadows of; empty before the first draw.
    const std::optional<ShadowLight>& light() const { return light_; }
    /// Whether they hold `light`'s shadows of `textures`' current texels at `stride`.
    bool holds(const SurfaceTextures& textures, const ShadowLight& light, int stride) const {
        return drawn_ && uid_ == textures.uid() && version_ == textures.texelsVersion() && light_ == light &&
               stride_ == stride;
    }

private:
    friend class TexelShadowPass;
    GlTexture texture_;
    int stride_ = 0, width_ = 0, height_ = 0;
    EdgeMode edges_ = EdgeMode::Wrap;
    bool drawn_ = false;
    std::optional<ShadowLight> light_;
    std::uint64_t uid_ = 0, version_ = 0; ///< the textures' and their texels' version drawn from
};

class TexelShadowPass {
public:
    /// Draws `textures`' texel shadows for `light` at every stride-th sample on each axis into
    /// `into` (allocated or remade where the size or stride changes), walking `bounds` (built
    /// here from the texels where they do not hold them). Throws hfx::Error for bounds that do
    /// not fit the textures, an invalid light or a stride that is not a power of two dividing
    /// the field's size, leaving `into` as it was. A compute pass: the same texels whatever
    /// framebuffer, blending, scissor test or colour mask the caller has set; it puts back every
    /// GL state it changes.
    void draw(const SurfaceTextures& textures, HeightBounds& bounds, const ShadowLight& light, int stride,
              TexelShadows& into);

private:
    std::optional<ShaderProgram> programs_[2]; ///< by the bounds' layout, each built by its first draw
    BoundsPass bounds_; ///< the walk's bounds and level-0 cells, where they are stale
    GlBuffer block_;
};

} // namespace hfx
