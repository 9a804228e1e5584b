#include "Scene.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/effects/FieldEffect.h"

namespace hfx::demo {

void Scene::applyMaterial() {
    material_.validate();
    if (auto* field = dynamic_cast<FieldEffect*>(&effect()))
        if (field->material().depthScale != material_.depthScale) field->setDepthScale(material_.depthScale);
}

void Scene::setMaterial(const SurfaceMaterial& base, const SceneOptions& o) {
    material_ = base;
    if (o.depthScale > 0.0f) material_.depthScale = o.depthScale;
    if (o.minSamples > 0) material_.minSamples = o.minSamples;
    if (o.maxSamples > 0) material_.maxSamples = o.maxSamples;
    if (material_.maxSamples < material_.minSamples) material_.maxSamples = material_.minSamples;
    material_.shadows = o.shadows;
    material_.lodThreshold = o.lodThreshold;
    technique = o.technique;
    material_.validate();
}

void Scene::drawSurface(SurfaceRenderer& renderer, const DirectionalLight& light) {
    renderer.draw(mesh(), model(), effect().textures(), material_, camera_, light, {.technique = technique});
    if (wireframe) {
        glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        renderer.drawFlat(mesh(), model(), camera_, {0.1f, 1.0f, 0.3f, 1.0f});
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    }
}

std::unique_ptr<Scene> makeScene(const std::string& name, ClContext& cl, const SceneOptions& options) {
    if (name == "water") return makeWaterScene(cl, options);
    if (name == "decals") return makeDecalScene(cl, options);
    if (name == "planet") return makePlanetScene(cl, options);
    if (name == "maps") return makeMapsScene(cl, options);
    throw Error(str("unknown scene '", name, "' (known scenes: ", kSceneNames, ", bench)"));
}

} // namespace hfx::demo
