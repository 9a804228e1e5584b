// hfx-demo bench-accuracy: every technique against the exact intersection, on four maps at five
// view angles; writes docs/ACCURACY.md (the table), a plot of error against fetches and crops of
// each technique at 80 degrees. Depth scale 0.1 texture widths, mip level 0, 8..32 samples.

#include "hfx/compute/DecalMap.h"
#include "hfx/compute/NoiseField.h"
#include "hfx/core/Error.h"
#include "hfx/effects/BrickWall.h"
#include "hfx/platform/GlContext.h"
#include "hfx/tools/AccuracyProbe.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

namespace hfx::demo {
namespace {

struct Map {
    std::string name;
    std::vector<float> heights;
};

std::vector<float> readBuffer(ClContext& cl, const cl::Buffer& buffer, size_t n) {
    std::vector<float> out(n);
    cl.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, n * sizeof(float), out.data());
    return out;
}

std::vector<Map> makeMaps(ClContext& cl, int n) {
    std::vector<Map> maps;
    std::vector<float> sines(size_t(n) * n);
    const double k = 2.0 * std::numbers::pi / n;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            sines[size_t(y) * n + x] = float(0.5 + 0.22 * std::sin(k * (3 * x + 1 * y) + 0.3) +
                                             0.13 * std::sin(k * (-2 * x + 5 * y) + 1.1) +
                                             0.07 * std::sin(k * (7 * x + 4 * y) + 2.0));
    maps.push_back({"smooth waves", sines});
    BrickWallMaps bricks = makeBrickWall({.size = n});
    maps.push_back({"bricks", bricks.heights});
    NoiseField noise(cl, {.width = n, .height = n, .frequency = 6.0f, .octaves = 5});
    std::vector<float> noisy = readBuffer(cl, noise.buffer(), size_t(n) * n);
    for (float& h : noisy) h = std::clamp(0.5f + 0.9f * (h - 0.5f), 0.0f, 1.0f);
    maps.push_back({"noise", noisy});
    DecalMap decals(cl, {.width = n, .height = n}, bricks.heights);
    for (int i = 0; i < 40; ++i)
        decals.addBulletHole({.u = float(std::fmod(0.137 * i * 7.3, 1.0)), .v = float(std::fmod(0.291 * i * 3.1, 1.0)),
                              .radius = 0.02f, .depth = 0.5f});
    decals.addExplosion({.u = 0.6f, .v = 0.4f, .radius = 0.08f, .debris = 30});
    decals.step(1.0 / 30.0);
    maps.push_back({"damaged wall", readBuffer(cl, decals.buffer(), size_t(n) * n)});
    return maps;
}

/// A scatter plot, log10 error (texels) against fetches, one colour per technique, drawn into
/// an RGB image: axes, a grid line per decade and every 10 fetches.
Image plot(const std::vector<std::tuple<Technique, double, double>>& points, const std::map<Technique, glm::vec3>& colors) {
    constexpr int W = 720, H = 480, left = 50, bottom = 40, right = 20, top = 20;
    Image image{W, H, 3, std::vector<float>(size_t(W) * H * 3, 1.0f)};
    double maxFetch = 10.0;
    for (const auto& [t, f, e] : points) maxFetch = std::max(maxFetch, f);
    maxFetch = std::ceil(maxFetch / 10.0) * 10.0;
    const double minLog = -4.0, maxLog = 2.0;
    auto px = [&](double f) { return left + int((W - left - right) * f / maxFetch); };
    auto py = [&](double e) {
        const double l = std::clamp(std::log10(std::max(e, 1e-4)), minLog, maxLog);
        return H - bottom - int((H - top - bottom) * (l - minLog) / (maxLog - minLog));
    };
    auto set = [&](int x, int y, glm::vec3 c) {
        if (x >= 0 && y >= 0 && x < W && y < H)
            for (int k = 0; k < 3; ++k) image.at(x, y, k) = c[k];
    };
    for (int d = int(minLog); d <= int(maxLog); ++d)
        for (int x = left; x < W - right; ++x) set(x, py(std::pow(10.0, d)), glm::vec3(d == 0 ? 0.6f : 0.85f));
    for (double f = 0; f <= maxFetch; f += 10)
        for (int y = top; y < H - bottom; ++y) set(px(f), y, glm::vec3(0.85f));
    for (int x = left; x < W - right; ++x) set(x, H - bottom, glm::vec3(0.0f));
    for (int y = top; y < H - bottom; ++y) set(left, y, glm::vec3(0.0f));
    for (const auto& [t, f, e] : points) {
        const int cx = px(f), cy = py(e);
        for (int dy = -3; dy <= 3; ++dy)
            for (int dx = -3; dx <= 3; ++dx) set(cx + dx, cy + dy, colors.at(t));
    }
    return image;
}

} // namespace

int runBenchAccuracy(const std::string& outDir, int field) {
    auto gl = createHeadlessContext({.width = 64, .height = 64});
    ClContext cl;
    const std::vector<Map> maps = makeMaps(cl, field);
    const double angles[] = {0, 45, 70, 80, 85};
    // One colour per row of the technique table, in its order.
    const std::pair<const char*, glm::vec3> palette[] = {
        {"grey", {0.5f, 0.5f, 0.5f}},   {"orange", {0.9f, 0.6f, 0.0f}}, {"red", {0.8f, 0.1f, 0.1f}},
        {"green", {0.1f, 0.6f, 0.1f}},  {"purple", {0.6f, 0.2f, 0.8f}}, {"blue", {0.1f, 0.3f, 0.9f}},
        {"black", {0.0f, 0.0f, 0.0f}},  {"brown", {0.55f, 0.3f, 0.1f}}, {"cyan", {0.0f, 0.7f, 0.8f}}};
    static_assert(std::size(palette) >= kTechniqueCount, "a colour for every technique");
    std::map<Technique, glm::vec3> colors;
    for (size_t i = 0; i < kTechniqueCount; ++i) colors[kTechniques[i]] = palette[i].second;
    const glm::vec3 light(std::sin(1.0472f) * 0.8f, std::cos(1.0472f), std::sin(1.0472f) * 0.6f); // 60 degrees

    std::ostringstream md;
    md << "# Accuracy of the surface techniques\n\n"
       << "Generated by `build/demo/hfx-demo bench-accuracy --out docs` (" << gl->description() << "). Each pixel's\n"
       << "hit is compared with the exact intersection of the bilinear surface (HeightFieldTracer, double\n"
       << "precision); fields " << field << "x" << field << ", depth scale 0.1 texture widths, mip level 0, 8..32\n"
       << "samples (the shadow pass: 8 samples, light 60 degrees off the normal), a 192x192 render of a plane\n"
       << "spanning one texture. Columns: texcoord error in texels (mean, 95th percentile), share of pixels\n"
       << "more than 4 texels off, mean height fetches per pixel counted in the shader (without shadows),\n"
       << "mean error of the depth fraction written to gl_FragDepth, agreement of the self-shadow with exact\n"
       << "shadow rays outside a 1.5-texel band around shadow edges (techniques without shadows: n/a),\n"
       << "and the median draw time of a 1280x720 frame filled by the plane at that angle (with the\n"
       << "technique's shadows: soft for pom, secant and hier, hard for steep and relief).\n\n";
    std::vector<std::tuple<Technique, double, double>> points;
    constexpr int kCropW = 180, kCropH = 180;
    Image strip{kCropW * int(std::size(kTechniques)), kCropH, 3,
                std::vector<float>(size_t(kCropW) * std::size(kTechniques) * kCropH * 3)};
    std::map<std::pair<std::string, double>, double> hierMean, hierFetches;
    for (const Map& map : maps) {
        AccuracyProbe probe(cl, map.heights, field, 0.1f);
        md << "## " << map.name << "\n\n| angle | technique | mean | p95 | > 4 texels | fetches | depth error | shadow agreement | ms 1280x720 |\n"
           << "|---|---|---|---|---|---|---|---|---|\n";
        for (double angle : angles) {
            for (size_t ti = 0; ti < std::size(kTechniques); ++ti) {
                const Technique t = kTechniques[ti];
                const AccuracyResult r = probe.measure(t, {.angleDegrees = angle});
                const bool hasShadows = techniqueInfo(t).shadow != SelfShadow::None;
                const AccuracyResult s =
                    hasShadows ? probe.measure(t, {.angleDegrees = angle, .shadows = true, .light = light}) : AccuracyResult{};
                char shadow[32] = "n/a", ms[32] = "-";
                if (hasShadows) std::snprintf(shadow, sizeof shadow, "%.1f%%", 100.0 * s.shadowAgreement);
                // Timed with shadows where the technique has them, as a renderer would draw it.
                if (angle <= 80)
                    std::snprintf(ms, sizeof ms, "%.1f",
                                  probe.timeDraw(t, {.angleDegrees = angle, .shadows = hasShadows, .light = light}, 1280, 720, 3));
                char line[400];
                std::snprintf(line, sizeof line, "| %.0f | %s | %.3f | %.3f | %.2f%% | %.1f | %.4f | %s | %s |\n", angle,
                              techniqueName(t), r.mean, r.p95, 100.0 * r.over4, r.fetches, r.depthMean, shadow, ms);
                md << line;
                if (techniqueInfo(t).traces) points.emplace_back(t, r.fetches, r.mean);
                if (t == Technique::Hierarchical) {
                    hierMean[{map.name, angle}] = r.mean;
                    hierFetches[{map.name, angle}] = r.fetches;
                }
                if (angle == 80 && map.name == "bricks") {
                    // The middle of the timed 1280x720 frame.
                    const Image& image = probe.lastFrame();
                    for (int y = 0; y < kCropH; ++y)
                        for (int x = 0; x < kCropW; ++x)
                            for (int c = 0; c < 3; ++c)
                                strip.at(int(ti) * kCropW + x, y, c) = image.at(640 - kCropW / 2 + x, 360 - kCropH / 2 + y, c);
                }
            }
        }
        // How many linear POM samples reach the hierarchical tracer's error at grazing angles.
        md << "\nPOM with more samples against the hierarchical tracer (same map):\n\n"
           << "| angle | POM max samples | POM mean | POM fetches | hier mean | hier fetches |\n|---|---|---|---|---|---|\n";
        for (double angle : {80.0, 85.0})
            for (int samples : {32, 64, 128, 256}) {
                const AccuracyResult r = probe.measure(Technique::ParallaxOcclusion,
                                                       {.angleDegrees = angle, .minSamples = 8, .maxSamples = samples});
                char line[200];
                std::snprintf(line, sizeof line, "| %.0f | %d | %.4f | %.1f | %.4f | %.1f |\n", angle, samples, r.mean,
                              r.fetches, hierMean[{map.name, angle}], hierFetches[{map.name, angle}]);
                md << line;
            }
        md << "\n";
        std::fprintf(stderr, "bench-accuracy: %s done\n", map.name.c_str());
    }
    // What the smaller surface formats (packed on the device, SurfacePacker) cost in accuracy.
    md << "## Surface formats\n\nThe same renders with the surface stored as RGBA32F (float32), RGBA16F "
          "(float16: half the memory and transfer) and RGBA8 (unorm8: a quarter; normal as n/2 + 1/2, "
          "heights in steps of 1/255, no pyramid and so no hier), packed on the device as the effects do: "
          "mean texel error, and POM's p95.\n\n"
       << "| map | angle | pom float32 | pom float16 | pom unorm8 | pom p95 float32 / unorm8 | hier float32 | "
          "hier float16 |\n|---|---|---|---|---|---|---|---|\n";
    for (const Map& map : maps) {
        AccuracyProbe full(cl, map.heights, field, 0.1f);
        AccuracyProbe half(cl, map.heights, field, 0.1f, SurfaceFormat::Float16);
        AccuracyProbe bytes(cl, map.heights, field, 0.1f, SurfaceFormat::Unorm8);
        for (double angle : {70.0, 85.0}) {
            const AccuracyResult pf = full.measure(Technique::ParallaxOcclusion, {.angleDegrees = angle});
            const AccuracyResult pb = bytes.measure(Technique::ParallaxOcclusion, {.angleDegrees = angle});
            char line[240];
            std::snprintf(line, sizeof line, "| %s | %.0f | %.4f | %.4f | %.4f | %.3f / %.3f | %.4f | %.4f |\n",
                          map.name.c_str(), angle, pf.mean,
                          half.measure(Technique::ParallaxOcclusion, {.angleDegrees = angle}).mean, pb.mean, pf.p95,
                          pb.p95, full.measure(Technique::Hierarchical, {.angleDegrees = angle}).mean,
                          half.measure(Technique::Hierarchical, {.angleDegrees = angle}).mean);
            md << line;
        }
    }
    md << "\n";
    md << "## Plot and crops\n\n![error against fetches](accuracy/plot.png)\n\n"
       << "Mean error (texels, log scale, 1e-4 to 100; grid lines per decade, the darker one at 1 texel)\n"
       << "against mean fetches per pixel (grid every 10), one point per map and angle. Colours: ";
    std::string legend, order;
    for (size_t i = 0; i < kTechniqueCount; ++i) {
        if (techniqueInfo(kTechniques[i]).traces)
            legend += str(legend.empty() ? "" : ", ", techniqueName(kTechniques[i]), " ", palette[i].first);
        order += str(order.empty() ? "" : ", ", techniqueName(kTechniques[i]));
    }
    md << legend << ".\n\n![crops at 80 degrees](accuracy/crops_80.jpg)\n\nThe bricks map at 80 degrees, left to right: "
       << order << ".\n";
    std::filesystem::create_directories(std::filesystem::path(outDir) / "accuracy");
    writeImage((std::filesystem::path(outDir) / "accuracy" / "plot.png").string(), plot(points, colors));
    writeImage((std::filesystem::path(outDir) / "accuracy" / "crops_80.jpg").string(), strip);
    const std::string mdPath = (std::filesystem::path(outDir) / "ACCURACY.md").string();
    std::ofstream(mdPath) << md.str();
    std::printf("%s", md.str().c_str());
    std::printf("wrote %s\n", mdPath.c_str());
    return 0;
}

/// hfx-demo bench-tracers: the exact tracer's draw time against POM 8..32's, both with their soft
/// self-shadows, at 1280x720 in one run: rounds of one draw each, interleaved, medians. Prints a
/// table and, with --out, writes tracers.csv. `only` restricts the maps by name.
int runBenchTracers(const std::string& outDir, int field, const std::vector<std::string>& only, int rounds) {
    auto gl = createHeadlessContext({.width = 64, .height = 64});
    ClContext cl;
    const glm::vec3 light(std::sin(1.0472f) * 0.8f, std::cos(1.0472f), std::sin(1.0472f) * 0.6f); // 60 degrees
    const Technique techniques[] = {Technique::ParallaxOcclusion, Technique::Hierarchical};
    std::ostringstream csv;
    csv << "map,angle,technique,shadows,ms,ratio_to_pom\n";
    std::printf("%s, field %dx%d, 1280x720, median of %d interleaved draws\n\n| map | angle | pom ms | hier ms | hier / pom |\n"
                "|---|---|---|---|---|\n", gl->description().c_str(), field, field, rounds);
    for (const Map& map : makeMaps(cl, field)) {
        if (!only.empty() && std::find(only.begin(), only.end(), map.name) == only.end()) continue;
        AccuracyProbe probe(cl, map.heights, field, 0.1f);
        for (double angle : {0.0, 45.0, 70.0, 80.0}) {
            const AccuracyConfig config{.angleDegrees = angle, .shadows = true, .light = light};
            std::map<Technique, std::vector<double>> times;
            for (Technique t : techniques) probe.timeDraw(t, config, 1280, 720, 1); // shaders built, caches warm
            for (int r = 0; r < rounds; ++r)
                for (Technique t : techniques) times[t].push_back(probe.timeDraw(t, config, 1280, 720, 1));
            std::map<Technique, double> median;
            for (auto& [t, v] : times) {
                std::sort(v.begin(), v.end());
                median[t] = v[v.size() / 2];
            }
            const double pom = median[Technique::ParallaxOcclusion];
            for (Technique t : techniques)
                csv << map.name << "," << angle << "," << techniqueName(t) << ",soft," << median[t] << "," << median[t] / pom << "\n";
            std::printf("| %s | %.0f | %.1f | %.1f | %.2fx |\n", map.name.c_str(), angle, pom, median[Technique::Hierarchical],
                        median[Technique::Hierarchical] / pom);
            std::fflush(stdout);
        }
    }
    if (!outDir.empty()) {
        std::filesystem::create_directories(outDir);
        const std::string path = (std::filesystem::path(outDir) / "tracers.csv").string();
        std::ofstream(path) << csv.str();
        std::printf("wrote %s\n", path.c_str());
    }
    return 0;
}

} // namespace hfx::demo
