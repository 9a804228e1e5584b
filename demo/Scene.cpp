#include "Scene.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/tools/ImageFiles.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

namespace hfx::demo {

CameraOrbit::CameraOrbit(const Camera& c) {
    const glm::vec3 d = c.position - c.target;
    distance = glm::length(d);
    elevation = std::asin(std::clamp(d.y / distance, -1.0f, 1.0f));
    azimuth = std::atan2(d.x, d.z);
}

void CameraOrbit::apply(Camera& c) const {
    c.position = Camera::orbit(c.target, distance, azimuth, elevation).position;
}

void Scene::turnCamera(float degrees) {
    CameraOrbit orbit(camera_);
    orbit.azimuth += glm::radians(degrees);
    orbit.apply(camera_);
}

void Scene::followPath(double seconds) {
    if (!cameraPath) return;
    cameraPath->apply(seconds, options); // the path's values only: the rest stay as made
    placeCamera(options);
}

void Scene::placeCamera(const SceneOptions& o) {
    if (!o.cameraAzimuth && !o.cameraElevation && !o.cameraDistance && !o.cameraTarget) return; // the scene's, to the bit
    CameraOrbit orbit(camera_);
    if (o.cameraTarget) camera_.target = *o.cameraTarget;
    if (o.cameraAzimuth) orbit.azimuth = glm::radians(*o.cameraAzimuth);
    if (o.cameraElevation) orbit.elevation = glm::radians(*o.cameraElevation);
    if (o.cameraDistance) orbit.distance = *o.cameraDistance;
    orbit.apply(camera_);
}

std::string Scene::cameraLabel() const {
    const CameraOrbit orbit(camera_);
    char label[256];
    std::snprintf(label, sizeof label,
                  "azimuth %.1f, elevation %.1f degrees, distance %.2f from its target (%.2f, %.2f, %.2f) "
                  "(--camera-azimuth, --camera-elevation, --camera-distance, --camera-target)",
                  double(glm::degrees(orbit.azimuth) + 0.0f), double(glm::degrees(orbit.elevation) + 0.0f), // no -0
                  double(orbit.distance), double(camera_.target.x + 0.0f), double(camera_.target.y + 0.0f),
                  double(camera_.target.z + 0.0f));
    return label;
}

void Scene::applyOptions(const SceneOptions& o) {
    SurfaceMaterial m = effect().material();
    if (o.depthScale > 0.0f) m.depthScale = o.depthScale;
    if (o.minSamples > 0) m.minSamples = o.minSamples;
    if (o.maxSamples > 0) m.maxSamples = o.maxSamples;
    if (m.maxSamples < m.minSamples) m.maxSamples = m.minSamples;
    m.shadows = o.shadows;
    m.lodThreshold = o.lodThreshold;
    if (o.pixelBudget >= 0.0f) m.pixelBudget = o.pixelBudget;
    effect().setMaterial(m);
    technique = o.technique;
    texelShadows = o.texelShadows;
    beamStart = o.beamStart;
    deferShadowWalks = o.deferShadowWalks;
    tracePass = o.tracePass;
}

namespace {

/// A decided trial: "the draw (auto: 3.37 ms, a compute pass 7.30 ms)".
std::string trialLabel(const TracePassTrialReport& trial) {
    const bool computed = trial.chosen == TracePass::Compute;
    char label[128];
    std::snprintf(label, sizeof label, "%s (auto: %.2f ms, %s %.2f ms)", computed ? "a compute pass" : "the draw",
                  computed ? trial.computeMs : trial.inDrawMs, computed ? "the draw" : "a compute pass",
                  computed ? trial.inDrawMs : trial.computeMs);
    return label;
}

} // namespace

std::string Scene::tracePassLabel() const {
    if (technique != Technique::Hierarchical) return "";
    std::string label = trial_.decided() ? trialLabel(trial_) : traced_.computeTrace ? "a compute pass" : "the draw";
    if (casterTrial_.decided()) label += "; its shadow map's, " + trialLabel(casterTrial_);
    return label;
}

std::string Scene::texelShadowsLabel() const {
    if (traced_.texelStride == 0) return "off";
    return traced_.texelStride > 1 ? str("on, stride ", traced_.texelStride) : "on";
}

void Scene::drawInto(const RenderTarget& target, const glm::vec4& background) {
    if (orthographic) { // the lens's frame at the target, parallel (the camera may have moved)
        const float h = glm::length(camera_.target - camera_.position) * std::tan(0.5f * camera_.fovY),
                    w = h * camera_.aspect, n = camera_.nearPlane, f = camera_.farPlane;
        camera_.customProjection = camera_.reversedZ ? glm::orthoRH_ZO(-w, w, -h, h, f, n) : glm::ortho(-w, w, -h, h, n, f);
    }
    const bool reversed = camera_.reversedZ;
    target.clear(background, {}, reversed ? 0.0f : 1.0f);
    struct ClipDepth { // GL_ZERO_TO_ONE while a reversed-Z camera draws, also when it throws
        bool set;
        explicit ClipDepth(bool s) : set(s) {
            if (set) glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        }
        ~ClipDepth() {
            if (set) glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        }
    } clip(reversed);
    draw();
}

void Scene::drawSurface(SurfaceRenderer& renderer, const DirectionalLight& light) {
    const std::vector<SurfaceLayer> layers = effect().layers();
    renderer.draw(mesh(), model(), layers, effect().material(), camera_, light, drawOptions());
    traced_ = technique == Technique::Hierarchical ? renderer.tracer().last() : TracerFrame{};
    trial_ = renderer.tracer().passTrial(mesh(), false);
    casterTrial_ = renderer.tracer().passTrial(mesh(), true); // where the scene casts it (the decal wall)
    tracerMemory_ = renderer.tracer().memory();
    if (wireframe) {
        glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        renderer.drawFlat(mesh(), model(), camera_, {0.1f, 1.0f, 0.3f, 1.0f});
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    }
}

ImpactScene::ImpactScene(const SceneOptions& o) : width_(o.width), height_(o.height) {
    if (!o.shots.empty()) shots_ = readShotList(o.shots);
}

void ImpactScene::prepare(double /*dt*/) {
    // As the decal scene: frame 0 is drawn before any update, so shots at 0 land with frame 1.
    ++frame_;
    for (const Shot& shot : shots_)
        if (shot.frame == frame_ || (frame_ == 1 && shot.frame == 0)) {
            if (shot.a < 0 || shot.b < 0 || shot.a >= width_ || shot.b >= height_)
                throw Error(str("shot list line ", shot.line, ": (", shot.a, ", ", shot.b, ") is outside the ", width_,
                                "x", height_, " image (", name(), " shots are pixels)"));
            fire(shot.kind == Shot::Kind::Explosion ? ImpactKind::Explosion : ImpactKind::Bullet, shot.a, shot.b,
                 width_, height_, shot.seed);
        }
}

void ImpactScene::fire(ImpactKind kind, double x, double y, int width, int height, std::uint64_t seed) {
    const Ray ray = camera_.rayThroughPixel(x, height - y, width, height);
    ImpactReceiver* targets[] = {&receiver()};
    if (const auto hit = routeImpact({.origin = ray.origin, .direction = ray.direction, .kind = kind, .seed = seed}, targets))
        std::printf("impact: %s at (%.3f, %.3f, %.3f) on the %s\n", impactKindName(kind), hit->hit.world.x,
                    hit->hit.world.y, hit->hit.world.z, targets[hit->receiver]->name());
}

Technique defaultTechnique(const std::string& scene, const SceneOptions& o) {
    if (scene == "water" || o.surfaceFormat == SurfaceFormat::Unorm8) return Technique::ParallaxOcclusion;
    auto powerOfTwo = [](int n) { return n > 0 && std::has_single_bit(unsigned(n)); };
    if (o.fieldSize > 0 && (!powerOfTwo(o.fieldSize) || (scene == "planet" && !powerOfTwo(std::max(4, o.fieldSize / 2)))))
        return Technique::ParallaxOcclusion;
    if (scene == "maps" && o.heightMap.empty()) return Technique::ParallaxOcclusion; // a normal map alone
    if ((scene == "maps" || scene == "decals") && !o.heightMap.empty()) {
        const ImageSize size = readImageSize(o.heightMap);
        if (!powerOfTwo(size.width) || !powerOfTwo(size.height)) return Technique::ParallaxOcclusion;
    }
    return Technique::Hierarchical;
}

std::vector<std::string> listedNames(std::string_view list) {
    std::vector<std::string> names;
    for (size_t at = 0; at < list.size();) {
        const size_t comma = std::min(list.find(", ", at), list.size());
        names.emplace_back(list.substr(at, comma - at));
        at = comma + 2;
    }
    return names;
}

bool isSceneName(std::string_view name) {
    const std::vector<std::string> scenes = listedNames(kSceneNames);
    return std::find(scenes.begin(), scenes.end(), name) != scenes.end();
}

std::unique_ptr<Scene> makeScene(const std::string& name, ClContext& cl, const SceneOptions& options) {
    std::unique_ptr<Scene> scene = name == "water"    ? makeWaterScene(cl, options)
                                   : name == "decals" ? makeDecalScene(cl, options)
                                   : name == "planet" ? makePlanetScene(cl, options)
                                   : name == "maps"   ? makeMapsScene(cl, options)
                                   : name == "noise"  ? makeNoiseScene(cl, options)
                                                      : nullptr;
    if (!scene) throw Error(str("unknown scene '", name, "' (known scenes: ", kSceneNames, ", bench)"));
    scene->placeCamera(options);
    scene->options = options;
    scene->cameraTurn = options.cameraTurn;
    scene->camera().reversedZ = options.reversedZ;
    scene->orthographic = options.orthographic;
    return scene;
}

} // namespace hfx::demo
