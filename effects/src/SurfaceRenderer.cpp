#include "hfx/effects/SurfaceRenderer.h"

#include "hfx/core/Error.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <cmath>

namespace hfx {
namespace detail {
std::string_view embeddedShader(std::string_view name);
}

namespace {

SourceFile shader(std::string_view name) {
    return loadSource(name, detail::embeddedShader(name), "HFX_SHADER_DIR");
}

/// Saves what draw() changes and puts it back, so the caller's state survives.
class GlStateGuard {
public:
    GlStateGuard() {
        depthTest_ = glIsEnabled(GL_DEPTH_TEST);
        glGetIntegerv(GL_DEPTH_FUNC, &depthFunc_);
        glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
        glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture_);
        for (int unit = 0; unit < 4; ++unit) {
            glActiveTexture(GL_TEXTURE0 + unit);
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &textures_[unit]);
        }
    }
    ~GlStateGuard() {
        (depthTest_ ? glEnable : glDisable)(GL_DEPTH_TEST);
        glDepthFunc(static_cast<GLenum>(depthFunc_));
        glUseProgram(static_cast<GLuint>(program_));
        glBindVertexArray(static_cast<GLuint>(vao_));
        for (int unit = 0; unit < 4; ++unit) glBindTextureUnit(unit, static_cast<GLuint>(textures_[unit]));
        glActiveTexture(static_cast<GLenum>(activeTexture_));
    }
    GlStateGuard(const GlStateGuard&) = delete;
    GlStateGuard& operator=(const GlStateGuard&) = delete;

private:
    GLboolean depthTest_;
    GLint depthFunc_, program_, vao_, activeTexture_, textures_[4];
};

void setTransforms(const ShaderProgram& p, const glm::mat4& model, const Camera& camera) {
    p.set("u_model", model);
    p.set("u_viewProj", camera.viewProjection());
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
    glProgramUniformMatrix3fv(p.id(), p.uniform("u_normalMatrix"), 1, GL_FALSE, &normalMatrix[0][0]);
}

} // namespace

const char* techniqueName(Technique technique) {
    switch (technique) {
    case Technique::NormalMapping: return "nm";
    case Technique::ParallaxOcclusion: return "pom";
    case Technique::ParallaxOffset: return "parallax";
    case Technique::SteepParallax: return "steep";
    case Technique::Relief: return "relief";
    case Technique::Secant: return "secant";
    case Technique::Hierarchical: return "hier";
    }
    return "?";
}

std::string techniqueNames() {
    std::string names;
    for (Technique t : kTechniques) names += (names.empty() ? "" : ", ") + std::string(techniqueName(t));
    return names;
}

Technique parseTechnique(const std::string& name) {
    for (Technique t : kTechniques)
        if (name == techniqueName(t)) return t;
    throw Error(str("unknown technique '", name, "' (expected one of ", techniqueNames(), ")"));
}

void SurfaceMaterial::validate() const {
    if (!(depthScale >= 0.0f) || !std::isfinite(depthScale) || depthScale > 1.0f)
        throw Error(str("SurfaceMaterial.depthScale must be in [0, 1], got ", depthScale));
    if (minSamples < 1 || minSamples > 256)
        throw Error(str("SurfaceMaterial.minSamples must be in [1, 256], got ", minSamples));
    if (maxSamples < minSamples || maxSamples > 256)
        throw Error(str("SurfaceMaterial.maxSamples must be in [minSamples=", minSamples,
                        ", 256], got ", maxSamples));
    if (!std::isfinite(lodThreshold))
        throw Error(str("SurfaceMaterial.lodThreshold must be finite, got ", lodThreshold));
    if (shadowSamples < 1 || shadowSamples > 32)
        throw Error(str("SurfaceMaterial.shadowSamples must be in [1, 32], got ", shadowSamples));
    if (!(shadowSharpness > 0.0f) || !std::isfinite(shadowSharpness))
        throw Error(str("SurfaceMaterial.shadowSharpness must be positive, got ", shadowSharpness));
    if (!(specularPower >= 1.0f) || !std::isfinite(specularPower))
        throw Error(str("SurfaceMaterial.specularPower must be >= 1, got ", specularPower));
    if (!(silhouetteFade >= 0.0f && silhouetteFade < 1.0f))
        throw Error(str("SurfaceMaterial.silhouetteFade must be in [0, 1), got ", silhouetteFade));
    if (shading == Shading::Water) {
        if (!(water.fresnelF0 >= 0.0f && water.fresnelF0 <= 1.0f))
            throw Error(str("WaterLook.fresnelF0 must be in [0, 1], got ", water.fresnelF0));
        if (!(water.glintPower >= 1.0f) || !std::isfinite(water.glintPower))
            throw Error(str("WaterLook.glintPower must be >= 1, got ", water.glintPower));
        if (!(water.glintStrength >= 0.0f) || !std::isfinite(water.glintStrength))
            throw Error(str("WaterLook.glintStrength must be >= 0, got ", water.glintStrength));
        if (!(water.hazeDistance > 0.0f))
            throw Error(str("WaterLook.hazeDistance must be positive, got ", water.hazeDistance));
        if (water.environment != 0 && !glIsTexture(water.environment))
            throw Error(str("WaterLook.environment ", water.environment, " is not a GL texture"));
    }
}

const ShaderProgram& SurfaceRenderer::program(const DrawOptions& options, Shading shading) {
    const auto key = std::make_tuple(static_cast<int>(options.technique), options.traceOutput,
                                     static_cast<int>(shading));
    auto it = programs_.find(key);
    if (it == programs_.end()) {
        const std::vector<ShaderDefine> defines = {
            {"HFX_TECHNIQUE", std::to_string(static_cast<int>(options.technique))},
            {"HFX_TRACE_OUTPUT", options.traceOutput ? "1" : "0"},
            {"HFX_SHADING", std::to_string(static_cast<int>(shading))}};
        ShaderProgram p(shader("surface.vert"), shader("surface.frag"), defines);
        p.set("s_surface", 0);
        p.set("s_albedo", 1);
        p.set("s_environment", 2);
        p.set("s_pyramid", 3);
        it = programs_.emplace(key, std::move(p)).first;
    }
    return it->second;
}

void SurfaceRenderer::draw(const Mesh& mesh, const glm::mat4& model, const SurfaceTextures& textures,
                           const SurfaceMaterial& material, const Camera& camera,
                           const DirectionalLight& light, const DrawOptions& options) {
    material.validate();
    if (options.technique == Technique::Hierarchical && !textures.pyramid())
        throw Error("the hierarchical technique needs surface textures with a height pyramid "
                    "(SurfaceTexturesConfig::pyramid, refreshed by uploadPyramid)");
    const ShaderProgram& p = program(options, material.shading);
    GlStateGuard guard;
    setTransforms(p, model, camera);
    p.set("u_cameraPos", camera.position);
    p.set("u_depthScale", material.depthScale);
    p.set("u_normalScale", material.depthScale / textures.config().normalDepth);
    p.set("u_normalDecode", textures.config().format == SurfaceFormat::Unorm8 ? glm::vec2(2.0f, -1.0f)
                                                                             : glm::vec2(1.0f, 0.0f));
    p.set("u_minSamples", material.minSamples);
    p.set("u_maxSamples", material.maxSamples);
    p.set("u_lodThreshold", material.lodThreshold);
    p.set("u_shadows", material.shadows ? 1 : 0);
    p.set("u_shadowSamples", material.shadowSamples);
    p.set("u_shadowSharpness", material.shadowSharpness);
    p.set("u_clipToPatch", material.clipToPatch ? 1 : 0);
    p.set("u_patchBounds", material.patchBounds);
    p.set("u_lightDir", glm::normalize(light.direction));
    p.set("u_lightColor", light.color);
    p.set("u_ambient", light.ambient);
    p.set("u_specularStrength", material.specularStrength);
    p.set("u_specularPower", material.specularPower);
    p.set("u_silhouetteFade", material.silhouetteFade);
    if (material.shading == Shading::Water) {
        const WaterLook& w = material.water;
        p.set("u_deepColor", w.deepColor);
        p.set("u_shallowColor", w.shallowColor);
        p.set("u_skyZenith", w.skyZenith);
        p.set("u_skyHorizon", w.skyHorizon);
        p.set("u_fresnelF0", w.fresnelF0);
        p.set("u_glintPower", w.glintPower);
        p.set("u_glintStrength", w.glintStrength);
        p.set("u_hazeDistance", w.hazeDistance);
        p.set("u_hasEnvironment", w.environment != 0 ? 1 : 0);
    }
    glBindTextureUnit(0, textures.surface());
    glBindTextureUnit(1, textures.albedo());
    if (material.shading == Shading::Water) glBindTextureUnit(2, material.water.environment);
    if (options.technique == Technique::Hierarchical) {
        p.set("u_pyramidLevels", textures.pyramidLevels());
        p.set("u_wrap", glm::ivec2(wrapsU(textures.config().edges), wrapsV(textures.config().edges)));
        glBindTextureUnit(3, textures.pyramid());
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    p.use();
    mesh.draw();
}

void SurfaceRenderer::drawFlat(const Mesh& mesh, const glm::mat4& model, const Camera& camera,
                               const glm::vec4& color) {
    if (!flat_.id()) flat_ = ShaderProgram(shader("surface.vert"), shader("flat.frag"));
    GlStateGuard guard;
    setTransforms(flat_, model, camera);
    flat_.set("u_color", color);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    flat_.use();
    mesh.draw();
}

} // namespace hfx
