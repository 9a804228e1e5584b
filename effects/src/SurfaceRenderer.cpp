#include "hfx/effects/SurfaceRenderer.h"

#include "hfx/core/GpuTimer.h"

#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/effects/ShadowMap.h"
#include "hfx/effects/Sky.h"

#include "GlStateGuard.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace hfx {
namespace detail {
std::string_view embeddedShader(std::string_view name);
}

SourceFile surfaceShader(std::string_view name) {
    return loadSource(name, detail::embeddedShader(name), "HFX_SHADER_DIR");
}

std::vector<SourceFile> surfaceStage(std::string_view top, const std::map<std::string, std::string, std::less<>>& slots) {
    return expandIncludes(surfaceShader(top), surfaceShader, slots);
}

namespace {

WaterUniforms waterUniforms(const WaterLook& w, const DirectionalLight& light) {
    return {.deepColor = w.deepColor,
            .fresnelF0 = w.fresnelF0,
            .shallowColor = w.shallowColor,
            .glintPower = w.glintPower,
            .skyZenith = w.skyZenith,
            .glintStrength = w.glintStrength,
            .skyHorizon = w.skyHorizon,
            .hazeDistance = w.hazeDistance,
            .foam = w.foam ? 1 : 0,
            .sunGlow = w.sunGlow,
            .translucency = w.translucency,
            .foamCells = w.foamCells,
            .foamColor = w.foamColor,
            .foamRoughness = w.foamRoughness,
            .foamDrift = w.foamDrift,
            .windDirection = w.windDirection,
            .spindrift = w.spindrift,
            .streakCells = w.streakCells,
            .windDirectionFrom = w.windDirectionFrom,
            .spindriftFrom = w.spindriftFrom,
            .cloudHeight = w.cloudHeight,
            .cloudDrift = w.cloudDrift,
            .cloudScale = w.cloudScale,
            .cloudThreshold = cloudThreshold(w.cloudCover),
            .cloudSunward = cloudSunwardStep(w, light),
            .cloudCover = w.cloudCover,
            .cloudVeil = cloudVeil(w),
            .cloudMeanThickness = cloudMeanThickness(w)};
}

/// The slope variance a format's rounding alone shows in its mip-0 normals (Toksvig must not
/// read it as roughness): float16 normals are unit to 2^-11, unorm8's to about 1/255.
float varianceFloor(SurfaceFormat format) {
    return format == SurfaceFormat::Float32 ? 0.0f : format == SurfaceFormat::Float16 ? 1e-3f : 8e-3f;
}

} // namespace

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
    if (!(pixelBudget >= 0.0f) || !std::isfinite(pixelBudget))
        throw Error(str("SurfaceMaterial.pixelBudget must be >= 0 (pixels; 0 = exact), got ", pixelBudget));
    if (shading == Shading::Water) {
        if (!(water.fresnelF0 >= 0.0f && water.fresnelF0 <= 1.0f))
            throw Error(str("WaterLook.fresnelF0 must be in [0, 1], got ", water.fresnelF0));
        if (!(water.glintPower >= 1.0f) || !std::isfinite(water.glintPower))
            throw Error(str("WaterLook.glintPower must be >= 1, got ", water.glintPower));
        if (!(water.glintStrength >= 0.0f) || !std::isfinite(water.glintStrength))
            throw Error(str("WaterLook.glintStrength must be >= 0, got ", water.glintStrength));
        if (!(water.translucency >= 0.0f && water.translucency <= 10.0f))
            throw Error(str("WaterLook.translucency must be in [0, 10], got ", water.translucency));
        if (!(water.hazeDistance > 0.0f))
            throw Error(str("WaterLook.hazeDistance must be positive, got ", water.hazeDistance));
        water.validateSky();
    }
    if (shading == Shading::Planet) planet.validate();
    if (!(triplanar.scale >= 0.0f) || !std::isfinite(triplanar.scale))
        throw Error(str("SurfaceMaterial.triplanar.scale must be >= 0 (texcoords per unit; 0 = off), got ", triplanar.scale));
    if (!(triplanar.sharpness >= 1.0f && triplanar.sharpness <= 64.0f))
        throw Error(str("SurfaceMaterial.triplanar.sharpness must be in [1, 64], got ", triplanar.sharpness));
    if (triplanar.on() && clipToPatch)
        throw Error("SurfaceMaterial.clipToPatch cannot be set with triplanar.scale > 0: the patch's bounds are in the "
                    "mesh's texcoords, which a triplanar mapping does not read");
}

SkyKind WaterLook::sky() const {
    return environment != 0 ? SkyKind::Environment : cloudCover > 0.0f ? SkyKind::Clouds : SkyKind::Gradient;
}

void WaterLook::validateSky() const {
    if (environment != 0 && !glIsTexture(environment))
        throw Error(str("WaterLook.environment ", environment, " is not a GL texture"));
    if (!(cloudCover >= 0.0f && cloudCover <= 1.0f))
        throw Error(str("WaterLook.cloudCover must be in [0, 1] (the share of the sky under cloud), got ", cloudCover));
    if (!(cloudScale > 0.0f && cloudScale <= 64.0f))
        throw Error(str("WaterLook.cloudScale must be in (0, 64] clouds per cloud height, got ", cloudScale));
    if (!(cloudHeight > 0.0f) || !std::isfinite(cloudHeight))
        throw Error(str("WaterLook.cloudHeight must be positive and finite (world units over y = 0), got ", cloudHeight));
    if (!isFinite(cloudDrift)) throw Error(str("WaterLook.cloudDrift must be finite, got ", text(cloudDrift)));
    if (cloudCover > 0.0f && environment != 0)
        throw Error(str("WaterLook.cloudCover ", cloudCover, " draws clouds in the procedural sky, but the look has an "
                        "environment image (", environment, "), which is the whole sky: set one or the other"));
}

void DirectionalLight::validate() const {
    if (!isFinite(direction) || !(glm::length(glm::dvec3(direction)) > 0.0))
        throw Error(str("DirectionalLight.direction must be finite and not zero, got ", text(direction)));
    for (const auto& [name, value] : {std::pair("color", color), std::pair("ambient", ambient)})
        if (!isFinite(value) || glm::any(glm::lessThan(value, glm::vec3(0.0f))))
            throw Error(str("DirectionalLight.", name, " must be finite and not negative, got ", text(value)));
    if (shadowMap && cascades)
        throw Error("DirectionalLight: a light's shadows come from its shadowMap or its cascades, not both");
}

void PlanetLook::validate() const {
    if (!(radius > 0.0f) || !std::isfinite(radius))
        throw Error(str("PlanetLook.radius must be positive, got ", radius));
    if (!(sunAngularRadius >= 0.0f && sunAngularRadius <= 0.1f))
        throw Error(str("PlanetLook.sunAngularRadius must be in [0, 0.1] radians, got ", sunAngularRadius));
    if (ringOuter == 0.0f) return; // no rings
    if (!(ringInner > radius && ringOuter > ringInner) || !std::isfinite(ringOuter))
        throw Error(str("PlanetLook: the rings must lie beyond the planet, radius ", radius, " < ringInner ", ringInner,
                        " < ringOuter ", ringOuter));
    if (ringProfile == 0 || !glIsTexture(ringProfile))
        throw Error(str("PlanetLook.ringProfile ", ringProfile, " is not a GL texture"));
}

PlanetUniforms planetUniforms(const PlanetLook& look, const glm::mat4& model) {
    PlanetUniforms u;
    const glm::mat3 linear(model);
    const float scale = std::cbrt(std::abs(glm::determinant(linear))); // uniform: its cube root
    u.planetCentre = glm::vec3(model[3]);
    u.planetRadius = look.radius * scale;
    u.ringAxis = glm::normalize(glm::transpose(glm::inverse(linear)) * glm::vec3(0.0f, 1.0f, 0.0f));
    u.ringInner = look.ringInner * scale;
    u.ringOuter = look.ringOuter * scale;
    u.sunRadius = look.sunAngularRadius;
    if (look.ringProfile != 0) {
        GLint width = 1;
        glGetTextureLevelParameteriv(look.ringProfile, 0, GL_TEXTURE_WIDTH, &width);
        u.ringTexels = float(width);
    }
    u.ringShine = look.ringShine && look.ringOuter > 0.0f ? 1.0f : 0.0f;
    return u;
}

namespace {
// Every texture unit of the table once, within its count: no unit serves two samplers.
constexpr GLuint kTextureUnits[] = {HFX_UNIT_SURFACE,  HFX_UNIT_ALBEDO,      HFX_UNIT_ENVIRONMENT, HFX_UNIT_PYRAMID,
                                    HFX_UNIT_SURFACE1, HFX_UNIT_SURFACE2,    HFX_UNIT_SURFACE3,    HFX_UNIT_ALBEDO1,
                                    HFX_UNIT_ALBEDO2,  HFX_UNIT_ALBEDO3,     HFX_UNIT_CHANNELS,    HFX_UNIT_SHADOW_MAP,
                                    HFX_UNIT_PYRAMID1, HFX_UNIT_PYRAMID2,    HFX_UNIT_PYRAMID3,    HFX_UNIT_TEXEL_SHADOWS,
                                    HFX_UNIT_BEAM_START, HFX_UNIT_RING_PROFILE, HFX_UNIT_RING_BEHIND,
                                    HFX_UNIT_RING_SHINE};
constexpr bool unitsDistinct() {
    for (size_t i = 0; i < std::size(kTextureUnits); ++i) {
        if (kTextureUnits[i] >= HFX_TEXTURE_UNITS) return false;
        for (size_t j = 0; j < i; ++j)
            if (kTextureUnits[i] == kTextureUnits[j]) return false;
    }
    return std::size(kTextureUnits) == HFX_TEXTURE_UNITS;
}
static_assert(unitsDistinct(), "hfx/core/Bindings.h: every texture unit once, below HFX_TEXTURE_UNITS");

/// Throws where the context's fragment stage has fewer texture units than the surface program binds.
void requireTextureUnits() {
    GLint units = 0, combined = 0;
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &combined);
    if (std::min(units, combined) < HFX_TEXTURE_UNITS)
        throw Error(str("the surface program binds ", HFX_TEXTURE_UNITS, " texture units (hfx/core/Bindings.h); this GL "
                        "context has ", units, " in a fragment stage (GL_MAX_TEXTURE_IMAGE_UNITS) and ", combined,
                        " in all (GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS)"));
}

/// The extra outputs' draw buffers, named: the motion's and the surface outputs'.
std::array<std::pair<const char*, int>, 5> extraOutputs(int motion, const SurfaceOutputs& o) {
    return {{{"the motion", motion},
             {"the normal", o.normal},
             {"the albedo", o.albedo},
             {"the material", o.material},
             {"the emission", o.emission}}};
}

/// Throws hfx::Error where two of the extra outputs name one draw buffer.
void checkDistinct(const char* what, int motion, const SurfaceOutputs& o) {
    const auto named = extraOutputs(motion, o);
    for (size_t i = 0; i < named.size(); ++i)
        for (size_t j = i + 1; j < named.size(); ++j)
            if (named[i].second != 0 && named[i].second == named[j].second)
                throw Error(str(what, ": ", named[i].first, " and ", named[j].first, " would both go to draw buffer ",
                                named[i].second));
}
} // namespace

const ShaderProgram& SurfaceRenderer::program(const DrawOptions& options, const SurfaceVariant& variant) {
    SurfaceVariant v = variant;
    if (v.layers < 1 || v.layers > kMaxSurfaceLayers)
        throw Error(str("SurfaceVariant.layers must be 1 to ", kMaxSurfaceLayers, ", got ", v.layers));
    if (v.traced <= 0 || v.traced > v.layers) v.traced = v.layers;
    v.rings = v.rings && v.shading == Shading::Water;
    if (v.shading != Shading::Water) v.sky = SkyKind::Gradient;
    if (v.caster || v.shadowMap < 0 || v.shadowMap > 2) v.shadowMap = 0; // a caster writes depth only
    v.texelShadows = v.texelShadows && !v.caster && v.selfShadows && v.layers == 1 &&
                     options.technique == Technique::Hierarchical;
    v.beamStart = v.beamStart && v.layers == 1 && options.technique == Technique::Hierarchical;
    if (v.triplanar) { // (no flat patch: each projection is walked in the draw or the compute pass)
        if (v.layers != 1) throw Error(str("SurfaceVariant.triplanar takes one layer, got ", v.layers));
        v.texelShadows = v.beamStart = false;
    }
    v.deferredShadows = v.deferredShadows && v.texelShadows && !options.traceOutput;
    v.traceLights = v.traceLights && v.computeTrace == 1 && v.selfShadows; // only the rays draw stores them
    if (v.caster || v.computeTrace == 1) { // a shadow map's pass, the rays draw: no colour
        v.motionOutput = 0;
        v.outputs = {};
        v.sky = SkyKind::Gradient;
    }
    const auto key = std::make_tuple(options.technique, options.traceOutput && !v.caster, v);
    auto it = programs_.find(key);
    if (it == programs_.end()) {
        // The outputs' draw buffers, checked once a variant (the key holds all they depend on).
        for (const auto& [name, buffer] : extraOutputs(v.motionOutput, v.outputs)) {
            checkDrawBuffer(str("SurfaceVariant, ", name).c_str(), buffer);
            if (buffer != 0 && options.traceOutput && buffer <= 2)
                throw Error(str(name, " output's draw buffer ", buffer,
                                " is one the trace output writes (DrawOptions::traceOutput: 1 and 2): set another "
                                "(SurfaceRenderer::setMotionOutput, setSurfaceOutputs)"));
        }
        checkDistinct("SurfaceVariant", v.motionOutput, v.outputs);
        requireTextureUnits();
        // surface.frag's parts with the technique's tracer and the shading model in their slots;
        // the table says the defines.
        const TechniqueInfo& info = techniqueInfo(options.technique);
        const std::vector<ShaderDefine> defines = {{"HFX_TRACES", info.traces ? "1" : "0"},
                                                   {"HFX_SELF_SHADOW", info.shadow != SelfShadow::None && v.selfShadows ? "1" : "0"},
                                                   {"HFX_TRACE_OUTPUT", options.traceOutput && !v.caster ? "1" : "0"},
                                                   {"HFX_SHADOW_CASTER", v.caster ? "1" : "0"},
                                                   {"HFX_LAYERS", std::to_string(v.layers)},
                                                   {"HFX_TRACED_LAYERS", std::to_string(v.traced)},
                                                   {"HFX_RINGS", v.rings ? "1" : "0"},
                                                   {"HFX_SKY", std::to_string(int(v.sky))},
                                                   {"HFX_BOUNDED_SEARCH", v.boundedSearch ? "1" : "0"},
                                                   {"HFX_SHADOW_MAP", std::to_string(v.shadowMap)},
                                                   {"HFX_TEXEL_SHADOWS", v.texelShadows ? "1" : "0"},
                                                   {"HFX_BEAM_START", v.beamStart ? "1" : "0"},
                                                   {"HFX_DEFERRED_SHADOWS", v.deferredShadows ? "1" : "0"},
                                                   {"HFX_COMPUTE_TRACE", std::to_string(v.computeTrace)},
                                                   {"HFX_TRACE_LIGHTS", v.traceLights ? "1" : "0"},
                                                   {"HFX_PYRAMID_ATLAS", v.pyramidAtlas ? "1" : "0"},
                                                   {"HFX_REVERSED_Z", v.reversedZ ? "1" : "0"},
                                                   {"HFX_MOTION_OUTPUT", std::to_string(v.motionOutput)},
                                                   {"HFX_NORMAL_OUTPUT", std::to_string(v.outputs.normal)},
                                                   {"HFX_ALBEDO_OUTPUT", std::to_string(v.outputs.albedo)},
                                                   {"HFX_MATERIAL_OUTPUT", std::to_string(v.outputs.material)},
                                                   {"HFX_EMISSION_OUTPUT", std::to_string(v.outputs.emission)},
                                                   {"HFX_TRIPLANAR", v.triplanar ? "1" : "0"}};
        ShaderProgram p(surfaceStage("surface.vert"),
                        surfaceStage("surface.frag", {{"tracer", info.shader}, {"shading", shadingShader(v.shading)}}), defines);
        it = programs_.emplace(key, std::move(p)).first;
    }
    return it->second;
}

void SurfaceRenderer::setMotionOutput(int drawBuffer) {
    checkDrawBuffer("SurfaceRenderer::setMotionOutput", drawBuffer);
    checkDistinct("SurfaceRenderer::setMotionOutput", drawBuffer, outputs_);
    motionOutput_ = drawBuffer;
}

void SurfaceRenderer::setSurfaceOutputs(const SurfaceOutputs& outputs) {
    for (const auto& [name, buffer] : extraOutputs(0, outputs))
        if (buffer != 0) checkDrawBuffer(str("SurfaceRenderer::setSurfaceOutputs, ", name).c_str(), buffer);
    checkDistinct("SurfaceRenderer::setSurfaceOutputs", motionOutput_, outputs);
    outputs_ = outputs;
}

namespace {
/// The draw buffers a draw writes: colour buffer 0, the motion's and the surface outputs' where
/// they are written, the trace output's (1 and 2) where asked.
unsigned buffersWritten(int motionOutput, const SurfaceOutputs& outputs, bool traceOutput) {
    unsigned written = 1u | (traceOutput ? 6u : 0u);
    for (const auto& [name, buffer] : extraOutputs(motionOutput, outputs))
        if (buffer > 0) written |= 1u << buffer;
    return written;
}
} // namespace

void SurfaceRenderer::bindUniforms(SurfaceUniforms& u, const glm::mat4& model, const glm::mat4& viewProj) {
    setTransform(u, model, viewProj);
    updateBlock(surfaceBlock_, HFX_BLOCK_SURFACE, u);
}

void SurfaceRenderer::draw(const Mesh& mesh, const glm::mat4& model, const SurfaceTextures& textures,
                           const SurfaceMaterial& material, const Camera& camera,
                           const DirectionalLight& light, const DrawOptions& options) {
    const SurfaceLayer layer{.textures = &textures};
    draw(mesh, model, std::span(&layer, 1), material, camera, light, options);
}

namespace {
void validateLayers(std::span<const SurfaceLayer> layers, const TechniqueInfo& technique) {
    if (layers.empty() || int(layers.size()) > kMaxSurfaceLayers)
        throw Error(str("a surface has 1 to ", kMaxSurfaceLayers, " layers, got ", layers.size()));
    float weights = 0.0f;
    for (size_t i = 0; i < layers.size(); ++i) {
        const SurfaceLayer& l = layers[i];
        if (!l.textures) throw Error(str("surface layer ", i, " has no textures"));
        if (!(l.texcoordScale > 0.0f) || !std::isfinite(l.texcoordScale))
            throw Error(str("surface layer ", i, ": texcoordScale must be positive, got ", l.texcoordScale));
        if (!(l.weight >= 0.0f) || !std::isfinite(l.weight))
            throw Error(str("surface layer ", i, ": weight must be >= 0, got ", l.weight));
        weights += l.weight;
        if (!l.traced && i == 0) throw Error("surface layer 0 is untraced: the first layer is always traced");
        if (l.traced && i > 0 && !layers[i - 1].traced)
            throw Error(str("surface layer ", i, " is traced after the untraced layer ", i - 1,
                            ": traced layers come first"));
        if (!(l.restHeight >= 0.0f && l.restHeight <= 1.0f))
            throw Error(str("surface layer ", i, ": restHeight must be in [0, 1], got ", l.restHeight));
        if (layers.size() > 1) {
            if (l.textures->config().edges != EdgeMode::Wrap)
                throw Error(str("surface layer ", i, " does not tile (edges ", edgeModeName(l.textures->config().edges),
                                "): the layers of a surface repeat at their own scales"));
            if (l.textures->config().format != layers[0].textures->config().format)
                throw Error(str("surface layer ", i, " is ", surfaceFormatName(l.textures->config().format),
                                ", layer 0 ", surfaceFormatName(layers[0].textures->config().format),
                                ": a surface's layers share one format"));
        }
    }
    if (std::abs(weights - 1.0f) > 1e-3f)
        throw Error(str("the weights of a surface's layers must sum to 1 (heights stay in [0,1]), got ", weights));
    if (technique.needsPyramid && layers.size() > 1)
        throw Error(str("the ", technique.name, " technique traces one grid; a layered surface (", layers.size(),
                        " layers) needs another technique"));
    if (technique.needsPyramid)
        if (const std::string why = boundsRefusal(layers[0].textures->config()); !why.empty())
            throw Error(str("the ", technique.name, " technique walks the surface's height pyramid, and ", why));
}
} // namespace

void SurfaceRenderer::draw(const Mesh& mesh, const glm::mat4& model, std::span<const SurfaceLayer> layers,
                           const SurfaceMaterial& material, const Camera& camera, const DirectionalLight& light,
                           const DrawOptions& options) {
    drawSurface(mesh, model, layers, material, camera, light, options, Viewer::Camera);
}

void SurfaceRenderer::drawShadow(const Mesh& mesh, const glm::mat4& model, const SurfaceTextures& textures,
                                 const SurfaceMaterial& material, const ShadowMap& map, const DrawOptions& options) {
    const SurfaceLayer layer{.textures = &textures};
    drawShadow(mesh, model, std::span(&layer, 1), material, map, options);
}

namespace {
/// A ShadowMap's casters are drawn between its begin() and end() (into its framebuffer), after a
/// fit() (its light's view).
void checkCasting(const ShadowMap& map, const char* call) {
    if (!map.fitted())
        throw Error(str("SurfaceRenderer::", call, ": the shadow map has no light's view yet (ShadowMap::fit)"));
    if (!map.begun())
        throw Error(str("SurfaceRenderer::", call, ": the shadow map is not begun; draw its casters between "
                        "ShadowMap::begin() and end() (or in its scope()), which bind its framebuffer"));
}

/// The light a caster's draw is given: towards the eye of its view (a caster walks no light ray,
/// and shades nothing; the direction only has to be valid, and a valid camera's eye is off its
/// target).
DirectionalLight casterLight(const Camera& lightView) {
    DirectionalLight light;
    light.direction = lightView.position - lightView.target;
    return light;
}
} // namespace

void SurfaceRenderer::drawShadow(const Mesh& mesh, const glm::mat4& model, std::span<const SurfaceLayer> layers,
                                 const SurfaceMaterial& material, const ShadowMap& map, const DrawOptions& options) {
    checkCasting(map, "drawShadow");
    drawSurface(mesh, model, layers, material, map.lightView(), casterLight(map.lightView()), options,
                Viewer::LightAroundAll);
}

void SurfaceRenderer::drawShadow(const Mesh& mesh, const glm::mat4& model, const SurfaceTextures& textures,
                                 const SurfaceMaterial& material, const Camera& lightView, const DrawOptions& options) {
    const SurfaceLayer layer{.textures = &textures};
    drawShadow(mesh, model, std::span(&layer, 1), material, lightView, options);
}

void SurfaceRenderer::drawShadow(const Mesh& mesh, const glm::mat4& model, std::span<const SurfaceLayer> layers,
                                 const SurfaceMaterial& material, const Camera& lightView, const DrawOptions& options) {
    lightView.validate();
    drawSurface(mesh, model, layers, material, lightView, casterLight(lightView), options, Viewer::Light);
}

int SurfaceRenderer::receiveShadows(const DirectionalLight& light) {
    if (!light.shadowMap && !light.cascades) return 0;
    if (light.shadowMap && !light.shadowMap->fitted())
        throw Error("DirectionalLight.shadowMap has no light's view yet (ShadowMap::fit): nothing was cast into it");
    const ShadowCascades shadows = light.shadowMap ? light.shadowMap->receiver() : *light.cascades;
    bool array = false;
    const ShadowUniforms u = shadowUniforms(shadows, array);
    updateBlock(shadowBlock_, HFX_BLOCK_SHADOWS, u);
    GlSampler& sampler = shadowSamplers_[shadows.reversedZ ? 1 : 0];
    if (!sampler) {
        // Hardware comparison with bilinear weights: each tap is a 2x2 percentage-closer filter;
        // lit where the point's depth is no farther from the light than the map's.
        sampler = GlSampler::create();
        glSamplerParameteri(sampler.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glSamplerParameteri(sampler.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glSamplerParameteri(sampler.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(sampler.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(sampler.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glSamplerParameteri(sampler.id(), GL_TEXTURE_COMPARE_FUNC, shadows.reversedZ ? GL_GEQUAL : GL_LEQUAL);
    }
    glBindTextureUnit(HFX_UNIT_SHADOW_MAP, shadows.texture);
    glBindSampler(HFX_UNIT_SHADOW_MAP, sampler.id());
    return array ? 2 : 1;
}

namespace {
/// Whether a closed mesh (MeshData::closed) drawn with `model` shows its viewer front faces only:
/// a shadow map's light (from outside everything it holds: `aroundAll`), a camera's or a light's
/// view whose eye lies outside the mesh's bounds by more than its near plane reaches (a near plane
/// that cut the mesh would show back faces through the cut; an orthographic view's near plane
/// reaches as far from its position, and lies as wholly within that distance).
bool backFacesHidden(const Mesh& mesh, const glm::mat4& model, const Camera& camera, bool aroundAll) {
    if (!mesh.closed()) return false;
    if (aroundAll) return true;
    const glm::vec4 b = mesh.bounds();
    const glm::vec3 centre(model * glm::vec4(glm::vec3(b), 1.0f));
    const glm::mat3 m(model);
    const float scale = std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
    return glm::length(camera.position - centre) > b.w * scale + camera.nearPlaneReach();
}
} // namespace

void SurfaceRenderer::drawSurface(const Mesh& mesh, const glm::mat4& model, std::span<const SurfaceLayer> layers,
                                  const SurfaceMaterial& material, const Camera& camera, const DirectionalLight& light,
                                  const DrawOptions& options, Viewer viewer) {
    const bool caster = viewer != Viewer::Camera;
    material.validate();
    camera.validate();
    light.validate();
    checkModel(model);
    if (options.previousModel && !isFinite(*options.previousModel))
        throw Error(str("DrawOptions.previousModel must be finite, got the columns ", columnsText(*options.previousModel)));
    // A caster draws with its light view's depth (a ShadowMap's is GL's default: ShadowMap::begin
    // sets it).
    const bool reversedZ = camera.reversedZ;
    checkClipControl(reversedZ);
    if (!caster) {
        checkOutputTarget(motionOutput_, "the motion (SurfaceRenderer::setMotionOutput)", TargetHolds::Negatives);
        checkOutputTarget(outputs_.normal, "the normal (SurfaceRenderer::setSurfaceOutputs)", TargetHolds::Negatives);
        checkOutputTarget(outputs_.emission, "the emission (SurfaceRenderer::setSurfaceOutputs)", TargetHolds::OverOne);
    }
    const TechniqueInfo& info = techniqueInfo(options.technique);
    validateLayers(layers, info);
    const SurfaceTextures& textures = *layers[0].textures;
    const bool triplanar = material.triplanar.on();
    if (triplanar && layers.size() != 1)
        throw Error(str("SurfaceMaterial.triplanar draws a surface of one layer, got ", layers.size(),
                        " (layers tile the mesh's texcoords)"));
    if (triplanar && textures.config().edges != EdgeMode::Wrap)
        throw Error(str("SurfaceMaterial.triplanar needs a surface that wraps both ways (its projections tile it), got "
                        "edges ", edgeModeName(textures.config().edges)));
    const int traced = int(std::count_if(layers.begin(), layers.end(), [](const SurfaceLayer& l) { return l.traced; }));
    GlStateGuard guard;
    const EdgeMode edges = textures.config().edges;
    SurfaceUniforms u{.patchBounds = material.patchBounds,
                      .depthScale = material.depthScale,
                      .lightDir = glm::normalize(light.direction),
                      .normalScale = material.depthScale / textures.config().normalDepth,
                      .lightColor = light.color,
                      .lodThreshold = material.lodThreshold,
                      .ambient = light.ambient,
                      .shadowSharpness = material.shadowSharpness,
                      .normalDecode = textures.config().format == SurfaceFormat::Unorm8
                                          ? glm::vec2(2.0f, -1.0f)
                                          : glm::vec2(1.0f, 0.0f),
                      .specularStrength = material.specularStrength,
                      .specularPower = material.specularPower,
                      .silhouetteFade = material.silhouetteFade,
                      .minSamples = material.minSamples,
                      .maxSamples = material.maxSamples,
                      .shadowSamples = material.shadowSamples,
                      .clipToPatch = material.clipToPatch ? 1 : 0,
                      .varianceFloor = varianceFloor(textures.config().format),
                      .pixelBudget = material.pixelBudget,
                      .reversedZ = reversedZ ? 1 : 0};
    if (triplanar) {
        u.triplanarScale = material.triplanar.scale;
        u.triplanarSharpness = material.triplanar.sharpness;
    }
    u.linearOutput = !caster && writesLinear(colorOutput_) ? 1 : 0;
    setEye(u, camera); // (a caster's: its light view's, whose rays it traces)
    const int motion = caster ? 0 : motionOutput_;
    if (motion) setMotion(u, camera, model, options.previousModel);
    const SurfaceOutputs outputs = caster ? SurfaceOutputs{} : outputs_;
    u.setField({textures.config().width, textures.config().height}, edges);
    // Layer i is read at texcoords * scale_i, so its slopes per mesh texcoord are scale_i times
    // its own, and its texels per pixel scale_i * size_i / size_0 times those of layer 0's
    // texture read at the mesh's own texcoords (the level surface.frag computes).
    const float base = float(textures.config().width);
    for (size_t i = 0; i < layers.size(); ++i) {
        const SurfaceLayer& l = layers[i];
        u.layerScale[int(i)] = l.texcoordScale;
        u.layerWeight[int(i)] = l.weight;
        u.layerSlope[int(i)] = material.depthScale * l.weight * l.texcoordScale / l.textures->config().normalDepth;
        u.layerLevel[int(i)] = std::log2(l.texcoordScale * float(l.textures->config().width) / base);
        if (!l.traced) u.untracedHeight += l.weight * l.restHeight;
    }
    const glm::mat4 viewProj = camera.viewProjection();
    // The exact tracer's data and passes, and the bounds of a bounded search, as it decides.
    // The deferred light walks rewrite the colour alone: where the material output holds the
    // self-shadow, they stay in the draw.
    DrawOptions tracing = options;
    tracing.deferShadowWalks = options.deferShadowWalks && outputs.material == 0;
    // The light's shadow maps first: a bad one is refused before the tracer's passes run.
    const int received = caster ? 0 : receiveShadows(light);
    const TracerFrame frame = tracer_.prepare(layers, mesh, model, viewProj, light, material, tracing, caster, u);
    const SurfaceVariant variant{.shading = material.shading,
                                 .layers = int(layers.size()),
                                 .traced = traced,
                                 .selfShadows = material.shadows,
                                 .boundedSearch = frame.boundedSearch,
                                 .shadowMap = received,
                                 .rings = material.water.ringCount > 0,
                                 .sky = material.water.sky(),
                                 .caster = caster,
                                 // (With the walks in the compute pass, neither draw reads the
                                 // texel shadows or the beam start: the pass does.)
                                 .texelShadows = frame.texelShadows != nullptr && !frame.computeTrace,
                                 .beamStart = frame.beamStart && !frame.computeTrace,
                                 .deferredShadows = frame.deferredShadows,
                                 .computeTrace = frame.computeTrace ? 2 : 0,
                                 .pyramidAtlas = frame.atlas,
                                 .reversedZ = reversedZ,
                                 .motionOutput = motion,
                                 .outputs = outputs,
                                 .triplanar = triplanar};
    const ShaderProgram& p = program(options, variant);
    // (A caster writes no colour buffer: an engine's shadow map may have a colour attachment.)
    const DrawBuffersWritten written(caster ? 0u : buffersWritten(motion, outputs, options.traceOutput));
    if (material.shading == Shading::Water) {
        const WaterLook& w = material.water;
        updateBlock(waterBlock_, HFX_BLOCK_WATER, waterUniforms(w, light));
        glBindTextureUnit(HFX_UNIT_ENVIRONMENT, w.environment);
        RingUniforms rings;
        rings.count = w.ringCount;
        for (int i = 0; i < w.ringCount; ++i) {
            const WaterRing& r = w.rings[size_t(i)];
            rings.shape[i] = {r.centre, r.radius, r.width};
            rings.wave[i] = {r.wavenumber, r.amplitude, r.foam, 0.0f};
        }
        updateBlock(ringBlock_, HFX_BLOCK_RINGS, rings);
    }
    if (material.shading == Shading::Planet) {
        const PlanetLook& look = material.planet;
        const PlanetUniforms planet = planetUniforms(look, model);
        updateBlock(planetBlock_, HFX_BLOCK_PLANET, planet);
        glBindTextureUnit(HFX_UNIT_RING_SHINE,
                          planet.ringShine > 0.0f && !caster
                              ? ringShine_.texture(look.ringProfile, look.ringInner / look.radius,
                                                   look.ringOuter / look.radius,
                                                   glm::dot(glm::normalize(light.direction), planet.ringAxis))
                              : 0);
        glBindTextureUnit(HFX_UNIT_RING_PROFILE, look.ringProfile);
    }
    glBindTextureUnit(HFX_UNIT_SURFACE, textures.surface());
    glBindTextureUnit(HFX_UNIT_ALBEDO, textures.albedo());
    glBindTextureUnit(HFX_UNIT_CHANNELS, textures.channels());
    for (size_t i = 1; i < layers.size(); ++i) {
        glBindTextureUnit(GLuint(HFX_UNIT_SURFACE1 + i - 1), layers[i].textures->surface());
        glBindTextureUnit(GLuint(HFX_UNIT_ALBEDO1 + i - 1), layers[i].textures->albedo());
    }
    bindUniforms(u, model, viewProj);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(reversedZ ? GL_GREATER : GL_LESS);
    // The mesh's winding as the model and the view leave it (a mirroring model turns it, and so
    // does a mirror's view: Camera::mirrored): the compute pass's draws tell front faces by it,
    // and the back faces a closed mesh hides are culled.
    const bool mirroredView = camera.mirrored;
    glFrontFace((glm::determinant(glm::mat3(model)) < 0.0f) != mirroredView ? GL_CW : GL_CCW);
    if (backFacesHidden(mesh, model, camera, viewer == Viewer::LightAroundAll)) {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
    }
    if (frame.computeTrace) {
        // The walks in a compute pass (trace/hier/trace.glsl): the rays draw stores each pixel's
        // ray (on a flat patch the tracer finds them from the screen), the tracer walks them,
        // and the draw below reads the hits.
        if (!frame.patchRays) {
            DrawOptions rays = options;
            rays.traceOutput = false;
            SurfaceVariant raysVariant = variant;
            raysVariant.computeTrace = 1;
            raysVariant.traceLights = frame.traceLights;
            const ShaderProgram& r = program(rays, raysVariant);
            const GpuScope scope("rays");
            const NoFramebufferWrites none(written);
            r.use();
            mesh.draw();
        }
        const GpuScope scope("walks");
        tracer_.walks(frame);
    }
    p.use();
    {
        const GpuScope scope(caster ? "shadow map" : "draw");
        mesh.draw();
    }
    tracer_.finish(frame);
}

std::optional<ShadowLight> flatSurfaceLight(const SurfaceFrame& frame, const DirectionalLight& light,
                                            const SurfaceMaterial& material) {
    if (!material.shadows || !(material.depthScale > 0.0f) || !(material.shadowSharpness > 1.0f)) return std::nullopt;
    const double t = glm::length(frame.tangent), b = glm::length(frame.bitangent);
    if (!(t > 0.0) || !(b > 0.0)) return std::nullopt;
    // shaders/surface.frag: world from texture = (dP/du, dP/dv, the normal at the same scale).
    const glm::dmat3 worldFromTexture(frame.tangent, frame.bitangent, frame.normal * std::sqrt(t * b));
    const glm::dvec3 l = glm::inverse(worldFromTexture) * glm::normalize(glm::dvec3(light.direction));
    if (!(l.z > 0.0)) return std::nullopt;
    return ShadowLight::of(glm::vec2(glm::dvec2(l) / l.z * double(material.depthScale)), material.shadowSharpness);
}

void SurfaceRenderer::drawSky(const Camera& camera, const DirectionalLight& light, const WaterLook& look) {
    camera.validate();
    light.validate();
    look.validateSky();
    checkOutputTarget(motionOutput_, "the motion (SurfaceRenderer::setMotionOutput)", TargetHolds::Negatives);
    ShaderProgram& sky = sky_[{look.sky(), motionOutput_}];
    if (!sky.id()) {
        sky = ShaderProgram(surfaceStage("sky.vert"), surfaceStage("sky.frag"),
                            {{"HFX_SKY", std::to_string(int(look.sky()))},
                             {"HFX_MOTION_OUTPUT", std::to_string(motionOutput_)}});
    }
    if (!empty_) empty_ = GlVertexArray::create();
    GlStateGuard guard;
    SurfaceUniforms u{.lightDir = glm::normalize(light.direction),
                      .lightColor = light.color,
                      .reversedZ = camera.reversedZ ? 1 : 0};
    u.linearOutput = writesLinear(colorOutput_) ? 1 : 0;
    setEye(u, camera);
    if (motionOutput_) setMotion(u, camera, glm::mat4(1.0f), std::nullopt);
    const DrawBuffersWritten written(buffersWritten(motionOutput_, {}, false));
    bindUniforms(u, glm::mat4(1.0f), camera.viewProjection());
    updateBlock(waterBlock_, HFX_BLOCK_WATER, waterUniforms(look, light));
    glBindTextureUnit(HFX_UNIT_ENVIRONMENT, look.environment);
    sky.set("u_inverseViewProj", glm::inverse(camera.viewProjection()));
    glDisable(GL_DEPTH_TEST);
    sky.use();
    glBindVertexArray(empty_.id());
    const GpuScope scope("sky");
    HFX_GL_CHECK(glDrawArrays(GL_TRIANGLES, 0, 3));
}

void SurfaceRenderer::drawFlat(const Mesh& mesh, const glm::mat4& model, const Camera& camera,
                               const glm::vec4& color, const DirectionalLight* light) {
    camera.validate();
    if (light) light->validate();
    drawFlatSeenBy(mesh, model, camera.viewProjection(), &camera, camera.reversedZ, color, light);
}

void SurfaceRenderer::drawFlatShadow(const Mesh& mesh, const glm::mat4& model, const ShadowMap& map) {
    checkCasting(map, "drawFlatShadow");
    drawFlatShadow(mesh, model, map.lightView());
}

void SurfaceRenderer::drawFlatShadow(const Mesh& mesh, const glm::mat4& model, const Camera& lightView) {
    lightView.validate();
    // Depth only: the eye's position feeds nothing that is written.
    drawFlatSeenBy(mesh, model, lightView.viewProjection(), nullptr, lightView.reversedZ, glm::vec4(1.0f), nullptr);
}

void SurfaceRenderer::drawFlatSeenBy(const Mesh& mesh, const glm::mat4& model, const glm::mat4& viewProj,
                                     const Camera* camera, bool reversedZ, const glm::vec4& color,
                                     const DirectionalLight* light) {
    checkModel(model);
    checkClipControl(reversedZ);
    GlStateGuard guard;
    const int received = light ? receiveShadows(*light) : 0;
    ShaderProgram& flat = flat_[received];
    if (!flat.id())
        flat = ShaderProgram(surfaceStage("surface.vert"), surfaceStage("flat.frag"),
                             {{"HFX_SHADOW_MAP", std::to_string(received)}});
    // (No motion: an engine draws its own meshes. A caster writes no colour: an engine's shadow
    // map may have a colour attachment.)
    const DrawBuffersWritten written(camera ? 1u : 0u);
    SurfaceUniforms u;
    if (camera) setEye(u, *camera);
    u.linearOutput = writesLinear(colorOutput_) ? 1 : 0;
    if (light) {
        u.lightDir = glm::normalize(light->direction);
        u.lightColor = light->color;
        u.ambient = light->ambient;
    }
    bindUniforms(u, model, viewProj);
    flat.set("u_color", color);
    flat.set("u_flatLit", light ? 1 : 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(reversedZ ? GL_GREATER : GL_LESS);
    flat.use();
    mesh.draw();
}

} // namespace hfx
