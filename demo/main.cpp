// hfx-demo: the module's users as scenes, in a window or headless to image files.
//   hfx-demo water --headless --frames 8 --out frames
//   hfx-demo decals --shots shots.txt --headless --frames 30 --video decals.mp4
//   hfx-demo planet --export-maps maps
//   hfx-demo bench

#include "Devices.h"
#include "Frames.h"
#include "Scene.h"
#include "Window.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/effects/GlStatePolicy.h"
#include "hfx/platform/GlContext.h"
#include "hfx/tools/ImageFiles.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/tools/Timing.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>

namespace hfx::demo {
int runBench(const DeviceOptions& devices, const SceneOptions& scene, int width, int height, int frames,
             const std::vector<std::string>& only);
int runBenchAccuracy(const DeviceOptions& devices, const std::string& outDir, int field, int width, int height);
int runBenchTracers(const DeviceOptions& devices, const std::string& outDir, int field,
                    const std::vector<std::string>& only, int rounds, int width, int height);
int runBenchMesh(const DeviceOptions& devices, int width, int height, int frames);
}

namespace {

using namespace hfx;
using namespace hfx::demo;

struct Options {
    std::string scene = "water";
    bool headless = false;
    int frames = 0; // 0: headless 1 frame, window until closed
    std::string out, video, exportMaps, windowShot;
    int width = 1280, height = 720;
    double dt = 1.0 / 30.0;
    std::string technique = "auto";
    std::string surfaceFormat = "auto";
    std::string tracePass = "auto";
    std::string glState = "restore";
    std::string transfer = "auto";
    std::string format = "png";
    bool noProgress = false;
    std::vector<std::string> benchOnly;
    SceneOptions sceneOptions;
    std::optional<CameraPath> cameraPath; ///< --camera-path, read before any device opens
    std::string gl = "auto";
    DeviceOptions devices;
    std::vector<std::string> hierOptions; ///< those of kHierOptions given on the command line
};

/// The options only hier reads; a headless run that draws another technique refuses them by name
/// (a window's panel may still switch to hier). --trace-pass auto, the default, passes.
const char* const kHierOptions[] = {"--texel-shadows", "--no-texel-shadows", "--no-beam-start",
                                    "--defer-shadow-walks", "--trace-pass"};

/// The first of the hier options asked for, refused where the headless run draws `technique`.
void refuseHierOptions(const Options& o, Technique technique) {
    if (technique == Technique::Hierarchical || o.hierOptions.empty()) return;
    throw Error(str(o.hierOptions[0], " is for the hier technique, and the ", o.scene, " scene draws ",
                    techniqueName(technique), o.technique == "auto" ? " (--technique auto's choice for it)" : "",
                    ": a headless run draws one technique"));
}

/// Refuses what CLI::Range lets through: NaN compares false with both bounds.
const CLI::Validator kFinite(
    [](std::string& text) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        return std::isfinite(v) ? std::string() : "'" + text + "' is not a finite number";
    },
    "FINITE");

/// The scenes an option is for, read from its help's label ("water: ...", "maps, decals: ..."); none
/// for an option that every scene takes (no label, or one that names no scene).
std::vector<std::string> optionScenes(const CLI::Option& option) {
    const std::string description = option.get_description();
    const std::size_t colon = description.find(':');
    if (colon == std::string::npos) return {};
    const std::vector<std::string> scenes = listedNames(std::string_view(description).substr(0, colon));
    return std::all_of(scenes.begin(), scenes.end(), [](const std::string& name) { return isSceneName(name); })
               ? scenes
               : std::vector<std::string>{};
}

/// Throws "WHAT is for the water and planet scenes: the noise scene does not take it" where
/// `option`'s label names scenes and not `scene`.
void refuseForScene(const CLI::Option& option, const std::string& scene, const std::string& what) {
    const std::vector<std::string> scenes = optionScenes(option);
    if (scenes.empty() || std::find(scenes.begin(), scenes.end(), scene) != scenes.end()) return;
    std::string names = scenes[0];
    for (std::size_t i = 1; i < scenes.size(); ++i) names += (i + 1 < scenes.size() ? ", " : " and ") + scenes[i];
    throw Error(str(what, " is for the ", names, " scene", scenes.size() > 1 ? "s" : "", ": the ", scene,
                    " scene does not take it"));
}

/// A scene refuses by name an option given on the command line that only other scenes take
/// (`water --rings 1`), where it would otherwise draw as if it had not been given; and a camera
/// path's value that only other scenes' cameras take (the option of its name's label).
void refuseOtherScenesOptions(const CLI::App& app, const std::string& scene, const std::optional<CameraPath>& path) {
    for (const CLI::Option* option : app.get_options())
        if (option->count() > 0) refuseForScene(*option, scene, option->get_name());
    if (path)
        for (const std::string& name : path->names())
            refuseForScene(*app.get_option("--camera-" + name), scene,
                           str("camera path ", path->file(), ": ", name, " (--camera-", name, ")"));
}

const glm::vec4 kBackground{0.55f, 0.68f, 0.85f, 1.0f};

glm::vec4 background(const std::string& scene) {
    return scene == "planet" ? glm::vec4(0.005f, 0.005f, 0.015f, 1.0f) : kBackground;
}

int runHeadless(const Options& o, Scene& scene) {
    RenderTarget target(o.width, o.height);
    const int frames = o.frames > 0 ? o.frames : 1;
    std::string outDir = o.out;
    if (outDir.empty() && o.video.empty()) outDir = "frames";
    if (!outDir.empty()) makeFolder(outDir, "--out");
    std::unique_ptr<VideoWriter> video;
    if (!o.video.empty()) video = std::make_unique<VideoWriter>(o.video, o.width, o.height, 1.0 / o.dt);
    Progress progress(frames, !o.noProgress && frames > 1);
    for (int frame = 0; frame < frames; ++frame) {
        // Headless runs advance by the fixed dt so two runs write identical frames. The next
        // field is computed while this one draws (begin after the draw, end before the next).
        if (frame > 0) scene.endUpdate();
        if (frame > 0 && scene.cameraTurn != 0.0f) scene.turnCamera(scene.cameraTurn * float(o.dt));
        scene.followPath(frame * o.dt);
        target.bind();
        scene.drawInto(target, background(o.scene));
        if (frame + 1 < frames) scene.beginUpdate(o.dt);
        const Image image = target.readColor();
        if (!outDir.empty()) {
            const std::string path = framePath(outDir, o.scene, frame, o.format);
            writeImage(path, image);
            if (!progress.enabled()) std::printf("wrote %s\n", path.c_str());
        }
        if (video) video->write(image);
        progress.step(frame + 1);
    }
    progress.finish();
    if (video) video->close();
    if (!outDir.empty() && progress.enabled())
        std::printf("wrote %d frames to %s\n", frames, outDir.c_str());
    // The last frame's texel-shadow choice, where the scene makes one (a flat surface under hier).
    if (scene.pixelsPerTexel() > 0.0)
        std::fprintf(stderr, "hfx: texel shadows %s (%.2f pixels per texel)\n", scene.texelShadowsLabel().c_str(),
                     scene.pixelsPerTexel());
    if (const std::string pass = scene.tracePassLabel(); !pass.empty())
        std::fprintf(stderr, "hfx: hier walked in %s\n", pass.c_str());
    if (const TracerMemory& m = scene.tracerMemory(); m.total() > 0) {
        constexpr double kMiB = 1024.0 * 1024.0;
        std::fprintf(stderr,
                     "hfx: the exact tracer holds %.1f MiB (the compute pass's slots %.1f, "
                     "bounds %.1f, texel shadows %.1f, prepasses %.1f)\n",
                     double(m.total()) / kMiB, double(m.slots) / kMiB, double(m.bounds) / kMiB,
                     double(m.texelShadows) / kMiB, double(m.prepasses) / kMiB);
    }
    if (!o.exportMaps.empty()) exportMaps(o.exportMaps, scene.effect().textures());
    scene.finish();
    return 0;
}

int run(const Options& o) {
    SceneOptions sceneOptions = o.sceneOptions;
    sceneOptions.surfaceFormat = parseSurfaceFormat(o.surfaceFormat);
    sceneOptions.technique = o.technique == "auto" ? defaultTechnique(o.scene, sceneOptions) : parseTechnique(o.technique);
    sceneOptions.transfer = parseTransferPath(o.transfer);
    sceneOptions.tracePass = o.tracePass == "draw"      ? TracePass::InDraw
                             : o.tracePass == "compute" ? TracePass::Compute
                                                        : TracePass::Auto;
    sceneOptions.width = o.width;
    sceneOptions.height = o.height;
    if (o.scene == "techniques") {
        std::printf("%s", techniqueTableMarkdown().c_str());
        return 0;
    }
    // The folders the run writes to, made before any device opens: one that cannot be made is named
    // at once, not after the scene's set-up or a bench's minutes.
    if (!o.out.empty()) makeFolder(o.out, "--out");
    if (!o.exportMaps.empty()) makeFolder(o.exportMaps, "--export-maps");
    if (const auto parent = std::filesystem::path(o.video).parent_path(); !parent.empty())
        makeFolder(parent.string(), "--video");
    // A bench's medians are of kTimedFrames frames a case at least (a noisy neighbour's spike is one
    // of them): more when --frames asks for more, and a smaller --frames is said to be raised.
    const int timedFrames = std::max(o.frames, kTimedFrames);
    const bool timesFrames = o.scene == "bench" || o.scene == "bench-mesh" || o.scene == "bench-tracers";
    if (timesFrames && o.frames > 0 && o.frames < kTimedFrames)
        std::fprintf(stderr, "hfx-demo %s: --frames %d raised to %d, the benches' fewest timed frames a case\n",
                     o.scene.c_str(), o.frames, kTimedFrames);
    if (o.scene == "bench")
        return runBench(o.devices, sceneOptions, o.width, o.height, timedFrames, o.benchOnly);
    if (o.scene == "bench-mesh") return runBenchMesh(o.devices, o.width, o.height, timedFrames);
    if (o.scene == "bench-accuracy") {
        const int field = sceneOptions.fieldSize > 0 ? sceneOptions.fieldSize : 256;
        if (field & (field - 1)) throw Error(str("bench-accuracy needs a power-of-two --field, got ", field));
        return runBenchAccuracy(o.devices, o.out.empty() ? "docs" : o.out, field, o.width, o.height);
    }
    if (o.scene == "bench-tracers") {
        const int field = sceneOptions.fieldSize > 0 ? sceneOptions.fieldSize : 256;
        if (field & (field - 1)) throw Error(str("bench-tracers needs a power-of-two --field, got ", field));
        return runBenchTracers(o.devices, o.out, field, o.benchOnly, timedFrames, o.width,
                               o.height);
    }
    if (!isSceneName(o.scene))
        throw Error(str("unknown scene '", o.scene, "' (known scenes: ", kSceneNames, ", bench)"));
    if (!o.video.empty()) checkVideoEncoder();

    Devices devices = openDevices(o.devices, {.width = o.width, .height = o.height, .title = "HFX " + o.scene},
                                  !o.headless);
    GlContext* gl = devices.gl.get();
    ClContext& cl = *devices.cl;
    if (gl->headless()) refuseHierOptions(o, sceneOptions.technique);
    setGlStatePolicy(o.glState == "defaults" ? GlStatePolicy::Defaults : GlStatePolicy::Restore);
    if (gl->headless() && !o.windowShot.empty()) // a window-only option, not dropped where none opened
        throw Error(str("--window-shot saves what a window shows, and this run is headless",
                        o.headless ? "" : " (no display)", ": its frames go to --out"));
    auto scene = makeScene(o.scene, cl, sceneOptions);
    if (o.cameraPath) {
        // Every frame's placement refused here, by its time, not mid-run (the planet's camera
        // inside its cloud tops): the path tried at 64 times between each pair of keys.
        scene->cameraPath = o.cameraPath;
        const std::vector<double>& keys = o.cameraPath->times();
        for (size_t k = 0; k < keys.size(); ++k)
            for (int i = 0; i < (k + 1 < keys.size() ? 64 : 1); ++i) {
                const double t = k + 1 < keys.size() ? keys[k] + (keys[k + 1] - keys[k]) * i / 64.0 : keys[k];
                try {
                    scene->followPath(t);
                } catch (const Error& e) {
                    throw Error(str("camera path ", o.cameraPath->file(), " at ", t, " s: ", e.what()));
                }
            }
        scene->followPath(0.0);
    }
    std::fprintf(stderr, "hfx: kernels: %s\nhfx: surface: %s\nhfx: technique: %s%s\n", cl.programReport().c_str(),
                 scene->effect().transferDescription().c_str(), techniqueName(scene->technique),
                 o.technique == "auto" ? " (auto: the scene's default)" : "");
    std::fprintf(stderr, "hfx: camera: %s\n", scene->cameraLabel().c_str());
    if (const std::string label = scene->sceneLabel(); !label.empty()) std::fprintf(stderr, "hfx: %s\n", label.c_str());
    if (scene->cameraTurn != 0.0f)
        std::fprintf(stderr, "hfx: camera: turning %.1f degrees a second (--camera-turn)\n", double(scene->cameraTurn));
    if (o.cameraPath)
        std::fprintf(stderr, "hfx: camera: following %s, %zu keys over %.2f s (--camera-path)\n",
                     o.cameraPath->file().c_str(), o.cameraPath->times().size(), o.cameraPath->duration());
    if (scene->camera().reversedZ) std::fprintf(stderr, "hfx: depth: reversed Z (near at 1, GL_ZERO_TO_ONE, GL_GREATER)\n");
    if (scene->orthographic)
        std::fprintf(stderr, "hfx: projection: orthographic (glm::ortho, the lens's frame at its target: parallel rays)\n");
    if (gl->headless()) return runHeadless(o, *scene);
    WindowLoop loop({.width = o.width,
                     .height = o.height,
                     .frames = o.frames,
                     .out = o.out,
                     .exportMaps = o.exportMaps,
                     .windowShot = o.windowShot,
                     .background = background(o.scene)});
    return loop.run(*gl, *scene);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"HFX demo: dynamic height fields rendered with parallax occlusion mapping.\n"
                 "Window controls: right-drag orbits, wheel zooms, left click shoots (decals), E explodes,\n"
                 "C clears the damage, F12 saves a screenshot, Esc quits; the panel edits every parameter."};
    Options o;
    SceneOptions& s = o.sceneOptions;
    app.add_option("scene", o.scene,
                   "scene: water (FFT ocean), decals (damage on a wall), planet (gas giant), noise (any noise as a "
                   "lit relief), maps "
                   "(a surface from image files), techniques (print the table of surface techniques), bench (frame-time benchmark), bench-tracers (the exact tracer's draw time against POM's, --bench-only MAP...), bench-accuracy (every technique "
                   "against the exact intersection; writes --out/ACCURACY.md, default docs) or bench-mesh (a POM "
                   "quad against a tessellated mesh of the same 1024² heights)")
        ->capture_default_str();
    app.add_flag("--headless", o.headless, "render off screen even when a display exists");
    app.add_option("--gl", o.gl,
                   "where the GL context comes from: auto (HFX_GL when set, else a window where a display exists and "
                   "--headless is absent, else EGL, else OSMesa), egl (a GPU's EGL device, else Mesa's surfaceless "
                   "platform, else its software device), egl-device, egl-surfaceless, or osmesa (Mesa's llvmpipe in "
                   "the process); anything but auto renders headless")
        ->check(CLI::IsMember({"auto", "egl", "egl-device", "egl-surfaceless", "osmesa"}))
        ->capture_default_str();
    app.add_option("--cl-device", o.devices.clDevice,
                   "the OpenCL device: a case-insensitive part of \"'NAME' (GPU|CPU) on 'PLATFORM'\" (nvidia, gpu, cpu, "
                   "portable); default HFX_CL_DEVICE, else a GPU before a CPU, then one on the GL renderer's hardware");
    app.add_option("--frames", o.frames, "frames to render (headless default 1; window: until closed); a bench's timed frames a case (at least 30)")
        ->check(CLI::Range(0, 1000000));
    app.add_option("--out", o.out, "folder for PNG frames (headless default: frames)");
    app.add_option("--format", o.format, "image format of the frames: png, jpg or exr")
        ->check(CLI::IsMember({"png", "jpg", "exr"}))->capture_default_str();
    app.add_option("--video", o.video, "also encode the frames into this video file (needs ffmpeg)");
    app.add_option("--export-maps", o.exportMaps,
                   "after the last frame, write the field's height, normal and albedo maps (EXR and PNG) to this folder");
    app.add_option("--width", o.width, "image width in pixels")->check(CLI::Range(16, 8192))->capture_default_str();
    app.add_option("--height", o.height, "image height in pixels")->check(CLI::Range(16, 8192))->capture_default_str();
    app.add_option("--dt", o.dt, "seconds between frames")->check(kFinite)->check(CLI::Range(1e-6, 10.0))->capture_default_str();
    app.add_option("--field", s.fieldSize, "height-field texels per edge (default: the scene's; ocean: a power of two; planet: the gas's width, "
                   "32-2048, its weather kept: 1024 on a GPU, 512 on a CPU device)")
        ->check(CLI::Range(8, 8192));
    std::vector<std::string> techniques{"auto"};
    std::string techniqueHelp = "surface technique (hfx-demo techniques lists them):\n  auto: hier where the scene's surface "
                                "can carry its height bounds (one power-of-two grid, float storage), pom elsewhere (the ocean's "
                                "cascades)";
    for (const TechniqueInfo& t : kTechniqueTable) {
        techniques.emplace_back(t.name);
        techniqueHelp += str("\n  ", t.name, ": ", t.summary);
    }
    app.add_option("--technique", o.technique, techniqueHelp)->check(CLI::IsMember(techniques))->capture_default_str();
    app.add_option("--samples-min", s.minSamples, "POM steps seen head-on (default: the scene's)")
        ->check(CLI::Range(1, 256));
    app.add_option("--samples-max", s.maxSamples, "POM steps at grazing angles (default: the scene's)")
        ->check(CLI::Range(1, 256));
    app.add_option("--depth-scale", s.depthScale, "relief depth in texture units (default: the scene's)")
        ->check(kFinite)->check(CLI::Range(0.0001, 1.0));
    app.add_option("--pixel-budget", s.pixelBudget,
                   "the screen error the tracers may leave, pixels (0: full effort; default: the scene's): hier stops "
                   "short of the exact hit by at most this much, the searches take no more steps than keep each within it, "
                   "and flat scenes may draw their texel shadows at every few samples that stay this close on screen")
        ->check(CLI::Range(0.0f, 64.0f));
    app.add_option("--lod-threshold", s.lodThreshold, "mip level where POM has faded to normal mapping")
        ->check(kFinite)->check(CLI::Range(0.0, 16.0))->capture_default_str();
    app.add_option("--seed", s.seed, "random seed of the field")->capture_default_str();
    bool noShadows = false;
    app.add_flag("--no-shadows", noShadows, "turn POM soft self-shadows off");
    bool texelShadowsOn = false, texelShadowsOff = false;
    app.add_flag("--texel-shadows", texelShadowsOn,
                 "decals, noise, maps: hier draws the flat surface's self-shadow at every texel each frame "
                 "(TexelShadowPass): pixels walk their light ray only where a hard shadow's edge crosses their cell; "
                 "by default they do where hier walks in the draw and the pass pays (from 1.75 pixels per texel) or, "
                 "under --pixel-budget, at every 2nd, 4th... texel where that pays and stays within the budget on "
                 "screen; a compute pass walks every pixel's light ray by default")
        ->excludes("--no-shadows");
    app.add_flag("--no-texel-shadows", texelShadowsOff,
                 "decals, noise, maps: hier never draws the texel shadows (every pixel walks its light ray)")
        ->excludes("--texel-shadows");
    bool noBeamStart = false;
    app.add_flag("--no-beam-start", noBeamStart,
                 "decals, noise, maps, water: hier walks every view ray on the flat surface from the top, without the "
                 "beam prepass that starts each 8x8-pixel block's rays where they may first meet the relief (the "
                 "same image, more steps)");
    app.add_flag("--reversed-z", s.reversedZ,
                 "water, decals, planet, noise, maps: draw with a reversed depth buffer, as many engines do (the near "
                 "plane at depth 1 under glClipControl's GL_ZERO_TO_ONE, GL_GREATER, cleared to 0: Camera::reversedZ; "
                 "the same image)");
    app.add_flag("--orthographic", s.orthographic,
                 "water, decals, planet, noise, maps: draw with an orthographic projection framing at the camera's "
                 "target what its lens frames there, as an editor's or a top-down game's view does (every pixel's "
                 "ray parallel: Camera::customProjection from glm::ortho)");
    app.add_flag("--defer-shadow-walks", s.deferShadowWalks,
                 "decals, noise, maps: the light walks hier's texel shadows leave (where a hard shadow's edge "
                 "crosses the samples around a pixel) are done by a pass after the draw, one to a lane, instead of "
                 "holding up their warp (the same image; slower on llvmpipe)")
        ->excludes("--no-shadows")
        ->excludes("--no-texel-shadows");
    app.add_option("--trace-pass", o.tracePass,
                   "where hier walks a convex surface's rays (a plane, the planet): auto (the device's: the draw on a "
                   "CPU rasteriser, else whichever of the two this device draws faster, timed on the first draws), "
                   "draw, or compute (a rays draw, none on a plane, a compute pass a lane per pixel, the shading draw; the "
                   "same hits)")
        ->check(CLI::IsMember({"auto", "draw", "compute"}))->capture_default_str();
    app.add_option("--gl-state", o.glState,
                   "what HFX's draws do with the GL state they change (hfx::GlStatePolicy): restore (read it first and "
                   "put it back) or defaults (read none of it and leave GL's defaults, as for an engine that binds its "
                   "own state before each draw; the same frames)")
        ->check(CLI::IsMember({"restore", "defaults"}))->capture_default_str();
    app.add_option("--surface-format", o.surfaceFormat,
                   "storage of normal + height: float32, float16 (half the memory and transfer), unorm8 "
                   "(a quarter; not with --technique hier) or auto (float16 on a GPU, float32 on a CPU rasteriser, "
                   "which converts a float16 texel per fetch); docs/ACCURACY.md measures their error")
        ->check(CLI::IsMember({"float32", "float16", "unorm8", "auto"}))->capture_default_str();
    app.add_option("--transfer", o.transfer,
                   "how the surface reaches GL: map (from the mapped device buffer), pixel-buffer (the device writes a "
                   "GL pixel buffer), staged (a read into pinned memory, copied into a fenced pixel-buffer ring: for a "
                   "discrete GPU), gl-sharing (cl_khr_gl_sharing: the device copies into shared GL buffers; a GLX window "
                   "on NVIDIA), external-memory (the device copies into memory Vulkan allocates on GL's device and both "
                   "import: any GL context, EGL's included, with libvulkan.so.1) or auto (gl-sharing where the contexts "
                   "share, pixel-buffer where the device shares host memory, else external-memory where offered, else "
                   "staged)")
        ->check(CLI::IsMember({"auto", "map", "pixel-buffer", "staged", "gl-sharing", "external-memory"}))
        ->capture_default_str();
    app.add_option("--waves", s.waves, "water: fft (Tessendorf ocean) or sine (directional waves)")
        ->check(CLI::IsMember({"fft", "sine"}))->capture_default_str();
    app.add_option("--wind-speed", s.windSpeed, "water: wind speed in m/s")->check(kFinite)->check(CLI::Range(0.5, 100.0))->capture_default_str();
    app.add_option("--wind-dir", s.windDirection, "water: wind direction in radians")
        ->check(kFinite)->check(CLI::Range(-10.0, 10.0))->capture_default_str();
    app.add_option("--environment", s.environment, "water: equirectangular sky image to reflect");
    app.add_option("--clouds", s.clouds,
                   "water: the share of the sky under cloud, 0 to 1 (default: the wind's weather, 0.4 up to Beaufort 6, "
                   "clouding over to 0.95 at 10; none with --environment, which is the whole sky)")
        ->check(kFinite)->check(CLI::Range(0.0, 1.0));
    app.add_option("--beaufort", s.beaufort, "water: Beaufort force 0-12, sets the wind speed (overrides --wind-speed)")
        ->check(CLI::Range(0, 12));
    app.add_option("--fetch", s.fetchKm, "water: fetch of the wind sea in km")->check(kFinite)->check(CLI::Range(1.0, 100000.0))->capture_default_str();
    app.add_option("--spectrum", s.spectrum, "water: phillips, pierson-moskowitz, jonswap or tma")
        ->check(CLI::IsMember({"phillips", "pierson-moskowitz", "jonswap", "tma"}))->capture_default_str();
    app.add_option("--spreading", s.spreading, "water: cos2s, hasselmann or donelan-banner")
        ->check(CLI::IsMember({"cos2s", "hasselmann", "donelan-banner"}))->capture_default_str();
    app.add_option("--sea-depth", s.depthMeters, "water: depth of the sea in metres (0: deep; tma uses it)")
        ->check(kFinite)->check(CLI::Range(0.0, 10000.0))->capture_default_str();
    app.add_option("--swell", s.swell, "water: energy of a swell 50 degrees off the wind (0: none, 1: a full sea)")
        ->check(kFinite)->check(CLI::Range(0.0, 4.0))->capture_default_str();
    app.add_option("--choppiness", s.choppiness, "water: horizontal displacement (0: heights only; near 1 the crests sharpen)")
        ->check(kFinite)->check(CLI::Range(0.0, 4.0))->capture_default_str();
    app.add_option("--cascades", s.cascades, "water: ocean cascades, 1-4 (default 4; 1 with --technique hier, which traces one grid)")->check(CLI::Range(1, 4));
    app.add_option("--time-scale", s.timeScale, "planet: simulated seconds per second (1 to 10000; storms live many rotations)")
        ->check(kFinite)->check(CLI::Range(1.0, 10000.0))->capture_default_str();
    app.add_option("--spin-up", s.spinUp,
                   "planet: simulated seconds of weather before the first frame (storms and shear work the bands; 0: "
                   "the bands as they start)")
        ->check(kFinite)->check(CLI::Range(0.0, 3600.0))->capture_default_str();
    app.add_option("--camera-pitch", s.cameraPitch, "water: degrees the camera looks below the horizon (small: the far field)")
        ->check(kFinite)->check(CLI::Range(0.0, 89.0))->capture_default_str();
    app.add_option("--camera-height", s.cameraHeight,
                   "water: metres the camera stands above the sea (high: the cascades' tiling and the far field)")
        ->check(kFinite)->check(CLI::Range(1.0, 2000.0))->capture_default_str();
    app.add_option("--foam-history", s.foamHistory,
                   "water: seconds of this wind the first frame's foam has seen (five of its 4 s half-lives by default: the whitecaps "
                   "and a gale's streaks of a sea that has blown a while; 0: a clear start, where they build over the first seconds)")
        ->check(kFinite)->check(CLI::Range(0.0, 600.0))->capture_default_str();
    // The camera's place about its target: given, each replaces the scene's own (SceneOptions).
    float cameraAzimuth = 0.0f, cameraElevation = 0.0f, cameraDistance = 0.0f;
    app.add_option("--camera-azimuth", cameraAzimuth,
                   "water, decals, planet, noise, maps: degrees about the vertical axis from +z where the camera "
                   "stands about its target (default: the scene's, which the log gives; water: the way it looks, 0 "
                   "along -z towards the low sun)")
        ->check(kFinite)->check(CLI::Range(-360.0, 360.0));
    app.add_option("--camera-elevation", cameraElevation,
                   "decals, planet, noise, maps: degrees the camera stands above its target (default: the scene's; "
                   "the water's camera stands above the sea: --camera-height, --camera-pitch)")
        ->check(kFinite)->check(CLI::Range(-89.0, 89.0));
    std::vector<float> cameraTarget;
    app.add_option("--camera-target", cameraTarget,
                   "decals, planet, noise, maps: the point X,Y,Z the camera looks at and stands about, world units "
                   "(default: the scene's, the origin; the wall spans -2..2 in x and y)")
        ->expected(3)->delimiter(',')->check(kFinite)->check(CLI::Range(-100.0, 100.0));
    app.add_option("--camera-turn", s.cameraTurn,
                   "water, decals, planet, noise, maps: degrees a second the camera turns about its target in the "
                   "frames' time (the water's on the spot), for a video of the relief's parallax as the view swings "
                   "(0: still)")
        ->check(kFinite)->check(CLI::Range(-360.0, 360.0))->capture_default_str();
    std::string cameraPath;
    app.add_option("--camera-path", cameraPath,
                   "water, decals, planet, noise, maps: a keyframed camera path, a file of lines 'SECONDS NAME=VALUE "
                   "...' with the --camera-NAME options' names and units (azimuth, elevation, distance, target=X,Y,Z; "
                   "the water's azimuth, height, pitch), every line the same names; eased between the keys, in the "
                   "frames' time (a window plays it once, then the mouse has the camera)");
    app.add_option("--camera-distance", cameraDistance,
                   "decals, planet, noise, maps: the camera's distance from its target (default: the scene's; "
                   "planet: radii from the centre, 2.6, a close-up 1.3)")
        ->check(kFinite)->check(CLI::Range(1.05, 100.0));
    app.add_option("--rings", s.rings, "planet: rings in the equatorial plane, casting and receiving shadows (1.24-2.27 radii: "
                                       "--camera-distance 5 shows them whole)")
        ->capture_default_str();
    app.add_option("--detail-scale", s.detailScale,
                   "planet: cloud-top detail texels per gas cell, 1, 2, 4 or 8 (0: 4 on a GPU, 2 on a CPU device, at most 2048 or 1024 wide)")
        ->check(CLI::IsMember({0, 1, 2, 4, 8}))->capture_default_str();
    app.add_option("--noise-kind", s.noiseKind, "noise: perlin, simplex or psrd")
        ->check(CLI::IsMember({"perlin", "simplex", "psrd"}))->capture_default_str();
    app.add_option("--fractal", s.fractal, "noise: fbm, ridged or turbulence")
        ->check(CLI::IsMember({"fbm", "ridged", "turbulence"}))->capture_default_str();
    app.add_option("--tiling", s.tiling, "noise: wrap (tiles), wrap-u (tiles in u) or clamp (does not tile; simplex)")
        ->check(CLI::IsMember({"wrap", "wrap-u", "clamp"}))->capture_default_str();
    app.add_option("--octaves", s.octaves, "noise: octaves summed")->check(CLI::Range(1, 16))->capture_default_str();
    app.add_option("--frequency", s.frequency, "noise: base cells across the field (whole when it tiles)")
        ->check(kFinite)->check(CLI::Range(0.5, 256.0))->capture_default_str();
    app.add_option("--lacunarity", s.lacunarity, "noise: frequency ratio of successive octaves")
        ->check(kFinite)->check(CLI::Range(1.0, 8.0))->capture_default_str();
    app.add_option("--gain", s.gain, "noise: amplitude ratio of successive octaves")
        ->check(kFinite)->check(CLI::Range(0.05, 1.0))->capture_default_str();
    app.add_option("--warp", s.warp, "noise: domain warp in base cells (0: none)")
        ->check(kFinite)->check(CLI::Range(0.0, 8.0))->capture_default_str();
    app.add_option("--noise-speed", s.noiseSpeed, "noise: animation speed (time units per second)")
        ->check(kFinite)->check(CLI::Range(0.0, 10.0))->capture_default_str();
    app.add_option("--triplanar", s.triplanar,
                   "noise: draw the relief on a rounded box, its texcoords projected along the box's axes (a triplanar "
                   "mapping), this many repeats per unit (0: the plane)")
        ->check(kFinite)->check(CLI::Range(0.0, 64.0))->capture_default_str();
    app.add_flag("--pillar", s.pillar,
                 "decals: the bricks and their damage on a column (a cylinder) instead of the wall, clicks picked on "
                 "its relief (pickMesh)");
    app.add_option("--save-damage", s.saveDamage, "decals: after the last frame, write the damage log (impacts, clock) to this file");
    app.add_option("--load-damage", s.loadDamage,
                   "decals: start from a saved damage log (drawn exactly as saved; no automatic volley)");
    app.add_option("--shots", s.shots,
                   "decals, water, planet: shot list to replay (lines 'bullet|explosion|click FRAME A B': the wall's "
                   "texcoords, else pixels)");
    app.add_option("--height-map", s.heightMap, "maps, decals: height map image (h in [0,1])");
    app.add_option("--normal-map", s.normalMap,
                   "maps, decals: tangent-space normal map (default: Sobel of the heights)");
    app.add_option("--color-map", s.colorMap, "maps, decals: colour map");
    app.add_option("--window-shot", o.windowShot,
                   "window runs with --frames: save the last frame as the window shows it, panel included");
    app.add_option("--bench-only", o.benchOnly, "bench: only these tables (default all); bench-tracers: only these maps")
        ->check(CLI::IsMember({"water", "decals", "planet", "transfer", "scaling", "smooth waves", "bricks", "noise",
                               "damaged wall"}))
        ->delimiter(',');
    app.add_flag("--no-progress", o.noProgress, "headless: print each frame's file instead of a progress bar");
    CLI11_PARSE(app, argc, argv);
    if (app.count("--camera-azimuth") > 0) s.cameraAzimuth = cameraAzimuth;
    if (app.count("--camera-elevation") > 0) s.cameraElevation = cameraElevation;
    if (app.count("--camera-distance") > 0) s.cameraDistance = cameraDistance;
    if (cameraTarget.size() == 3) s.cameraTarget = glm::vec3(cameraTarget[0], cameraTarget[1], cameraTarget[2]);
    o.devices.gl = parseGlBackend(o.gl);
    s.shadows = !noShadows;
    s.texelShadows = texelShadowsOn ? TexelShadowChoice::On : texelShadowsOff ? TexelShadowChoice::Off : TexelShadowChoice::Auto;
    s.beamStart = !noBeamStart;
    for (const char* name : kHierOptions)
        if (app.count(name) > 0 && (std::string_view(name) != "--trace-pass" || o.tracePass != "auto"))
            o.hierOptions.emplace_back(name);
    if (s.maxSamples > 0 && s.minSamples > 0 && s.maxSamples < s.minSamples) {
        std::fprintf(stderr, "hfx-demo: error: --samples-max (%d) is below --samples-min (%d)\n", s.maxSamples,
                     s.minSamples);
        return 2;
    }
    try {
        // The benches draw each scene from one place: a turn or a path would be dropped unsaid.
        if (o.scene.starts_with("bench") && (s.cameraTurn != 0.0f || !cameraPath.empty()))
            throw Error(str(s.cameraTurn != 0.0f ? "--camera-turn" : "--camera-path", " is for the scenes' runs: ",
                            o.scene, " draws each scene from one place (--camera-azimuth, --camera-elevation, "
                                     "--camera-distance and --camera-target place it)"));
        if (!cameraPath.empty()) {
            if (s.cameraTurn != 0.0f)
                throw Error("--camera-path excludes --camera-turn (the path turns the camera: give it azimuth keys)");
            o.cameraPath = CameraPath::load(cameraPath);
        }
        if (isSceneName(o.scene)) refuseOtherScenesOptions(app, o.scene, o.cameraPath);
        // The triplanar box is no flat patch: what follows a flat patch's light is refused by
        // name rather than left undone.
        if (s.triplanar > 0.0f)
            for (const std::string& asked : o.hierOptions)
                if (asked == "--texel-shadows" || asked == "--defer-shadow-walks")
                    throw Error(str(asked, " is for the plane: --triplanar's box is no flat patch (the texel shadows "
                                           "and the deferred walks follow a flat patch's light)"));
        // The pillar is no flat patch either: the texel shadows and the deferred walks follow a
        // flat patch's light, and would be left undone without a word.
        if (s.pillar)
            for (const std::string& asked : o.hierOptions)
                if (asked == "--texel-shadows" || asked == "--defer-shadow-walks")
                    throw Error(str(asked, " is for the wall: --pillar's column is no flat patch (the texel shadows and "
                                           "the deferred walks follow a flat patch's light)"));
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "hfx-demo: error: %s\n", e.what());
        return 1;
    }
}
