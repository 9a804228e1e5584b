// The procedural-water user: the FFT ocean (or the cheap directional sine waves) on a plane of
// open sea, 8 km across in metres, seen from a few metres up towards a low sun, shaded as water;
// the plane's texcoords count the effect's patches (the ocean's largest cascade).

#include "Scene.h"

#include "hfx/core/Error.h"
#include "hfx/tools/ImageFiles.h"
#include "hfx/effects/OceanEffect.h"
#include "hfx/effects/SineWavesEffect.h"
#include "hfx/effects/Sky.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace hfx::demo {
namespace {

constexpr float kSeaMeters = 8000.0f;
/// The clouds' layer over the sea, and how much faster than the wind at 10 m it moves.
constexpr float kCloudHeightMeters = 1500.0f, kWindAloft = 2.0f;

/// The sky's weather at a wind of `u10` m/s: fair-weather cumulus over 0.4 of the sky up to a
/// strong breeze (the middle of Beaufort 6), clouding over to 0.95 at a storm (Beaufort 10) and
/// beyond, where a veil over the deck greys its gaps (hfx::cloudVeil, from a cover of 0.7,
/// between Beaufort 8 and 9); the haze half the colour at 2,500 m up to a gale (Beaufort 8), its
/// spray thickening it to 1,200 m at a storm and 600 m at the most (the scale's own words: "spray
/// may affect visibility" at 9, "visibility affected" at 10).
struct Weather {
    float cloudCover, hazeDistance;
};
Weather weatherAt(float u10) {
    const float overcast = std::clamp((u10 - beaufortWindSpeed(6)) / (beaufortWindSpeed(10) - beaufortWindSpeed(6)), 0.0f, 1.0f);
    const float spray = std::max((u10 - beaufortWindSpeed(8)) / (beaufortWindSpeed(10) - beaufortWindSpeed(8)), 0.0f);
    return {0.4f + 0.55f * overcast, std::max(2500.0f - 1300.0f * spray, 600.0f)};
}
/// Where the default camera (7 m up, 8 degrees down, along -z) looks at the sea: the clouds' layer
/// starts with the sun out there (sunnyDrift).
constexpr glm::vec3 kSunnySpot{0.0f, 0.0f, -50.0f};
/// Seconds the sky takes to settle two thirds of the way to a new wind's weather (the waves
/// blend over four: OceanEffect::setWind).
constexpr float kWeatherSeconds = 1.3f;

/// The sea state the options describe: a Beaufort force, or a wind speed; fetch, spectrum,
/// spreading, depth and swell as given.
OceanEffectConfig oceanConfig(const SceneOptions& o) {
    OceanEffectConfig c;
    if (o.fieldSize > 0) c.ocean.size = o.fieldSize;
    if (o.cascades > 0) c.ocean.cascades = o.cascades;
    // Smaller cascades cannot take the default ratio between lengths (size / 48 at most): one
    // cascade, unless asked otherwise.
    else if (c.ocean.size < 256) c.ocean.cascades = 1;
    c.ocean.seed = o.seed;
    c.ocean.choppiness = o.choppiness;
    WaveSpectrum& wind = c.ocean.sea.wind;
    wind.windSpeed = o.beaufort >= 0 ? beaufortWindSpeed(o.beaufort) : o.windSpeed;
    wind.direction = o.windDirection;
    wind.fetchKm = o.fetchKm;
    wind.shape = parseSpectrumShape(o.spectrum.c_str());
    wind.spreading = parseSpreading(o.spreading.c_str());
    c.ocean.sea.depthMeters = o.depthMeters;
    c.ocean.sea.swell.energy = o.swell;
    c.ocean.sea.swell.direction = o.windDirection + 0.9f;
    // hier traces one grid: the ocean then runs one cascade. More, asked for by --cascades, are
    // refused by name rather than drawn as one.
    c.surface = o.surfaceOptions();
    if (o.technique == Technique::Hierarchical) {
        if (o.cascades > 1)
            throw Error(str("--cascades ", o.cascades, ": the hier technique traces one grid and the ocean's cascades "
                            "are one each (--technique pom draws them, or --cascades 1)"));
        c.ocean.cascades = 1;
    }
    return c;
}

class WaterScene final : public ImpactScene {
public:
    WaterScene(ClContext& cl, const SceneOptions& o)
        : ImpactScene(o), wind_(o.windSpeed), windDir_(o.windDirection) {
        if (o.waves != "fft" && o.waves != "sine")
            throw Error(str("unknown waves '", o.waves, "' (expected fft or sine)"));
        if (!o.environment.empty()) {
            const Image sky = readImage(o.environment);
            environment_ = makeEnvironment(sky);
        }
        float patch = 0.0f; // metres per texcoord unit
        if (o.waves == "fft") {
            ocean_ = std::make_unique<OceanEffect>(cl, oceanConfig(o));
            if (o.foamHistory > 0.0f) ocean_->settleFoam(o.foamHistory);
            patch = ocean_->ocean().config().patchMeters;
            wind_ = ocean_->ocean().config().sea.wind.windSpeed;
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
            patch = c.waves.patchMeters;
        }
        const PlaneConfig sea{.size = kSeaMeters, .texcoordScale = kSeaMeters / patch, .subdivisions = 1};
        plane_ = Mesh(makePlane(sea));
        if (ocean_) impacts_ = std::make_unique<OceanImpacts>(*ocean_, SurfaceFrame::ofPlane(sea));
        // A low sun ahead (first: where the clouds start depends on it, sunnyDrift).
        light_.direction = {-0.35f, 0.22f, -1.0f};
        light_.color = {1.0f, 0.9f, 0.75f};
        light_.ambient = {0.35f, 0.42f, 0.5f};
        SurfaceMaterial m = effect().material();
        m.water.environment = environment_.id();
        // The wind's weather: its haze (metres), and its clouds unless --clouds holds them.
        // Cumulus about a kilometre across at 1.5 km (an environment image is the whole sky: a
        // cover asked for with one is refused by name).
        const Weather weather = weatherAt(wind_);
        cloudsFollowWind_ = o.clouds < 0.0f && o.environment.empty();
        m.water.hazeDistance = weather.hazeDistance;
        m.water.cloudCover = o.clouds >= 0.0f ? o.clouds : cloudsFollowWind_ ? weather.cloudCover : 0.0f;
        m.water.cloudHeight = kCloudHeightMeters;
        m.water.cloudScale = kCloudHeightMeters / 1000.0f;
        m.water.cloudDrift = sunnyDrift(m.water); // the sun out where the default view looks
        effect().setMaterial(m);
        applyOptions(o);
        // Seven metres above the water unless told, looking down (8 degrees unless told) towards
        // the low sun.
        stand(o.cameraHeight, o.cameraPitch);
        camera_.aspect = o.aspect();
        camera_.nearPlane = 0.2f;
        camera_.farPlane = 12000.0f;
    }

    /// --camera-azimuth turns the way the camera looks about the vertical (0: along -z, towards the
    /// low sun); it keeps its place above the sea and its pitch, unless a camera path moves them
    /// (--camera-height and --camera-pitch place the camera when the scene is made).
    /// The other placements are refused by name (their options' labels leave the water out).
    void placeCamera(const SceneOptions& o) override {
        const bool moved = o.cameraHeight != camera_.position.y || o.cameraPitch != pitch_;
        if (!moved && !o.cameraAzimuth) return; // the scene's, to the bit
        const float azimuth = o.cameraAzimuth ? glm::radians(*o.cameraAzimuth) : lookAzimuth();
        if (moved) stand(o.cameraHeight, o.cameraPitch);
        look(azimuth);
    }

    /// Stands `height` metres above the sea at the origin, looking `pitch` degrees below the
    /// horizon along -z (look turns it).
    void stand(float height, float pitch) {
        pitch_ = pitch;
        camera_.position = {0.0f, height, 0.0f};
        camera_.target = camera_.position + glm::vec3(0.0f, -100.0f * std::tan(glm::radians(pitch)), -100.0f);
    }
    /// On the spot: the way it looks turns, its place and pitch stay.
    void turnCamera(float degrees) override { look(lookAzimuth() + glm::radians(degrees)); }

    /// The way the camera looks, radians about the vertical (0 along -z).
    float lookAzimuth() const {
        const glm::vec3 d = camera_.target - camera_.position;
        return std::atan2(-d.x, -d.z);
    }

    /// Looks along `azimuth` (radians about the vertical, 0 along -z) at the pitch it has.
    void look(float azimuth) {
        const float ahead = glm::length(camera_.target - camera_.position);
        const glm::vec3 d = glm::normalize(camera_.target - camera_.position);
        const float horizontal = std::sqrt(std::max(0.0f, 1.0f - d.y * d.y));
        camera_.target = camera_.position + ahead * glm::vec3(-std::sin(azimuth) * horizontal, d.y,
                                                              -std::cos(azimuth) * horizontal);
    }

    std::string cameraLabel() const override {
        const glm::vec3 view = glm::normalize(camera_.target - camera_.position);
        float azimuth = glm::degrees(lookAzimuth());
        azimuth = azimuth < -179.95f ? azimuth + 360.0f : azimuth + 0.0f; // (-180, 180], no -0
        char label[160];
        std::snprintf(label, sizeof label,
                      "azimuth %.1f degrees (looking along -z at 0), %.1f below the horizon, %.0f m above the sea "
                      "(--camera-azimuth, --camera-pitch)",
                      double(azimuth), double(glm::degrees(std::asin(-view.y))),
                      double(camera_.position.y));
        return label;
    }

    std::string sceneLabel() const override {
        const WaterLook& look = (ocean_ ? static_cast<const Effect&>(*ocean_) : *sine_).material().water;
        // An overcast deck's veil over its gaps (hfx::cloudVeil), where there is one.
        char veil[64] = "";
        if (const float v = cloudVeil(look); v > 0.0f)
            std::snprintf(veil, sizeof veil, ", a veil over %.2f of their gaps", double(v));
        // The seconds of wind the foam has seen, told before the first frame (a clear start: none).
        char foam[96] = "";
        if (ocean_)
            std::snprintf(foam, sizeof foam, "; the first frame's foam had %.0f s of this wind behind it (--foam-history)",
                          ocean_->foamSeconds());
        char label[320];
        std::snprintf(label, sizeof label, "weather: clouds over %.2f of the sky (%s)%s, haze half the colour at %.0f m%s",
                      double(look.cloudCover),
                      cloudsFollowWind_ ? "the wind's: --clouds sets them"
                                        : look.environment ? "an environment image" : "--clouds",
                      veil, double(look.hazeDistance), foam);
        return label;
    }

    /// The sky settles towards the wind's weather (a new wind from the panel), and the clouds drift
    /// downwind with the wind aloft (the texcoords' v runs along -z on the plane).
    void prepare(double dt) override {
        ImpactScene::prepare(dt); // this frame's shots
        SurfaceMaterial m = effect().material();
        const Weather weather = weatherAt(wind_);
        const float settle = 1.0f - std::exp(-float(dt) / kWeatherSeconds);
        m.water.hazeDistance += (weather.hazeDistance - m.water.hazeDistance) * settle;
        if (cloudsFollowWind_) m.water.cloudCover += (weather.cloudCover - m.water.cloudCover) * settle;
        const float speed = kWindAloft * wind_ / kCloudHeightMeters; // cloud heights per second
        if (m.water.cloudCover > 0.0f) m.water.cloudDrift -= float(dt) * speed * downwind();
        if (!(m == effect().material())) effect().setMaterial(m);
    }

    /// The way the wind blows over the layer (world x, z); the drift, read as p + drift, falls
    /// along it, so the clouds move downwind.
    glm::vec2 downwind() const { return {std::cos(windDir_), -std::sin(windDir_)}; }

    /// Where the clouds' layer starts (WaterLook::cloudDrift): the first drift downwind, in steps
    /// of a tenth of a cloud height (150 m), that leaves kSunnySpot in full sun, or the sunniest of
    /// 64 such steps (an overcast deck has no gap). The layer drifts from there, so the default
    /// view's first frames show the waves in the sun rather than a cloud's shadow by chance; the
    /// start depends on the weather, the wind and the sun, not on the camera, so every camera
    /// sees the same sky.
    glm::vec2 sunnyDrift(WaterLook look) const {
        if (!(look.cloudCover > 0.0f)) return look.cloudDrift;
        glm::vec2 best = look.cloudDrift;
        float sunniest = -1.0f;
        for (int k = 0; k < 64 && sunniest < 0.999f; ++k) {
            look.cloudDrift = -0.1f * float(k) * downwind();
            if (const float sun = cloudSunlight(look, light_, kSunnySpot, 1.0f); sun > sunniest) {
                sunniest = sun;
                best = look.cloudDrift;
            }
        }
        return best;
    }

    void draw() override {
        renderer_.drawSky(camera_, light_, effect().material().water);
        drawSurface(renderer_, light_);
    }
    Effect& effect() override {
        if (ocean_) return *ocean_;
        return *sine_;
    }
    const char* name() const override { return "water"; }
    const Mesh& mesh() const override { return plane_; }

    void panel() override {
        if (!ocean_) return;
        // Beaufort presets: the middle of each force's wind; the slider shows the force it is in.
        static constexpr const char* kForces[] = {"0 calm", "1 light air", "2 light breeze", "3 gentle breeze",
                                                  "4 moderate breeze", "5 fresh breeze", "6 strong breeze",
                                                  "7 near gale", "8 gale", "9 strong gale", "10 storm",
                                                  "11 violent storm", "12 hurricane"};
        int force = 0;
        while (force < 12 && beaufortWindSpeed(force + 1) - 0.5f * (beaufortWindSpeed(force + 1) - beaufortWindSpeed(force)) <= wind_)
            ++force;
        bool changed = false;
        if (ImGui::Combo("Beaufort", &force, kForces, IM_ARRAYSIZE(kForces))) {
            wind_ = beaufortWindSpeed(force);
            changed = true;
        }
        changed |= ImGui::SliderFloat("wind speed (m/s)", &wind_, 0.5f, 40.0f);
        changed |= ImGui::SliderAngle("wind direction", &windDir_, -180.0f, 180.0f);
        if (changed) ocean_->setWind(wind_, windDir_); // the sea's new depth is in the ocean's material
        SurfaceMaterial m = effect().material();
        // The slider holds the clouds where it leaves them; the wind's weather moves them again
        // from the next change of wind.
        if (m.water.environment == 0 && ImGui::SliderFloat("clouds", &m.water.cloudCover, 0.0f, 1.0f)) {
            effect().setMaterial(m);
            cloudsFollowWind_ = false;
        }
        if (changed) cloudsFollowWind_ = m.water.environment == 0;
        const OceanField& sea = ocean_->ocean();
        double variance = 0.0;
        for (int i = 0; i < sea.cascadeCount(); ++i) variance += double(sea.cascade(i).sigma) * sea.cascade(i).sigma;
        ImGui::Text("Hs %.2f m (4 sigma), %d cascades of %d^2, %.0f m patch", 4.0 * std::sqrt(variance),
                    sea.cascadeCount(), sea.config().size, double(sea.config().patchMeters));
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

    ImpactReceiver& receiver() override {
        if (!impacts_) throw Error("the sine waves take no impacts (--waves fft does)");
        return *impacts_;
    }

    std::unique_ptr<OceanEffect> ocean_;
    std::unique_ptr<SineWavesEffect> sine_;
    std::unique_ptr<OceanImpacts> impacts_;
    GlTexture environment_;
    Mesh plane_;
    DirectionalLight light_;
    SurfaceRenderer renderer_;
    float wind_, windDir_;
    bool cloudsFollowWind_ = true; ///< the clouds are the wind's weather (not --clouds, the slider or an environment)
    float pitch_ = 0.0f; ///< degrees the camera looks below the horizon (placeCamera)
};

} // namespace

std::unique_ptr<Scene> makeWaterScene(ClContext& cl, const SceneOptions& options) {
    return std::make_unique<WaterScene>(cl, options);
}

} // namespace hfx::demo
