#pragma once
// A gas giant's rings: a thin slab of particles in the planet's equatorial plane with a radial
// profile of opacity and colour (a dense middle ring, a faint inner one, a gap between the outer
// two, thin gaps and ringlets down to a few kilometres' worth of the profile's texels), seeded
// and made once. They cast their shadow on the cloud tops (the planet's shading reads look():
// SurfaceMaterial::planet) and receive the planet's, both with the penumbra of the sun's disc;
// their own draw scatters the sunlight once through the slab, so their lit face is bright and
// their unlit face glows only where they are thin (shaders/rings.frag, shaders/shade/rings.glsl).
//
// Draw the planet first, then draw() over it: the rings cover the planet and the sky by their
// opacity and hide behind the planet's depth.
//
// Owns its texture, mesh and program. Thread: the thread whose GL context is current.

#include "hfx/core/Camera.h"
#include "hfx/core/GlObject.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/ShaderProgram.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace hfx {

struct PlanetRingsConfig {
    float radius = 1.0f;        ///< the planet's, in its model units (makeSphere's radius)
    float inner = 1.24f;        ///< where the rings begin, model units from the centre (Saturn's: 1.24 radii)
    float outer = 2.27f;        ///< ... and end (Saturn's A ring: 2.27)
    float opacity = 1.0f;       ///< scales the profile's optical depth (1: the densest ring about 0.9 opaque)
    glm::vec3 color{0.62f, 0.56f, 0.47f}; ///< the particles' albedo, linear RGB (Saturn's B ring: about 0.6)
    float sunAngularRadius = 0.00465f;    ///< radians (the Sun's from Earth): the shadows' penumbrae
    int texels = 4096;          ///< the profile's resolution from inner to outer
    std::uint64_t seed = 1;     ///< the ringlets
    void validate() const;      ///< throws hfx::Error naming the bad field and its value
};

/// The rings' radial profile, config.texels samples from inner (first) to outer (last), each at
/// its texel's centre: rgb the particles' albedo, a the opacity seen along the rings' normal
/// (1 - e^-tau), every value in [0, 1]. The same seed gives the same profile.
std::vector<glm::vec4> ringProfile(const PlanetRingsConfig& config);

/// A flat annulus in the XZ plane about the origin, normal +Y, from `inner` to `outer` (its outer
/// polygon's edges touch the circle of `outer` from outside, so the circle is covered).
MeshData makeAnnulus(float inner, float outer, int segments = 256);

class PlanetRings {
public:
    explicit PlanetRings(const PlanetRingsConfig& config = {});

    /// What the planet's draw needs for the rings' shadow on it (SurfaceMaterial::planet).
    PlanetLook look() const;
    /// Draws the rings of the planet drawn with `model`, seen by `camera`, lit by `light`, into the
    /// bound framebuffer over what it holds: it copies the viewport's colour first (display
    /// values into GL_RGBA8; where the colours are written linear (ColorOutput), a float
    /// target's into GL_RGBA16F, an sRGB one's into GL_SRGB8_ALPHA8) and composes them over it in
    /// linear light; depth tested, no depth written. Throws hfx::Error for a multisampled
    /// framebuffer (GL copies from none). Restores the GL state it changes. `previousModel`: the
    /// planet's model at the previous frame, for the motion (setMotionOutput; empty: this one's).
    void draw(const glm::mat4& model, const Camera& camera, const DirectionalLight& light,
              const std::optional<glm::mat4>& previousModel = std::nullopt);
    /// Where the rings write their screen motion for an engine's temporal anti-aliasing or motion
    /// blur, as SurfaceRenderer::setMotionOutput says (the same draw buffer, 1 to 7, of a float or
    /// signed normalized target; 0, the default: none): a second pass of the annulus writes it
    /// where the rings cover at least half of what lies behind them (the ring point's motion:
    /// Camera::previousViewProjection, `previousModel`); through their gaps and thin rings the
    /// pixel keeps the motion of what shows through. Throws hfx::Error for a buffer outside 0 to 7.
    void setMotionOutput(int drawBuffer);
    int motionOutput() const { return motionOutput_; }
    /// How the rings' colours are encoded (ColorOutput: Auto by default, as SurfaceRenderer's):
    /// the planet's draw and theirs must agree.
    void setColorOutput(ColorOutput output) { colorOutput_ = output; }
    ColorOutput colorOutput() const { return colorOutput_; }
    const PlanetRingsConfig& config() const { return config_; }
    GLuint profile() const { return profile_.id(); }

private:
    PlanetRingsConfig config_;
    GlTexture profile_;
    Mesh annulus_;
    ShaderProgram program_;
    ShaderProgram motionProgram_; ///< the motion pass's (HFX_MOTION_OUTPUT), for motionOutput_
    int motionOutput_ = 0, motionProgramOutput_ = 0;
    GlBuffer surfaceBlock_, planetBlock_;
    GlTexture behind_; ///< the copy of the frame behind the rings
    int behindWidth_ = 0, behindHeight_ = 0;
    GLenum behindFormat_ = GL_RGBA8; ///< as the frame holds the colours (draw())
    ColorOutput colorOutput_ = ColorOutput::Auto;
};

} // namespace hfx
