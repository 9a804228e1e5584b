// hfx-demo bench: one run measuring the frame at width x height, POM against normal mapping,
// and the share of compute + upload of the field. Medians of interleaved frames, so a noisy
// neighbour on the machine hits both techniques alike.

#include "Scene.h"

#include "hfx/core/Gl.h"
#include "hfx/core/GlContext.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

namespace hfx::demo {
namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

template <typename F>
double timeMs(F&& f) {
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    f();
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

int runBench(const SceneOptions& options, int width, int height, int frames) {
    auto gl = createHeadlessContext({.width = width, .height = height});
    ClContext cl;
    SceneOptions pomOptions = options;
    pomOptions.technique = Technique::ParallaxOcclusion;
    SceneOptions nmOptions = options;
    nmOptions.technique = Technique::NormalMapping;
    SceneOptions unshadowedOptions = pomOptions;
    unshadowedOptions.shadows = false;
    auto pom = makeWaterScene(cl, pomOptions);
    auto unshadowed = makeWaterScene(cl, unshadowedOptions);
    auto nm = makeWaterScene(cl, nmOptions);
    RenderTarget target(width, height);
    target.bind();

    std::vector<double> compute, upload, drawPom, drawUnshadowed, drawNm;
    for (int frame = -2; frame < frames; ++frame) { // two warm-up frames build and settle
        const double u = timeMs([&] { pom->update(1.0 / 30.0); });
        const StageTimes stages = pom->effect().lastTimes();
        const double p = timeMs([&] { target.clear(); pom->draw(); });
        const double s = timeMs([&] { target.clear(); unshadowed->draw(); });
        const double n = timeMs([&] { target.clear(); nm->draw(); });
        if (frame < 0) continue;
        drawUnshadowed.push_back(s);
        compute.push_back(stages.compute);
        upload.push_back(u - stages.compute);
        drawPom.push_back(p);
        drawNm.push_back(n);
    }
    const double c = median(compute), up = median(upload), dp = median(drawPom), dn = median(drawNm);
    const double ds = median(drawUnshadowed);
    const int field = pom->effect().textures().config().width;
    std::printf("hfx-demo bench: %dx%d, field %dx%d, %d frames (medians), %s\n", width, height, field, field,
                frames, gl->description().c_str());
    std::printf("OpenCL: %s\n", cl.description().c_str());
    std::printf("| stage | ms |\n|---|---|\n");
    std::printf("| field compute (%s waves + Sobel) | %.2f |\n", options.waves.c_str(), c);
    std::printf("| upload (map + texture + mips) | %.2f |\n", up);
    std::printf("| draw, normal mapping | %.2f |\n", dn);
    const SurfaceMaterial& m = pom->material();
    std::printf("| draw, POM %d..%d samples + %d-sample soft shadows | %.2f |\n", m.minSamples, m.maxSamples,
                m.shadowSamples, dp);
    std::printf("| draw, POM %d..%d samples, no shadows | %.2f |\n", m.minSamples, m.maxSamples, ds);
    std::printf("POM / normal mapping draw: %.2fx (without shadows %.2fx)\n", dp / dn, ds / dn);
    std::printf("compute + upload share of the POM frame: %.1f%%\n", 100.0 * (c + up) / (c + up + dp));
    return 0;
}

} // namespace hfx::demo
