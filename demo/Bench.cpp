// hfx-demo bench: the frame budget of every scene, measured in one run. For each scene at two
// field sizes (the noise scene at three): per-stage medians (field step, normals, pyramid/colours,
// transfer to GL, draw with POM, POM without shadows, normal mapping and the scene's own technique
// where that is not POM (hier: what the decal, planet and noise scenes ship with), interleaved
// frame by frame so a noisy neighbour hits them alike), frames per second, the ratios issue 7 asks
// for, the process's peak resident memory and whether the flat scenes drew texel shadows; for the
// water's clouds, its POM and NM draws under a clear sky, the same frames. Then the scaling of the
// water frame with field size and output resolution.

#include "Scene.h"

#include "hfx/core/Error.h"
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

/// One scene's frame, stage by stage, on both clocks (medians over the timed frames).
struct Budget {
    // The CPU wall clock, each stage waited for (glFinish, clFinish) on its own.
    double field, normals, extra, upload, pom, unshadowed, nm;
    double own; ///< the scene's own technique with shadows; 0 where that is POM
    // Device time: the frame's kernels (CL event profiling, VkFFT's included) and each GL pass
    // (timer queries): the uploads and each draw whole (its shadow map, bounds, texel shadows
    // and beam start included), with the own technique's beam start, bounds and texel shadows apart.
    double kernels, glUpload, gpuPom, gpuUnshadowed, gpuNm, gpuOwn, ownBeam, ownBounds, ownTexels;
    /// A water look with clouds: its POM and NM draws without them (WaterLook::cloudCover 0), the
    /// same frames, and the sky pass of the POM draws with and without them; 0 where the look has
    /// none.
    double gpuPomClear = 0.0, gpuNmClear = 0.0, gpuSky = 0.0, gpuSkyClear = 0.0;
    double compute() const { return field + normals + extra; }
    double frame() const { return compute() + upload + pom; }
    /// The transfer: its CPU wall clock (map or read, copies, GL's upload calls) or the GL
    /// upload's device time, whichever is longer (on a CPU rasteriser they are the same clock).
    double transfer() const { return std::max(upload, glUpload); }
    /// A frame drawn with POM: kernels, transfer, the draw.
    double gpuFrame() const { return kernels + transfer() + gpuPom; }
    /// The compute and the transfer's share of it.
    double computeShare() const { return (kernels + transfer()) / gpuFrame(); }
};

/// The median of a pass's GPU samples on `timer`, 0 where it never ran.
double gpuMedian(const GpuTimer& timer, const char* pass) {
    const auto it = timer.samples().find(pass);
    return it == timer.samples().end() ? 0.0 : median(it->second);
}

/// What measure() draws each frame.
enum class Draws {
    All,    ///< POM, POM without shadows, NM, the own technique, the clear-sky pair: the scene table
    PomOnly ///< POM with shadows alone, all the transfer and scaling tables read (the others stay 0)
};

/// `frames` frames after kWarmupFrames warm-up frames, each: an update (staged: every stage
/// waited for and timed), then the scene drawn with POM, and with Draws::All also POM without
/// shadows, normal mapping and its own technique (and, for a water look with clouds, POM and
/// normal mapping under a clear sky), interleaved frame by frame so a noisy neighbour hits them alike.
Budget measure(Scene& scene, RenderTarget& target, ClContext& cl, int frames, Draws draws = Draws::All) {
    std::vector<double> field, normals, extra, upload, pom, unshadowed, nm, own, kernels;
    const SurfaceMaterial material = scene.effect().material();
    const Technique ownTechnique = scene.technique;
    // One timer per kind of work, so that each one's passes ("draw", "beam", ...) stay its own.
    GpuTimer updateTimer, pomTimer, unshadowedTimer, nmTimer, ownTimer, pomClearTimer, nmClearTimer;
    const bool all = draws == Draws::All;
    const bool clouds = all && material.shading == Shading::Water && material.water.sky() == SkyKind::Clouds;
    for (int frame = -kWarmupFrames; frame < frames; ++frame) {
        if (frame == 0)
            for (GpuTimer* t : {&updateTimer, &pomTimer, &unshadowedTimer, &nmTimer, &ownTimer, &pomClearTimer, &nmClearTimer}) {
                t->finish();
                t->clearSamples();
            }
        double u = 0.0;
        {
            GpuTimer::Activation on(updateTimer);
            updateTimer.beginFrame();
            cl.recordKernelTimes(true);
            u = timeMs([&] { scene.update(1.0 / 30.0); });
            cl.recordKernelTimes(false);
            updateTimer.endFrame();
        }
        double k = 0.0;
        for (const auto& [name, ms] : cl.takeKernelTimes()) k += ms;
        const StageTimes s = scene.effect().lastTimes();
        auto draw = [&](GpuTimer& timer, Technique t, bool shadows, bool clear = false) {
            scene.technique = t;
            SurfaceMaterial m = material;
            m.shadows = shadows;
            if (clear) m.water.cloudCover = 0.0f;
            scene.effect().setMaterial(m);
            GpuTimer::Activation on(timer);
            timer.beginFrame();
            const double ms = timeMs([&] {
                const GpuScope whole("whole");
                scene.drawInto(target, {0.0f, 0.0f, 0.0f, 1.0f});
            });
            timer.endFrame();
            return ms;
        };
        const double p = draw(pomTimer, Technique::ParallaxOcclusion, true);
        const double q = all ? draw(unshadowedTimer, Technique::ParallaxOcclusion, false) : 0.0;
        const double n = all ? draw(nmTimer, Technique::NormalMapping, true) : 0.0;
        const double o = !all || ownTechnique == Technique::ParallaxOcclusion ? 0.0 : draw(ownTimer, ownTechnique, true);
        if (clouds) {
            draw(pomClearTimer, Technique::ParallaxOcclusion, true, true);
            draw(nmClearTimer, Technique::NormalMapping, true, true);
        }
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
        kernels.push_back(k);
    }
    for (GpuTimer* t : {&updateTimer, &pomTimer, &unshadowedTimer, &nmTimer, &ownTimer, &pomClearTimer, &nmClearTimer})
        t->finish();
    return {.field = median(field),
            .normals = median(normals),
            .extra = median(extra),
            .upload = median(upload),
            .pom = median(pom),
            .unshadowed = median(unshadowed),
            .nm = median(nm),
            .own = median(own),
            .kernels = median(kernels),
            .glUpload = gpuMedian(updateTimer, "upload"),
            .gpuPom = gpuMedian(pomTimer, "whole"),
            .gpuUnshadowed = gpuMedian(unshadowedTimer, "whole"),
            .gpuNm = gpuMedian(nmTimer, "whole"),
            .gpuOwn = gpuMedian(ownTimer, "whole"),
            .ownBeam = gpuMedian(ownTimer, "beam"),
            .ownBounds = gpuMedian(ownTimer, "bounds"),
            .ownTexels = gpuMedian(ownTimer, "texel shadows"),
            .gpuPomClear = gpuMedian(pomClearTimer, "whole"),
            .gpuNmClear = gpuMedian(nmClearTimer, "whole"),
            .gpuSky = clouds ? gpuMedian(pomTimer, "sky") : 0.0,
            .gpuSkyClear = gpuMedian(pomClearTimer, "sky")};
}

/// Wall time per frame of update + POM draw, run one after the other and overlapped (the next
/// field computed while this one draws), medians over `frames` frames each.
std::pair<double, double> sequentialAndOverlapped(Scene& scene, RenderTarget& target, int frames) {
    scene.technique = Technique::ParallaxOcclusion;
    std::vector<double> sequential, overlapped;
    for (int frame = -kWarmupFrames; frame < frames; ++frame) {
        const double t = timeMs([&] {
            scene.update(1.0 / 30.0);
            scene.drawInto(target, {0.0f, 0.0f, 0.0f, 1.0f});
        });
        if (frame >= 0) sequential.push_back(t);
    }
    scene.beginUpdate(1.0 / 30.0);
    for (int frame = -kWarmupFrames; frame < frames; ++frame) {
        const double t = timeMs([&] {
            scene.endUpdate();
            scene.drawInto(target, {0.0f, 0.0f, 0.0f, 1.0f});
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
    std::printf("hfx-demo bench: %dx%d, medians of %d frames per case after %d warm-up frames\n%s\n", width, height,
                frames, kWarmupFrames, devices.summary().c_str());
    // The scenes' surfaces as this device stores them (SurfaceFormat::Auto: float16 on a GPU).
    std::printf("Surfaces: %s texels (--surface-format %s)\n\n",
                surfaceFormatName(chooseSurfaceFormat(options.surfaceFormat)), surfaceFormatName(options.surfaceFormat));
    std::printf("Device time, ms (CL kernels by event profiling, VkFFT's included; GL passes by timer queries). A draw\n"
                "is the whole scene drawn with that technique (its shadow map, the pyramids' build from the new heights\n"
                "(bounds: hier's, and the bounded searches' of the ocean's POM), hier's texel shadows where they pay and\n"
                "its beam start included); frame = kernels + transfer + POM draw, the transfer counted as the longer of\n"
                "its CPU wall clock (map or read, copies, GL's upload calls) and the GL upload's device time; the share\n"
                "is the compute and the transfer's part of the frame. On a CPU rasteriser the GL passes are timed by the\n"
                "CPU clock around glFinish (GpuTimer.h).\n\n"
                "| scene | field | kernels | GL upload | transfer (wall) | POM draw | POM no shadows | "
                "NM draw | own technique draw (beam, bounds, texel shadows) | frame | POM/NM | compute+transfer share |\n"
                "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    std::string wallRows, skyRows;
    RenderTarget target(width, height);
    target.bind();
    for (const char* name : {"water", "decals", "planet", "noise"})
        for (int size : {256, 512, 1024}) {
            // The noise scene from its own default size (256²), the others from 512².
            if (!wanted(name) || (size == 256 && std::string(name) != "noise")) continue;
            SceneOptions o = options;
            o.fieldSize = size;
            // The height bounds (hier) are built each frame, so their cost shows; the ocean as shipped has
            // four cascades, which hier cannot trace (one grid), so water runs POM.
            o.technique = std::string(name) == "water" ? Technique::ParallaxOcclusion : Technique::Hierarchical;
            o.width = width;
            o.height = height;
            auto scene = makeScene(name, cl, o);
            const Budget b = measure(*scene, target, cl, frames);
            // The texel shadows drawn or not in measure()'s hier draws (the exact tracer's choice;
            // sequentialAndOverlapped draws POM) and the pixels per texel that chose it: the
            // surface's quad on this image over the field's texels.
            char texels[64] = "-";
            if (scene->pixelsPerTexel() > 0.0)
                std::snprintf(texels, sizeof texels, "%s (%.2f px/texel)", scene->texelShadowsLabel().c_str(),
                              scene->pixelsPerTexel());
            // Where hier walked (TracePass::Auto: the device's, and its trial's medians where it timed both).
            const std::string pass = scene->tracePassLabel();
            const auto [sequential, overlapped] = sequentialAndOverlapped(*scene, target, frames);
            const auto& config = scene->effect().textures().config();
            char ownDraw[96] = "(POM)", ownWall[64] = "(POM)";
            if (b.own > 0.0) {
                std::snprintf(ownDraw, sizeof ownDraw, "%s %.2f (%.2f, %.2f, %.2f)", techniqueName(o.technique),
                              b.gpuOwn, b.ownBeam, b.ownBounds, b.ownTexels);
                std::snprintf(ownWall, sizeof ownWall, "%s %.2f", techniqueName(o.technique), b.own);
            }
            std::printf("| %s | %dx%d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %s | %.2f | %.2fx | %.1f%% |\n", name,
                        config.width, config.height, b.kernels, b.glUpload, b.upload, b.gpuPom,
                        b.gpuUnshadowed, b.gpuNm, ownDraw, b.gpuFrame(), b.gpuPom / b.gpuNm, 100.0 * b.computeShare());
            std::fflush(stdout);
            char row[768];
            std::snprintf(row, sizeof row,
                          "| %s | %dx%d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %.1f | %.2fx | %.1f%% | "
                          "%.1f (%.1f sequential) | %ld | %s | %s | %s |\n",
                          name, config.width, config.height, b.field, b.normals, b.extra, b.upload, b.pom, b.unshadowed,
                          b.nm, b.frame(), 1000.0 / b.frame(), b.pom / b.nm, 100.0 * (b.compute() + b.upload) / b.frame(),
                          overlapped, sequential, peakResidentMiB(), ownWall, texels, pass.empty() ? "-" : pass.c_str());
            wallRows += row;
            if (b.gpuPomClear > 0.0) {
                std::snprintf(row, sizeof row,
                              "| %s | %dx%d | %.2f | %.2f | %.2fx | %.2f | %.2f | %.2fx | %.2f | %.2f | %.2fx |\n", name,
                              config.width, config.height, b.gpuPom, b.gpuPomClear, b.gpuPom / b.gpuPomClear, b.gpuNm,
                              b.gpuNmClear, b.gpuNm / b.gpuNmClear, b.gpuSky, b.gpuSkyClear, b.gpuSky / b.gpuSkyClear);
                skyRows += row;
            }
        }
    if (!wallRows.empty())
        std::printf("\nCPU wall clock, ms, each stage waited for (glFinish, clFinish) on its own, the same frames:\n\n"
                    "| scene | field | step | normals | pyramid/extra | upload | POM draw | POM no shadows | NM draw | "
                    "frame | fps | POM/NM | compute+upload share | overlapped frame | peak RSS MiB | own technique draw | "
                    "texel shadows | hier walked in |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n%s",
                    wallRows.c_str());
    if (!skyRows.empty())
        std::printf("\nThe water's clouds (WaterLook::cloudCover): device time of the draws above (the sky pass and the\n"
                    "sea, which reflects them and lies in their shadows) against the same draws under a clear sky, the\n"
                    "same frames, and the POM draws' sky pass alone:\n\n"
                    "| scene | field | POM draw | POM, clear sky | ratio | NM draw | NM, clear sky | ratio | sky pass | "
                    "sky pass, clear | ratio |\n|---|---|---|---|---|---|---|---|---|---|---|\n%s",
                    skyRows.c_str());

    if (wanted("transfer")) {
        // A path the device lacks is named with its reason, which a lent machine's run should say.
        std::printf("\n");
        for (TransferPath path : {TransferPath::GlSharing, TransferPath::ExternalMemory})
            if (const std::string why = transferPathRefusal(cl, path); !why.empty())
                std::printf("Not offered: %s\n", why.c_str());
        std::printf("\nTransfer of the water field by surface format and path (POM with shadows): the transfer's CPU wall\n"
                    "clock (what the frame waits for: map or read, copy, GL upload calls) and its rate, the GL upload's GPU\n"
                    "time, the kernels' device time (extra: packing included), the POM draw's GPU time:\n\n"
                    "| field | format | path | bytes / frame | transfer (wall) | GB/s | GL upload | kernels | POM draw | "
                    "compute+transfer share |\n|---|---|---|---|---|---|---|---|---|---|\n");
        for (int size : {512, 1024})
            for (SurfaceFormat format : kSurfaceFormats)
                for (TransferPath path : availableTransferPaths(cl)) {
                    SceneOptions o = options;
                    o.fieldSize = size;
                    o.technique = Technique::ParallaxOcclusion;
                    o.surfaceFormat = format;
                    o.transfer = path;
                    o.width = width;
                    o.height = height;
                    auto scene = makeScene("water", cl, o);
                    const Budget b = measure(*scene, target, cl, frames, Draws::PomOnly);
                    // The ocean's cascades: one surface each, all moved every frame.
                    const double bytes = double(texelBytes(format)) * size * size *
                                         double(scene->effect().layers().size());
                    std::printf("| %d² | %s | %s | %.1f MiB | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f%% |\n", size,
                                surfaceFormatName(format), transferPathName(path), bytes / (1024.0 * 1024.0), b.upload,
                                bytes / (b.upload * 1e6), b.glUpload, b.kernels, b.gpuPom, 100.0 * b.computeShare());
                    std::fflush(stdout);
                }
    }

    if (!wanted("scaling")) return 0;
    std::printf("\nScaling of the water frame (POM with shadows): device time of the kernels, the GL upload and the\n"
                "draw, the transfer's wall clock:\n\n| field | output | kernels | transfer (wall) | GL upload | POM draw | "
                "frame |\n|---|---|---|---|---|---|---|\n");
    auto scaling = [&](int size, int w, int h) {
        SceneOptions o = options;
        // POM, as the water ships: with the bench's own default technique (hier) the ocean runs
        // a single cascade.
        o.technique = Technique::ParallaxOcclusion;
        o.fieldSize = size;
        o.width = w;
        o.height = h;
        RenderTarget t(w, h);
        t.bind();
        auto scene = makeScene("water", cl, o);
        const Budget b = measure(*scene, t, cl, frames, Draws::PomOnly);
        std::printf("| %d² | %dx%d | %.2f | %.2f | %.2f | %.2f | %.2f |\n", size, w, h, b.kernels, b.upload, b.glUpload,
                    b.gpuPom, b.gpuFrame());
        std::fflush(stdout);
    };
    for (int size : {256, 512, 1024}) scaling(size, width, height); // the ocean's cascades are at most 1024²
    for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1920, 1080}}) scaling(512, w, h);
    return 0;
}

} // namespace hfx::demo
