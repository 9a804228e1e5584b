#include "Scene.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"

namespace hfx::demo {

void Scene::applyOptions(const SceneOptions& o) {
    SurfaceMaterial m = effect().material();
    if (o.depthScale > 0.0f) m.depthScale = o.depthScale;
    if (o.minSamples > 0) m.minSamples = o.minSamples;
    if (o.maxSamples > 0) m.maxSamples = o.maxSamples;
    if (m.maxSamples < m.minSamples) m.maxSamples = m.minSamples;
    m.shadows = o.shadows;
    m.lodThreshold = o.lodThreshold;
    effect().setMaterial(m);
    technique = o.technique;
}

void Scene::drawSurface(SurfaceRenderer& renderer, const DirectionalLight& light) {
    const std::vector<SurfaceLayer> layers = effect().layers();
    renderer.draw(mesh(), model(), layers, effect().material(), camera_, light, {.technique = technique});
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
