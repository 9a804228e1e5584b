#include "Scene.h"

#include "hfx/core/Mesh.h"
#include "hfx/effects/ImageSurface.h"

#include <glm/mat4x4.hpp>

namespace hfx::demo {
namespace {

class MapsScene final : public Scene {
public:
    MapsScene(ClContext& cl, const SceneOptions& o)
        : options_(o), surface_(cl, config(o)),
          plane_(makePlane({.size = 4.0f, .texcoordScale = 2.0f, .subdivisions = 1})) {
        camera_ = Camera::orbit({0.0f, 0.0f, 0.0f}, 4.2f, 0.5f, 0.55f);
        camera_.aspect = o.aspect;
        light_.direction = {-1.0f, 0.45f, -0.3f};
    }

    void update(double dt) override { surface_.update(dt); }
    void draw() override {
        renderer_.draw(plane_, glm::mat4(1.0f), surface_.textures(), surface_.material(), camera_,
                       light_, {.technique = options_.technique});
    }
    Effect& effect() override { return surface_; }
    Camera& camera() override { return camera_; }

private:
    static ImageSurfaceConfig config(const SceneOptions& o) {
        ImageSurfaceConfig c{.heightMap = o.heightMap, .normalMap = o.normalMap, .colorMap = o.colorMap};
        c.material.depthScale = o.depthScale;
        c.material.minSamples = o.minSamples;
        c.material.maxSamples = o.maxSamples;
        c.material.shadows = o.shadows;
        return c;
    }

    SceneOptions options_;
    ImageSurface surface_;
    Mesh plane_;
    Camera camera_;
    DirectionalLight light_;
    SurfaceRenderer renderer_;
};

} // namespace

std::unique_ptr<Scene> makeMapsScene(ClContext& cl, const SceneOptions& options) {
    return std::make_unique<MapsScene>(cl, options);
}

} // namespace hfx::demo
