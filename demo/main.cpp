// hfx-demo: the module's scenes in a window, or headless to image files.
//   hfx-demo water --headless --frames 8 --out frames
//   hfx-demo bench

#include "Scene.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/GlContext.h"
#include "hfx/core/Image.h"
#include "hfx/core/RenderTarget.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>

namespace hfx::demo {
int runBench(const SceneOptions& scene, int width, int height, int frames);
}

namespace {

using namespace hfx;
using namespace hfx::demo;

struct Options {
    std::string scene = "water";
    bool headless = false;
    int frames = 0; // 0: headless 1 frame, window until closed
    std::string out;
    int width = 1280, height = 720;
    double dt = 1.0 / 30.0;
    std::string technique = "pom";
    SceneOptions sceneOptions;
};

int run(const Options& o) {
    SceneOptions sceneOptions = o.sceneOptions;
    sceneOptions.technique = parseTechnique(o.technique);
    sceneOptions.aspect = float(o.width) / float(o.height);
    if (o.scene == "bench") return runBench(sceneOptions, o.width, o.height, o.frames > 0 ? o.frames : 20);
    if (o.scene != "water" && o.scene != "maps")
        throw Error(str("unknown scene '", o.scene, "' (known scenes: ", kSceneNames, ", bench)"));
    if (o.scene == "maps" && sceneOptions.heightMap.empty())
        throw Error("the maps scene needs --height-map FILE");

    auto gl = createContext({.width = o.width, .height = o.height, .title = "HFX " + o.scene},
                            !o.headless);
    std::fprintf(stderr, "hfx-demo: %s, %s\n", gl->headless() ? "headless" : "window",
                 gl->description().c_str());
    ClContext cl;
    auto scene = makeScene(o.scene, cl, sceneOptions);
    RenderTarget target(o.width, o.height);

    const int frames = o.frames > 0 ? o.frames : (gl->headless() ? 1 : 0);
    std::string outDir = o.out;
    if (outDir.empty() && gl->headless()) outDir = "frames";
    if (!outDir.empty()) std::filesystem::create_directories(outDir);

    auto last = std::chrono::steady_clock::now();
    for (int frame = 0; frames == 0 || frame < frames; ++frame) {
        if (!gl->pollEvents()) break;
        // Headless runs advance by the fixed dt so two runs write identical frames.
        double dt = o.dt;
        if (!gl->headless() && frame > 0) {
            const auto now = std::chrono::steady_clock::now();
            dt = std::chrono::duration<double>(now - last).count();
            last = now;
        }
        if (frame > 0) scene->update(dt);
        target.bind();
        target.clear({0.55f, 0.68f, 0.85f, 1.0f});
        scene->draw();
        if (!outDir.empty() && frame < (frames == 0 ? 1 : frames)) {
            char name[64];
            std::snprintf(name, sizeof name, "%s_%04d.png", o.scene.c_str(), frame);
            const std::string path = (std::filesystem::path(outDir) / name).string();
            writeImage(path, target.readColor());
            std::printf("wrote %s\n", path.c_str());
        }
        if (!gl->headless()) {
            const glm::ivec2 size = gl->framebufferSize();
            glBlitNamedFramebuffer(target.framebuffer(), 0, 0, 0, o.width, o.height, 0, 0, size.x,
                                   size.y, GL_COLOR_BUFFER_BIT, GL_LINEAR);
            gl->swapBuffers();
        }
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"HFX demo: dynamic height fields rendered with parallax occlusion mapping"};
    Options o;
    app.add_option("scene", o.scene,
                   "scene to show: water, maps (a surface from image files), or bench (frame-time "
                   "benchmark)")
        ->capture_default_str();
    app.add_flag("--headless", o.headless, "render off screen even when a display exists");
    app.add_option("--frames", o.frames, "frames to render (headless default 1; window: until closed)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--out", o.out, "folder for PNG frames (headless default: frames)");
    app.add_option("--width", o.width, "image width in pixels")->check(CLI::Range(16, 8192))->capture_default_str();
    app.add_option("--height", o.height, "image height in pixels")->check(CLI::Range(16, 8192))->capture_default_str();
    app.add_option("--dt", o.dt, "seconds between frames")->check(CLI::Range(1e-6, 10.0))->capture_default_str();
    app.add_option("--field", o.sceneOptions.fieldSize, "height-field texels per edge")
        ->check(CLI::Range(2, 8192))->capture_default_str();
    app.add_option("--technique", o.technique, "pom or nm (normal mapping)")
        ->check(CLI::IsMember({"pom", "nm"}))->capture_default_str();
    app.add_option("--samples-min", o.sceneOptions.minSamples, "POM steps seen head-on")
        ->check(CLI::Range(1, 256))->capture_default_str();
    app.add_option("--samples-max", o.sceneOptions.maxSamples, "POM steps at grazing angles")
        ->check(CLI::Range(1, 256))->capture_default_str();
    app.add_option("--depth-scale", o.sceneOptions.depthScale, "relief depth in texture units")
        ->check(CLI::Range(0.0, 1.0))->capture_default_str();
    app.add_option("--seed", o.sceneOptions.seed, "random seed of the field")->capture_default_str();
    app.add_option("--height-map", o.sceneOptions.heightMap, "maps scene: height map image (h in [0,1])");
    app.add_option("--normal-map", o.sceneOptions.normalMap,
                   "maps scene: tangent-space normal map (default: Sobel of the heights)");
    app.add_option("--color-map", o.sceneOptions.colorMap, "maps scene: colour map");
    bool noShadows = false;
    app.add_flag("--no-shadows", noShadows, "turn POM soft self-shadows off");
    CLI11_PARSE(app, argc, argv);
    o.sceneOptions.shadows = !noShadows;
    if (o.sceneOptions.maxSamples < o.sceneOptions.minSamples) {
        std::fprintf(stderr, "hfx-demo: error: --samples-max (%d) is below --samples-min (%d)\n",
                     o.sceneOptions.maxSamples, o.sceneOptions.minSamples);
        return 2;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "hfx-demo: error: %s\n", e.what());
        return 1;
    }
}
