#pragma once
// A directional light's shadow map: a depth texture seen from the light (orthographic, fitted
// around a sphere that holds the casters and receivers). Casters are drawn into it between
// begin() and end() with SurfaceRenderer::drawShadow / drawFlatShadow; a relief surface writes
// the depth its tracer finds along the light's rays (not its polygon's), so relief shadows other
// geometry where the relief is, and geometry shadows the relief at the relief's depth.
// Receivers read it through DirectionalLight::shadowMap: the light is multiplied by the map's
// visibility (3x3 taps of hardware 2x2 comparison), with a depth bias and a normal offset of
// about a map texel so a surface does not shadow itself through the map's rounding (the
// relief's own self-shadow is its tracer's, exact). An engine with shadow maps of its own draws
// the same casters into them (SurfaceRenderer::drawShadow with the light's view as a Camera), and
// the surfaces receive those through DirectionalLight::cascades (ShadowCascades.h) instead.
//
// Owns its framebuffer and depth texture. Thread: the thread whose GL context is current.

#include "hfx/core/Camera.h"
#include "hfx/core/GlObject.h"
#include "hfx/effects/ShadowCascades.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace hfx {

class ShadowMap {
public:
    /// size: texels per edge, 16..16384; throws hfx::Error naming the value otherwise.
    explicit ShadowMap(int size = 2048);

    /// Points the light's view along -towardsLight at the sphere (centre, radius) that holds
    /// everything casting or receiving; throws hfx::Error for a zero direction or radius <= 0.
    void fit(glm::vec3 towardsLight, glm::vec3 centre, float radius);

    /// Binds the map's framebuffer for drawing, sets its viewport, turns the scissor test off and
    /// depth writes on (the casters fill the whole map whatever the caller left), sets GL's
    /// default clip control and depth range (the map's depth, whatever a reversed-Z caller uses)
    /// and clears the depth; end() puts back the draw and read framebuffers, the viewport, the
    /// scissor test, the depth mask, the clip control and the depth range that were set. begin()
    /// twice or end() without begin() throws hfx::Error.
    void begin();
    void end();

    /// begin() now and end() when it goes out of scope, also when a caster throws: the form the
    /// demo's scenes use (`const auto casting = map.scope();`).
    class Scope {
    public:
        explicit Scope(ShadowMap& map) : map_(&map) { map.begin(); }
        ~Scope() {
            if (map_->begun()) map_->end();
        }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        ShadowMap* map_;
    };
    [[nodiscard]] Scope scope() { return Scope(*this); }

    bool begun() const { return begun_; }
    /// Whether fit() has placed the light's view (casters drawn before it are refused).
    bool fitted() const { return fitted_; }
    int size() const { return size_; }
    GLuint texture() const { return depth_.id(); }
    /// World to the light's clip space (orthographic: window depth is linear in distance).
    const glm::mat4& viewProj() const { return viewProj_; }
    /// The light's view as an orthographic camera (GL's default depth): what the casters are
    /// drawn with.
    const Camera& lightView() const { return lightView_; }
    /// Unit vector towards the light (what the casters' tracers trace along, reversed).
    glm::vec3 towardsLight() const { return towardsLight_; }
    /// World units per map texel.
    float texelWorld() const { return 2.0f * radius_ / float(size_); }
    /// Window depth per world unit along the light.
    float depthPerWorld() const { return 1.0f / (4.0f * radius_); }
    /// A receiver's lookup: moved off the surface along its normal by normalOffset() (world
    /// units) and compared depthBias() (window depth) nearer, 1.5 map texels each, so a surface
    /// does not shadow itself through the map's rounding (surface/shadowmap.glsl).
    float normalOffset() const { return 1.5f * texelWorld(); }
    float depthBias() const { return normalOffset() * depthPerWorld(); }
    /// The map as its receivers read it: one cascade over the whole texture, GL's default depth
    /// (shadowUniforms() makes the receiving block; the lookup's offset and bias come out as
    /// normalOffset() and depthBias()). Valid while the map lives.
    ShadowCascades receiver() const { return {.texture = depth_.id(), .cascades = std::span(&cascade_, 1)}; }

private:
    int size_;
    GlFramebuffer fbo_;
    GlTexture depth_;
    glm::mat4 viewProj_{1.0f};
    Camera lightView_;
    ShadowCascade cascade_;
    glm::vec3 towardsLight_{0.0f, 1.0f, 0.0f};
    float radius_ = 1.0f;
    GLint savedDraw_ = 0, savedRead_ = 0, savedViewport_[4] = {0, 0, 0, 0};
    GLboolean savedScissor_ = GL_FALSE, savedDepthMask_ = GL_TRUE;
    GLint savedClipOrigin_ = GL_LOWER_LEFT, savedClipDepth_ = GL_NEGATIVE_ONE_TO_ONE;
    GLdouble savedDepthRange_[2] = {0.0, 1.0};
    bool begun_ = false, fitted_ = false;
};

} // namespace hfx
