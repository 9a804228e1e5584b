#pragma once
// A scene of the demo: the smallest complete use of one effect of the module.

#include "hfx/compute/ClContext.h"
#include "hfx/core/Camera.h"
#include "hfx/effects/Effect.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <cstdint>
#include <memory>
#include <string>

namespace hfx::demo {

struct SceneOptions {
    int fieldSize = 512;
    Technique technique = Technique::ParallaxOcclusion;
    int minSamples = 8;
    int maxSamples = 50;
    float depthScale = 0.06f;
    bool shadows = true;
    std::uint32_t seed = 1;
    float aspect = 16.0f / 9.0f;
    std::string heightMap, normalMap, colorMap; ///< the maps scene's files
};

class Scene {
public:
    virtual ~Scene() = default;
    virtual void update(double dt) = 0;
    /// Draws into the bound framebuffer (depth test on, viewport set by the caller).
    virtual void draw() = 0;
    virtual Effect& effect() = 0;
    virtual Camera& camera() = 0;
};

/// The known scene names, for help texts and errors.
inline constexpr const char* kSceneNames = "water, maps";

std::unique_ptr<Scene> makeWaterScene(ClContext& cl, const SceneOptions& options);
std::unique_ptr<Scene> makeMapsScene(ClContext& cl, const SceneOptions& options);
/// Throws hfx::Error naming the scene and listing the known ones.
std::unique_ptr<Scene> makeScene(const std::string& name, ClContext& cl, const SceneOptions& options);

} // namespace hfx::demo
