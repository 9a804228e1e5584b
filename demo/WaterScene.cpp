#include "Scene.h"

#include "hfx/core/Error.h"
#include "hfx/core/Mesh.h"
#include "hfx/effects/WaterEffect.h"

#include <glm/mat4x4.hpp>

namespace hfx::demo {
namespace {

class WaterScene final : public Scene {
public:
    WaterScene(ClContext& cl, const SceneOptions& o)
        : options_(o), water_(cl, config(o)),
          plane_(makePlane({.size = 48.0f, .texcoordScale = 6.0f, .subdivisions = 1})) {
        // Low over the water, looking towards a low sun: grazing views are where POM shows.
        camera_.position = {0.0f, 2.4f, 6.0f};
        camera_.target = {0.0f, 0.0f, -4.0f};
        camera_.aspect = o.aspect;
        camera_.farPlane = 200.0f;
        light_.direction = {-0.35f, 0.3f, -1.0f};
        light_.color = {1.0f, 0.92f, 0.8f};
        light_.ambient = {0.25f, 0.32f, 0.4f};
    }

    void update(double dt) override { water_.update(dt); }
    void draw() override {
        renderer_.draw(plane_, glm::mat4(1.0f), water_.textures(), water_.material(), camera_,
                       light_, {.technique = options_.technique});
    }
    Effect& effect() override { return water_; }
    Camera& camera() override { return camera_; }

private:
    static WaterConfig config(const SceneOptions& o) {
        WaterConfig c;
        c.waves.size = o.fieldSize;
        c.waves.seed = o.seed;
        c.waves.maxCycles = std::min(20, o.fieldSize / 2);
        c.waves.minCycles = std::min(c.waves.minCycles, c.waves.maxCycles);
        c.material.depthScale = o.depthScale;
        c.material.minSamples = o.minSamples;
        c.material.maxSamples = o.maxSamples;
        c.material.shadows = o.shadows;
        return c;
    }

    SceneOptions options_;
    WaterEffect water_;
    Mesh plane_;
    Camera camera_;
    DirectionalLight light_;
    SurfaceRenderer renderer_;
};

} // namespace

std::unique_ptr<Scene> makeWaterScene(ClContext& cl, const SceneOptions& options) {
    return std::make_unique<WaterScene>(cl, options);
}

std::unique_ptr<Scene> makeScene(const std::string& name, ClContext& cl, const SceneOptions& options) {
    if (name == "water") return makeWaterScene(cl, options);
    if (name == "maps") return makeMapsScene(cl, options);
    throw Error(str("unknown scene '", name, "' (known scenes: ", kSceneNames, ", bench)"));
}

} // namespace hfx::demo
