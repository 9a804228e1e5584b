#pragma once
// A scene of the demo: one user of the module (water, decals, planet, or maps from files), with
// its camera and light; the effect owns the material the panel edits. The program loop (main.cpp) owns the context,
// the frame and the UI; a scene only updates its effect and draws.

#include "CameraPath.h"

#include "hfx/compute/ClContext.h"
#include "hfx/core/Camera.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/Effect.h"
#include "hfx/effects/Impacts.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/tools/ShotList.h"

#include <array>
#include <cstdint>
#include <optional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace hfx::demo {

struct SceneOptions {
    int fieldSize = 0;                 ///< 0: the scene's default
    Technique technique = Technique::ParallaxOcclusion;
    int minSamples = 0, maxSamples = 0; ///< 0: the scene's default
    float depthScale = 0.0f;           ///< 0: the scene's default
    bool shadows = true;
    float lodThreshold = 4.0f;
    float pixelBudget = -1.0f;         ///< SurfaceMaterial::pixelBudget (-1: the scene's default)
    /// The texel shadows (DrawOptions::texelShadows: pixels walk their light rays only where a
    /// hard shadow's edge passes between the samples around them): by default wherever the exact
    /// tracer finds they pay on the view (ExactTracer); On draws them always, Off never.
    TexelShadowChoice texelShadows = TexelShadowChoice::Auto;
    /// hier's beam start on flat surfaces (DrawOptions::beamStart): the same hits in shorter walks.
    bool beamStart = true;
    /// The light walks the texel shadows leave done by a pass after the draw
    /// (DrawOptions::deferShadowWalks): the same image.
    bool deferShadowWalks = false;
    /// Where hier walks a convex mesh's rays (DrawOptions::tracePass): the device's by default,
    /// in the draw or in a compute pass between a rays draw and the shading draw.
    TracePass tracePass = TracePass::Auto;
    /// The cameras' depth reversed (Camera::reversedZ), drawn under GL_ZERO_TO_ONE (Scene::drawInto):
    /// how an engine with a reversed depth buffer draws HFX.
    bool reversedZ = false;
    /// The cameras orthographic (Camera::customProjection from glm::ortho, set at each drawInto to
    /// frame at the camera's target what its lens frames there): an editor's or a top-down game's
    /// view, every pixel's ray parallel.
    bool orthographic = false;
    std::uint32_t seed = 1;
    int width = 1280, height = 720;    ///< the image: the cameras' aspect, pixel shots
    float aspect() const { return float(width) / float(height); }
    SurfaceFormat surfaceFormat = SurfaceFormat::Auto; ///< storage of the surface textures
    TransferPath transfer = TransferPath::Auto;        ///< how the surface reaches GL
    /// An effect's surface options: the storage and the path to GL.
    SurfaceOptions surfaceOptions() const { return {.format = surfaceFormat, .transfer = transfer}; }
    std::string waves = "fft";         ///< water: fft (Tessendorf) or sine (directional waves)
    float windSpeed = 10.0f, windDirection = 0.6f; ///< water: U10 (m/s), radians from +x
    int beaufort = -1;                 ///< water: a Beaufort force 0..12 sets the wind (-1: windSpeed)
    float fetchKm = 300.0f;            ///< water: fetch of the wind sea
    std::string spectrum = "jonswap";  ///< water: phillips, pierson-moskowitz, jonswap, tma
    std::string spreading = "donelan-banner"; ///< water: cos2s, hasselmann, donelan-banner
    float depthMeters = 0.0f;          ///< water: sea depth (0: deep)
    float swell = 0.0f;                ///< water: energy of a swell from 50 degrees off the wind (0: none)
    float choppiness = 1.0f;           ///< water: horizontal displacement lambda
    int cascades = 0;                  ///< water: 0: the ocean's default (4)
    float cameraPitch = 8.0f;          ///< water: degrees the camera looks below the horizon
    float cameraHeight = 7.0f;         ///< water: metres the camera stands above the sea
    /// Where the camera stands about the scene's target, each the scene's own where not given
    /// (Scene::placeCamera): degrees about the vertical axis from +z (water: the way it looks, 0
    /// along -z), degrees above the target (not water: its camera stands cameraHeight above the
    /// sea, its pitch is cameraPitch), and the distance (planet: radii from the centre).
    std::optional<float> cameraAzimuth, cameraElevation, cameraDistance;
    /// The point the camera looks at and stands about (not water), the scene's own where not given.
    std::optional<glm::vec3> cameraTarget;
    /// Degrees a second the camera turns about its target (the water's on the spot), in the
    /// frames' time (Scene::turnCamera): a video of the relief's parallax as the view swings. 0: still.
    float cameraTurn = 0.0f;
    float foamHistory = 20.0f;         ///< water: seconds of wind the first frame's foam has seen (0: a clear start)
    int detailScale = 0;               ///< planet: detail texels per gas cell (0: the device's)
    float timeScale = 1.0f;            ///< planet: simulated seconds per second, 1 to 10^4
    float spinUp = 60.0f;              ///< planet: simulated seconds of weather before the first frame
    bool rings = false;                ///< planet: rings (PlanetRings) and their shadows
    std::string heightMap, normalMap, colorMap; ///< maps scene (decals: height and colour)
    std::string shots;                 ///< decals, water, planet: shot list file (decals headless default: a seeded volley)
    std::string environment;           ///< water: equirectangular sky image
    float clouds = -1.0f;              ///< water: the share of the sky under cloud (-1: the wind's weather, none with an environment)
    std::string saveDamage, loadDamage; ///< decals: damage log written after the last frame, read at start
    bool pillar = false;               ///< decals: the bricks on a column (a cylinder) instead of the wall
    // noise: the NoiseField shown (NoiseConfig's fields)
    std::string noiseKind = "perlin", fractal = "fbm", tiling = "wrap";
    int octaves = 5;
    float frequency = 6.0f, lacunarity = 2.0f, gain = 0.5f, warp = 0.0f, noiseSpeed = 0.3f;
    /// noise: > 0 draws the relief on a rounded box with a triplanar mapping (TriplanarMapping::scale,
    /// texcoords per unit) instead of the plane's texcoords
    float triplanar = 0.0f;
};

/// Where a camera stands about its target: the inverse of Camera::orbit (radians; azimuth about
/// the vertical axis from +z, elevation above the target), read from a camera and put back.
struct CameraOrbit {
    explicit CameraOrbit(const Camera& c);
    /// Moves c's position to this orbit about c's target.
    void apply(Camera& c) const;
    float distance, azimuth, elevation;
};

class Scene {
public:
    virtual ~Scene() = default;
    /// Sequential: the next field, computed (stage by stage, see Effect::lastTimes) and
    /// uploaded before this returns.
    void update(double dt) {
        prepare(dt);
        effect().update(dt);
    }
    /// Overlapped: start the next field on the compute device (after the scene's own per-frame
    /// work, prepare()), draw the current one, then endUpdate() to take the new one to GL.
    void beginUpdate(double dt) {
        prepare(dt);
        effect().beginUpdate(dt);
    }
    void endUpdate() { effect().endUpdate(); }
    /// Draws into the bound framebuffer with material() and technique.
    virtual void draw() = 0;
    /// Clears the target for the camera (colour, and depth to its convention's far plane) and
    /// draws the scene under the clip control the camera's depth convention needs (a reversed-Z
    /// camera's GL_ZERO_TO_ONE, GL's default put back after); an orthographic scene's camera gets
    /// its projection for where it is now.
    void drawInto(const RenderTarget& target, const glm::vec4& background);
    virtual Effect& effect() = 0;
    virtual const char* name() const = 0;
    /// What the scene does before each field step (decals: this frame's shots).
    virtual void prepare(double /*dt*/) {}
    /// Scene-specific controls in the UI panel (ImGui), if any.
    virtual void panel() {}
    /// A click at pixel (x, y) from the top-left of a width x height image (decals: a shot).
    virtual void click(double /*x*/, double /*y*/, int /*width*/, int /*height*/) {}
    /// The explosion key at pixel (x, y).
    virtual void explode(double /*x*/, double /*y*/, int /*width*/, int /*height*/) {}
    /// The clear key (decals: forget the damage).
    virtual void clear() {}
    /// After the last frame: writes what the options asked for (the decal scene's damage log).
    virtual void finish() {}
    /// SceneOptions' camera placement over the scene's own (makeScene, after the scene set its
    /// camera): its target moved, then the orbit about it, each only where given.
    virtual void placeCamera(const SceneOptions& options);
    /// Where the camera stands, for the log: "azimuth 65.9, elevation 8.6 degrees, distance 3.40
    /// from its target (--camera-...)".
    virtual std::string cameraLabel() const;
    /// What else the log says of the scene as it starts (the water's weather); empty for nothing.
    virtual std::string sceneLabel() const { return {}; }
    /// Turns the camera `degrees` about the vertical through its target (the water's: on the spot).
    virtual void turnCamera(float degrees);
    /// SceneOptions::cameraTurn, degrees a second: the program loops call turnCamera with it.
    float cameraTurn = 0.0f;
    /// --camera-path: the program loops call followPath with the frames' time.
    std::optional<CameraPath> cameraPath;
    /// Places the camera where cameraPath has it at `seconds`: the path's values written into
    /// `options`, then placeCamera; nothing without a path.
    void followPath(double seconds);
    /// The options the scene was made with (makeScene), the camera path's values since the last
    /// followPath.
    SceneOptions options;

    Camera& camera() { return camera_; }
    /// SceneOptions::orthographic: drawInto gives the camera an orthographic projection.
    bool orthographic = false;
    Technique technique = Technique::ParallaxOcclusion;
    bool wireframe = false; ///< overlay the base mesh's triangles
    /// The mesh and model matrix drawn (for the wireframe overlay and for picking).
    virtual const Mesh& mesh() const = 0;
    virtual glm::mat4 model() const { return glm::mat4(1.0f); }
    TexelShadowChoice texelShadows = TexelShadowChoice::Auto; ///< SceneOptions::texelShadows
    bool beamStart = true;                                    ///< SceneOptions::beamStart
    bool deferShadowWalks = false;                            ///< SceneOptions::deferShadowWalks
    TracePass tracePass = TracePass::Auto;                    ///< SceneOptions::tracePass
    /// How this scene's surface is drawn, by the camera and into a shadow map alike.
    DrawOptions drawOptions() const {
        return {.technique = technique,
                .beamStart = beamStart,
                .texelShadows = texelShadows,
                .deferShadowWalks = deferShadowWalks,
                .tracePass = tracePass};
    }
    /// Where the last camera draw under hier walked its rays: "a compute pass" or "the draw"
    /// ("" where the scene does not draw with hier), and where TracePass::Auto timed both on this
    /// device, its medians: "the draw (auto: 3.37 ms, a compute pass 7.30 ms)", and the shadow
    /// map's the same where the scene casts the mesh into one.
    std::string tracePassLabel() const;
    /// The last draw's texel shadows as the exact tracer chose them (ExactTracer::last): "off",
    /// "on" or "on, stride N", for the panel and the bench table, and the flat surface's pixels
    /// per field texel they were chosen from (0 where not flat or not hier).
    std::string texelShadowsLabel() const;
    double pixelsPerTexel() const { return traced_.pixelsPerTexel; }
    /// What the renderer's exact tracer held at the last drawSurface (ExactTracer::memory).
    const TracerMemory& tracerMemory() const { return tracerMemory_; }

protected:
    /// Draws the effect's surface with its own material (the one owner: the panel edits it there).
    void drawSurface(SurfaceRenderer& renderer, const DirectionalLight& light);
    /// The command line's overrides of the effect's material (samples, depth, shadows, LOD) and
    /// its technique.
    void applyOptions(const SceneOptions& options);
    Camera camera_;

private:
    TracerFrame traced_; ///< the exact tracer's choice at the last drawSurface (none: not hier)
    TracePassTrialReport trial_; ///< its TracePass::Auto trial of the mesh's camera views then
    TracePassTrialReport casterTrial_; ///< ... and of its casts into a shadow map
    TracerMemory tracerMemory_; ///< what the renderer's exact tracer held then
};

/// A scene whose surface takes impacts through routeImpact (water, planet): a click fires a
/// bullet from the camera through the pixel, the explosion key a blast, and a shot list
/// (--shots) replays both, every line's A B being pixel coordinates here.
class ImpactScene : public Scene {
public:
    void prepare(double dt) override;
    void click(double x, double y, int width, int height) override { fire(ImpactKind::Bullet, x, y, width, height, 1); }
    void explode(double x, double y, int width, int height) override {
        fire(ImpactKind::Explosion, x, y, width, height, ++blasts_);
    }

protected:
    ImpactScene(const SceneOptions& options);
    /// The surface the impacts go to (made by the derived scene).
    virtual ImpactReceiver& receiver() = 0;

private:
    void fire(ImpactKind kind, double x, double y, int width, int height, std::uint64_t seed);
    std::vector<Shot> shots_;
    int frame_ = 0, width_, height_;
    std::uint64_t blasts_ = 0;
};

/// The known scene names, for help texts and errors.
inline constexpr const char* kSceneNames = "water, decals, planet, noise, maps";
/// The names of a list written "a, b, c" (kSceneNames; an option's scene label in --help).
std::vector<std::string> listedNames(std::string_view list);
/// Whether `name` is one of kSceneNames.
bool isSceneName(std::string_view name);

std::unique_ptr<Scene> makeWaterScene(ClContext& cl, const SceneOptions& options);
std::unique_ptr<Scene> makeDecalScene(ClContext& cl, const SceneOptions& options);
std::unique_ptr<Scene> makePlanetScene(ClContext& cl, const SceneOptions& options);
std::unique_ptr<Scene> makeMapsScene(ClContext& cl, const SceneOptions& options);
std::unique_ptr<Scene> makeNoiseScene(ClContext& cl, const SceneOptions& options);
/// Throws hfx::Error naming the scene and listing the known ones.
std::unique_ptr<Scene> makeScene(const std::string& name, ClContext& cl, const SceneOptions& options);

/// --technique auto, every scene's default: the exact tracer (hier) wherever the scene's surface
/// can carry its height bounds (one grid of power-of-two sizes in a float format); POM for the ocean,
/// whose cascades are layers on different grids (no common cells to walk), and for fields or
/// height maps of other sizes. Reads a height map's header (maps, decals) for its size.
Technique defaultTechnique(const std::string& scene, const SceneOptions& options);

} // namespace hfx::demo
