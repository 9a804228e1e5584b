// The procedural-water user: the FFT ocean (or the cheap directional sine waves) on a large
// plane seen low over the water towards a low sun, shaded as water.

#include "Scene.h"

#include "hfx/core/Error.h"
#include "hfx/core/Image.h"
#include "hfx/effects/OceanEffect.h"
#include "hfx/effects/SineWavesEffect.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace hfx::demo {
namespace {

constexpr PlaneConfig kPlane{.size = 48.0f, .texcoordScale = 6.0f, .subdivisions = 1};

class WaterScene final : public Scene {
public:
    WaterScene(ClContext& cl, const SceneOptions& o) : plane_(makePlane(kPlane)), wind_(o.windSpeed), windDir_(o.windDirection) {
        if (o.waves != "fft" && o.waves != "sine")
            throw Error(str("unknown waves '", o.waves, "' (expected fft or sine)"));
        if (!o.environment.empty()) {
            const Image sky = readImage(o.environment);
            environment_ = makeEnvironment(sky);
        }
        if (o.waves == "fft") {
            OceanEffectConfig c;
            c.ocean.size = o.fieldSize > 0 ? o.fieldSize : 512;
            c.ocean.seed = o.seed;
            c.ocean.windSpeed = o.windSpeed;
            c.ocean.windDirection = o.windDirection;
            c.surface = o.surfaceOptions();
            ocean_ = std::make_unique<OceanEffect>(cl, c);
        } else {
            SineWavesConfig c;
            c.waves.size = o.fieldSize > 0 ? o.fieldSize : 512;
            c.waves.seed = o.seed;
            c.waves.maxCycles = std::min(20, c.waves.size / 2);
            c.waves.minCycles = std::min(c.waves.minCycles, c.waves.maxCycles);
            c.material.shading = Shading::Water;
            c.material.specularStrength = 0.0f;
            c.surface = o.surfaceOptions();
            sine_ = std::make_unique<SineWavesEffect>(cl, c);
        }
        SurfaceMaterial m = effect().material();
        m.water.environment = environment_.id();
        effect().setMaterial(m);
        applyOptions(o);
        camera_.position = {0.0f, 2.4f, 6.0f};
        camera_.target = {0.0f, 0.0f, -4.0f};
        camera_.aspect = o.aspect();
        camera_.farPlane = 200.0f;
        light_.direction = {-0.35f, 0.22f, -1.0f};
        light_.color = {1.0f, 0.9f, 0.75f};
        light_.ambient = {0.35f, 0.42f, 0.5f};
    }

    void draw() override { drawSurface(renderer_, light_); }
    Effect& effect() override {
        if (ocean_) return *ocean_;
        return *sine_;
    }
    const char* name() const override { return "water"; }
    const Mesh& mesh() const override { return plane_; }

    void panel() override {
        if (!ocean_) return;
        bool changed = ImGui::SliderFloat("wind speed (m/s)", &wind_, 1.0f, 30.0f);
        changed |= ImGui::SliderAngle("wind direction", &windDir_, -180.0f, 180.0f);
        if (changed) ocean_->setWind(wind_, windDir_); // the sea's new depth is in the ocean's material
    }

private:
    static GlTexture makeEnvironment(const Image& sky) {
        GlTexture t = GlTexture::create();
        std::vector<float> rgb(size_t(sky.width) * sky.height * 3);
        for (int y = 0; y < sky.height; ++y)
            for (int x = 0; x < sky.width; ++x)
                for (int c = 0; c < 3; ++c)
                    // Rows bottom first for GL; grey images fill all three channels.
                    rgb[(size_t(sky.height - 1 - y) * sky.width + x) * 3 + c] = sky.at(x, y, std::min(c, sky.channels - 1));
        glTextureStorage2D(t.id(), 1, GL_RGB32F, sky.width, sky.height);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTextureSubImage2D(t.id(), 0, 0, 0, sky.width, sky.height, GL_RGB, GL_FLOAT, rgb.data());
        glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        return t;
    }

    std::unique_ptr<OceanEffect> ocean_;
    std::unique_ptr<SineWavesEffect> sine_;
    GlTexture environment_;
    Mesh plane_;
    DirectionalLight light_;
    SurfaceRenderer renderer_;
    float wind_, windDir_;
};

} // namespace

std::unique_ptr<Scene> makeWaterScene(ClContext& cl, const SceneOptions& options) {
    return std::make_unique<WaterScene>(cl, options);
}

} // namespace hfx::demo
