// A surface from image files (height, optional normal and colour maps) on a plane.

#include "Scene.h"

#include "hfx/tools/ImageFiles.h"

#include "hfx/core/Error.h"
#include "hfx/effects/ImageSurface.h"

namespace hfx::demo {
namespace {

/// The plane the surface repeats on, twice each way.
constexpr PlaneConfig kPlane{.size = 4.0f, .texcoordScale = 2.0f, .subdivisions = 1};

class MapsScene final : public Scene {
public:
    MapsScene(ClContext& cl, const SceneOptions& o)
        : surface_(cl, config(o)), plane_(makePlane(kPlane)) {
        applyOptions(o);
        camera_ = Camera::orbit({0.0f, 0.0f, 0.0f}, 4.2f, 0.5f, 0.55f);
        camera_.aspect = o.aspect();
        light_.direction = {-1.0f, 0.45f, -0.3f};
    }

    void draw() override { drawSurface(renderer_, light_); }
    Effect& effect() override { return surface_; }
    const char* name() const override { return "maps"; }
    const Mesh& mesh() const override { return plane_; }

private:
    static ImageSurfaceConfig config(const SceneOptions& o) {
        if (o.heightMap.empty()) throw Error("the maps scene needs --height-map FILE");
        ImageSurfaceConfig c{.maps = readSurfaceMaps(o.heightMap, o.normalMap, o.colorMap)};
        if (o.depthScale > 0.0f) c.material.depthScale = o.depthScale;
        c.surface = o.surfaceOptions();
        return c;
    }

    ImageSurface surface_;
    Mesh plane_;
    DirectionalLight light_;
    SurfaceRenderer renderer_;
};

} // namespace

std::unique_ptr<Scene> makeMapsScene(ClContext& cl, const SceneOptions& options) {
    return std::make_unique<MapsScene>(cl, options);
}

} // namespace hfx::demo
