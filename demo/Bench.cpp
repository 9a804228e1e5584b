// hfx-demo bench: the frame budget of every scene, measured in one run. For each scene at two
// field sizes (the noise scene at three): per-stage medians (field step, normals, pyramid/colours,
// transfer to GL, draw with POM, POM without shadows, normal mapping and the scene's own technique
// where that is not POM (hier: what the decal, planet and noise scenes ship with), interleaved
// frame by frame so a noisy neighbour hits them alike), frames per second, the ratios issue 7 asks
// for, the process's peak resident memory and whether the flat scenes drew texel shadows. Then the
// scaling of the water frame with field size and output resolution.

#include "Scene.h"

#include "hfx/core/Gl.h"
#include "Devices.h"
#include "hfx/platform/GlContext.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/tools/Timing.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace hfx::demo {
namespace {

long peakResidentMiB() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6)) / 1024;
    return -1;
}

struct Budget {
    double field, normals, extra, upload, pom, unshadowed, nm;
    double own; ///< the scene's own technique with shadows; 0 where that is POM
    double compute() const { return field + normals + extra; }
    double frame() const { return compute() + upload + pom; }
};

/// Medians over `frames` frames after two warm-up frames; the scene's own material and POM, and
/// the scene's own technique.
Budget measure(Scene& scene, RenderTarget& target, int frames) {
    std::vector<double> field, normals, extra, upload, pom, unshadowed, nm, own;
    const SurfaceMaterial material = scene.effect().material();
    const Technique ownTechnique = scene.technique;
    for (int frame = -2; frame < frames; ++frame) {
        const double u = timeMs([&] { scene.update(1.0 / 30.0); });
        const StageTimes s = scene.effect().lastTimes();
        auto draw = [&](Technique t, bool shadows) {
            scene.technique = t;
            SurfaceMaterial m = material;
            m.shadows = shadows;
            scene.effect().setMaterial(m);
            return timeMs([&] {
                target.clear();
                scene.draw();
            });
        };
        const double p = draw(Technique::ParallaxOcclusion, true);
        const double q = draw(Technique::ParallaxOcclusion, false);
        const double n = draw(Technique::NormalMapping, true);
        const double o = ownTechnique == Technique::ParallaxOcclusion ? 0.0 : draw(ownTechnique, true);
        scene.effect().setMaterial(material);
        scene.technique = ownTechnique;
        if (frame < 0) continue;
        field.push_back(s.field);
        normals.push_back(s.normals);
        extra.push_back(s.extra);
        upload.push_back(u - s.compute); // everything update() did besides the device work
        pom.push_back(p);
        unshadowed.push_back(q);
        nm.push_back(n);
        own.push_back(o);
    }
    return {median(field), median(normals),    median(extra), median(upload),
            median(pom),   median(unshadowed), median(nm),    median(own)};
}

/// Wall time per frame of update + POM draw, run one after the other and overlapped (the next
/// field computed while this one draws), medians over `frames` frames each.
std::pair<double, double> sequentialAndOverlapped(Scene& scene, RenderTarget& target, int frames) {
    scene.technique = Technique::ParallaxOcclusion;
    std::vector<double> sequential, overlapped;
    for (int frame = -1; frame < frames; ++frame) {
        const double t = timeMs([&] {
            scene.update(1.0 / 30.0);
            target.clear();
            scene.draw();
        });
        if (frame >= 0) sequential.push_back(t);
    }
    scene.beginUpdate(1.0 / 30.0);
    for (int frame = -1; frame < frames; ++frame) {
        const double t = timeMs([&] {
            scene.endUpdate();
            target.clear();
            scene.draw();
            scene.beginUpdate(1.0 / 30.0);
        });
        if (frame >= 0) overlapped.push_back(t);
    }
    scene.endUpdate();
    return {median(sequential), median(overlapped)};
}

} // namespace

int runBench(const DeviceOptions& deviceOptions, const SceneOptions& options, int width, int height, int frames,
             const std::vector<std::string>& only) {
    auto wanted = [&](const std::string& part) { return only.empty() || std::ranges::find(only, part) != only.end(); };
    const Devices devices = openDevices(deviceOptions, {.width = width, .height = height}, false);
    ClContext& cl = *devices.cl;
    std::printf("hfx-demo bench: %dx%d, %d frames per case (medians)\n%s\n\n", width, height, frames,
                devices.summary().c_str());

    std::printf("| scene | field | step | normals | pyramid/extra | upload | POM draw | POM no shadows | NM draw | "
                "frame | fps | POM/NM | compute+upload share | overlapped frame | peak RSS MiB | own technique draw | "
                "texel shadows |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    RenderTarget target(width, height);
    target.bind();
    for (const char* name : {"water", "decals", "planet", "noise"})
        for (int size : {256, 512, 1024}) {
            // The noise scene from its own default size (256²), the others from 512².
            if (!wanted(name) || (size == 256 && std::string(name) != "noise")) continue;
            SceneOptions o = options;
            o.fieldSize = size;
            // The pyramid (hier) is built each frame, so its cost shows; the ocean as shipped has
            // four cascades, which hier cannot trace (one grid), so water runs POM.
            o.technique = std::string(name) == "water" ? Technique::ParallaxOcclusion : Technique::Hierarchical;
            o.width = width;
            o.height = height;
            auto scene = makeScene(name, cl, o);
            const Budget b = measure(*scene, target, frames);
            // The texel shadows drawn or not in measure()'s frames (their pass is in the upload,
            // their reads in hier's draw; sequentialAndOverlapped draws POM) and the pixels per
            // texel that chose it: the surface's quad on this image over the field's texels.
            char texels[64] = "-";
            if (scene->pixelsPerTexel() > 0.0)
                std::snprintf(texels, sizeof texels, "%s (%.2f px/texel)", scene->texelShadowsLabel().c_str(),
                              scene->pixelsPerTexel());
            const auto [sequential, overlapped] = sequentialAndOverlapped(*scene, target, frames);
            const auto& config = scene->effect().textures().config();
            char ownDraw[64] = "(POM)";
            if (b.own > 0.0) std::snprintf(ownDraw, sizeof ownDraw, "%s %.2f", techniqueName(o.technique), b.own);
            std::printf("| %s | %dx%d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %.1f | %.2fx | %.1f%% | "
                        "%.1f (%.1f sequential) | %ld | %s | %s |\n",
                        name, config.width, config.height, b.field, b.normals, b.extra, b.upload, b.pom,
                        b.unshadowed, b.nm, b.frame(), 1000.0 / b.frame(), b.pom / b.nm,
                        100.0 * (b.compute() + b.upload) / b.frame(), overlapped, sequential, peakResidentMiB(),
                        ownDraw, texels);
            std::fflush(stdout);
        }

    if (wanted("transfer")) {
        std::printf("\nTransfer of the water field by surface format and path (POM with shadows; extra = packing on "
                    "the device):\n\n| field | format | path | bytes / frame | normals | extra | upload | compute+upload | "
                    "POM draw | compute+upload share |\n|---|---|---|---|---|---|---|---|---|---|\n");
        for (int size : {512, 1024})
            for (SurfaceFormat format : kSurfaceFormats)
                for (TransferPath path : {TransferPath::Map, TransferPath::PixelBuffer}) {
                    SceneOptions o = options;
                    o.fieldSize = size;
                    o.technique = Technique::ParallaxOcclusion;
                    o.surfaceFormat = format;
                    o.transfer = path;
                    o.width = width;
                    o.height = height;
                    auto scene = makeScene("water", cl, o);
                    const Budget b = measure(*scene, target, frames);
                    std::printf("| %d² | %s | %s | %.1f MiB | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f%% |\n", size,
                                surfaceFormatName(format), transferPathName(path),
                                double(texelBytes(format)) * size * size / (1024.0 * 1024.0), b.normals, b.extra, b.upload,
                                b.compute() + b.upload, b.pom, 100.0 * (b.compute() + b.upload) / b.frame());
                    std::fflush(stdout);
                }
    }

    if (!wanted("scaling")) return 0;
    std::printf("\nScaling of the water frame (POM with shadows):\n\n| field | output | compute | upload | POM draw | frame ms |\n|---|---|---|---|---|---|\n");
    auto scaling = [&](int size, int w, int h) {
        SceneOptions o = options;
        o.fieldSize = size;
        o.width = w;
        o.height = h;
        RenderTarget t(w, h);
        t.bind();
        auto scene = makeScene("water", cl, o);
        const Budget b = measure(*scene, t, std::max(5, frames / 2));
        std::printf("| %d² | %dx%d | %.2f | %.2f | %.2f | %.1f |\n", size, w, h, b.compute(), b.upload, b.pom, b.frame());
        std::fflush(stdout);
    };
    for (int size : {256, 512, 1024}) scaling(size, width, height); // the ocean's cascades are at most 1024²
    for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1920, 1080}}) scaling(512, w, h);
    return 0;
}

} // namespace hfx::demo
