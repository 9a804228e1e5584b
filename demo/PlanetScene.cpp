// The gas-planet user: the Navier-Stokes gas on a longitude-latitude grid drives a sphere's
// relief and colour; the planet turns slowly, lit from the side so the terminator crosses it.

#include "Scene.h"

#include "hfx/core/Error.h"
#include "hfx/effects/GasPlanetEffect.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace hfx::demo {
namespace {

/// The planet's sphere, drawn and picked (PlanetImpacts) alike.
constexpr SphereConfig kSphere{.radius = 1.0f, .segments = 128, .rings = 64};

class PlanetScene final : public ImpactScene {
public:
    PlanetScene(ClContext& cl, const SceneOptions& o)
        : ImpactScene(o), planet_(cl, config(o)), sphere_(makeSphere(kSphere)),
          impacts_(planet_, makeSphere(kSphere)) {
        applyOptions(o);
        if (o.spinUp > 0.0f) { // a minute of a 512x256 gas takes seconds on a CPU device: say why the start waits
            const auto start = std::chrono::steady_clock::now();
            planet_.spinUp(o.spinUp);
            cl.queue().finish();
            std::fprintf(stderr, "hfx: planet: %.0f s of weather spun up in %.1f s (--spin-up)\n", double(o.spinUp),
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
        camera_ = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.6f, 0.3f, 0.25f); // --camera-distance: placeCamera
        camera_.aspect = o.aspect();
        light_.direction = {0.95f, 0.15f, -0.2f}; // 83 degrees from the view: the terminator crosses the disc
        // With rings: the sun 25 degrees below their plane (Saturn's reaches 27) and the camera
        // above it, so their shadow lies across the hemisphere in view and their unlit face shows
        // (the dense ring dark, the thin ones glowing with the light they let through).
        if (o.rings) light_.direction = {0.95f, -0.47f, -0.2f};
        light_.color = {1.0f, 0.97f, 0.92f};
        light_.ambient = {0.03f, 0.03f, 0.04f};
    }

    /// The orbit options, then a camera inside the planet's cloud tops refused by name: where it
    /// stands, and with --camera-turn anywhere on the circle it turns round (about the vertical
    /// through its target, which need not be the planet's centre).
    void placeCamera(const SceneOptions& o) override {
        Scene::placeCamera(o);
        constexpr float kNearest = 1.05f; // radii from the centre
        const auto refuse = [](float fromCentre, const char* where) {
            char radii[32];
            std::snprintf(radii, sizeof radii, "%.2f", double(fromCentre));
            throw Error(str("the planet's camera would ", where, " ", radii,
                            " radii from its centre, inside its cloud tops (at least 1.05: --camera-target, "
                            "--camera-distance, --camera-elevation)"));
        };
        const float fromCentre = glm::length(camera_.position);
        if (fromCentre < kNearest) refuse(fromCentre, "stand");
        if (o.cameraTurn == 0.0f) return;
        // The turn's circle: centred above the target, in the horizontal plane through the
        // camera; its nearest point to the planet's centre lies towards the centre's vertical.
        const glm::vec3 offset = camera_.position - camera_.target;
        const float radius = glm::length(glm::vec2(offset.x, offset.z));
        const float targetAcross = glm::length(glm::vec2(camera_.target.x, camera_.target.z));
        const float nearest = std::hypot(camera_.position.y, targetAcross - radius);
        if (nearest < kNearest) refuse(nearest, "pass, turning (--camera-turn),");
    }

    void draw() override {
        drawSurface(renderer_, light_);
        if (planet_.rings()) planet_.rings()->draw(model(), camera_, light_);
    }
    Effect& effect() override { return planet_; }
    const char* name() const override { return "planet"; }
    const Mesh& mesh() const override { return sphere_; }
    glm::mat4 model() const override { return planet_.modelMatrix(); }
    void panel() override {
        if (ImGui::Button("storm")) planet_.addStorm(0.5f, 0.5f, true);
        float scale = planet_.timeScale();
        if (ImGui::SliderFloat("time scale", &scale, 1.0f, 1e4f, "%.0fx", ImGuiSliderFlags_Logarithmic))
            planet_.setTimeScale(scale);
        if (planet_.rings()) { // swing the sun through the rings' plane: their shadow sweeps the disc
            const glm::vec3 d = glm::normalize(light_.direction);
            float elevation = glm::degrees(std::asin(d.y));
            if (ImGui::SliderFloat("sun above the rings", &elevation, -60.0f, 60.0f, "%.0f deg")) {
                const glm::vec2 across = glm::normalize(glm::vec2(d.x, d.z));
                const float e = glm::radians(elevation);
                light_.direction = {across.x * std::cos(e), std::sin(e), across.y * std::cos(e)};
            }
        }
        ImGui::Text("click: a storm there, E: a big one");
    }

private:
    static GasPlanetConfig config(const SceneOptions& o) {
        GasPlanetConfig c;
        // The gas on the device's grid (1024x512 on a GPU), or as wide as asked, with the same
        // weather: its rates scale with the grid (GasPlanetConfig::gridScale).
        if (o.fieldSize > 0 && (o.fieldSize < 32 || o.fieldSize > 2048))
            throw Error(str("planet: --field is the gas's width, 32 to 2048 (", c.gas.width, " its reference), got ",
                            o.fieldSize));
        c.gridScale = o.fieldSize > 0 ? float(o.fieldSize) / float(c.gas.width) : 0.0f;
        c.gas.seed = o.seed;
        c.detail.scale = o.detailScale;
        c.timeScale = o.timeScale;
        c.seed = o.seed;
        c.surface = o.surfaceOptions();
        if (o.rings) c.rings = PlanetRingsConfig{.seed = o.seed};
        return c;
    }

    ImpactReceiver& receiver() override { return impacts_; }

    GasPlanetEffect planet_;
    Mesh sphere_;
    PlanetImpacts impacts_;
    DirectionalLight light_;
    SurfaceRenderer renderer_;
};

} // namespace

std::unique_ptr<Scene> makePlanetScene(ClContext& cl, const SceneOptions& options) {
    return std::make_unique<PlanetScene>(cl, options);
}

} // namespace hfx::demo
