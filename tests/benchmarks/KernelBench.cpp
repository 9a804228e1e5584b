// hfx-bench-kernels: every compute kernel at 512^2 and 2048^2, timed per step (enqueue to
// finish, and the kernels' device time by CL event profiling), with two ratios taken in the same run: against a single-threaded C++ reference of the
// same math, and the bytes the kernel must move per second against plain memcpy bandwidth.
//
//   build/tests/hfx-bench-kernels --benchmark_counters_tabular=true

#include "support/Fields.h"
#include "support/References.h"

#include "hfx/compute/DamageLog.h"
#include "hfx/compute/DecalMap.h"
#include "hfx/compute/FlowDetail.h"
#include "hfx/compute/GasField.h"
#include "hfx/compute/InverseRealFft.h"
#include "hfx/compute/BoundsPyramid.h"
#include "hfx/compute/NoiseField.h"
#include "hfx/compute/OceanField.h"
#include "hfx/compute/OceanQuery.h"
#include "hfx/compute/PolarFilter.h"
#include "hfx/compute/SobelNormals.h"
#include "hfx/compute/WaveField.h"
#include "hfx/compute/shared/NoiseMath.h"
#include "hfx/core/Random.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/GasPlanetEffect.h"
#include "hfx/effects/GlStatePolicy.h"
#include "hfx/effects/Picking.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/platform/GlContext.h"

#include <benchmark/benchmark.h>
#include <fftw3.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <numbers>
#include <random>

namespace hfx::test {
namespace {

using Clock = std::chrono::steady_clock;

ClContext& cl() {
    static ClContext* context = new ClContext({.log = false}); // outlives every benchmark
    return *context;
}

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

/// Mean seconds of f over repeats lasting at least minSeconds.
double timeIt(const std::function<void()>& f, double minSeconds = 0.3) {
    int runs = 0;
    const auto start = Clock::now();
    do {
        f();
        ++runs;
    } while (seconds(start, Clock::now()) < minSeconds);
    return seconds(start, Clock::now()) / runs;
}

/// Single-threaded memcpy bandwidth (bytes/s, counting read + write), measured once.
double memcpyBandwidth() {
    static const double bandwidth = [] {
        const size_t bytes = size_t(64) << 20;
        std::vector<char> a(bytes, 1), b(bytes);
        const double t = timeIt([&] {
            std::memcpy(b.data(), a.data(), bytes);
            benchmark::DoNotOptimize(b.data());
        });
        return 2.0 * bytes / t;
    }();
    return bandwidth;
}

std::vector<float> randomHeights(int n, unsigned seed = 1) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> h(size_t(n) * n);
    for (float& v : h) v = unit(random);
    return h;
}

/// Times `step` (one device step, then finish) in the benchmark loop and reports: ms per step,
/// GB/s of `bytesPerStep`, that as a fraction of memcpy, and the reference's time over the
/// kernel's (the reference is run once per benchmark, in the same process).
void measure(benchmark::State& state, const std::function<void()>& step, double bytesPerStep,
             const std::function<void()>& reference) {
    step(); // first launch compiles and picks the local size
    cl().queue().finish();
    double total = 0, device = 0;
    int64_t steps = 0;
    for (auto _ : state) {
        cl().recordKernelTimes(true);
        const auto start = Clock::now();
        step();
        cl().queue().finish();
        total += seconds(start, Clock::now());
        cl().recordKernelTimes(false);
        for (const auto& [kernel, ms] : cl().takeKernelTimes()) device += ms;
        ++steps;
    }
    const double perStep = total / double(steps);
    state.counters["ms"] = perStep * 1e3;
    // The kernels' own time on the device (CL event profiling, VkFFT's included), without the
    // enqueue-and-wait cost the wall clock above adds.
    state.counters["device_ms"] = device / double(steps);
    state.counters["GB/s"] = bytesPerStep / perStep / 1e9;
    state.counters["of_memcpy"] = bytesPerStep / perStep / memcpyBandwidth();
    if (reference) state.counters["x_1thread"] = timeIt(reference, 0.2) / perStep;
}

void BM_Sobel(benchmark::State& state) {
    const int n = int(state.range(0));
    const auto heights = randomHeights(n);
    cl::Buffer input(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, heights.size() * 4,
                     const_cast<float*>(heights.data()));
    SobelNormals sobel(cl(), {.width = n, .height = n});
    // 9 reads hit the cache; memory sees one float in and one float4 out per texel.
    measure(state, [&] { sobel.run(input); }, 20.0 * n * n,
            [&] { benchmark::DoNotOptimize(sobelReference(heights, n, 0.05f)); });
}

/// The two Sobel kernels side by side on the same input: one texel per work-item (what widths
/// that are not a multiple of 4 run) and four (SobelNormals' choice otherwise).
void BM_SobelKernel(benchmark::State& state) {
    const int n = int(state.range(0)), perItem = int(state.range(1));
    const auto heights = randomHeights(n);
    cl::Buffer input(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, heights.size() * 4,
                     const_cast<float*>(heights.data()));
    cl::Buffer output(cl().context(), CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR, heights.size() * 16);
    cl::Kernel kernel = cl().kernel("sobel.cl", perItem == 4 ? "sobel4" : "sobel", edgeOptions(EdgeMode::Wrap));
    kernel.setArg(0, input);
    kernel.setArg(1, output);
    kernel.setArg(2, n);
    kernel.setArg(3, n);
    kernel.setArg(4, 0.05f * n);
    kernel.setArg(5, 0.05f * n);
    measure(state, [&] { cl().enqueue(kernel, cl::NDRange(n / perItem, n)); },
            20.0 * n * n, nullptr);
}

/// The gas's pressure sweep (walls in y) side by side: one cell per work-item and four.
void BM_GasPressureKernel(benchmark::State& state) {
    const int n = int(state.range(0)), perItem = int(state.range(1));
    const auto p0 = randomHeights(n, 2), div = randomHeights(n, 3);
    auto buffer = [&](const std::vector<float>& v) {
        return cl::Buffer(cl().context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, v.size() * 4, const_cast<float*>(v.data()));
    };
    cl::Buffer p = buffer(p0), d = buffer(div), out = buffer(p0), metric = buffer(gasMetricTable({.width = n, .height = n}));
    cl::Kernel kernel = cl().kernel("gas.cl", perItem == 4 ? "pressure4" : "pressure", edgeOptions(EdgeMode::WrapU));
    setArgs(kernel, p, d, metric, out, n, n);
    measure(state, [&] { cl().enqueue(kernel, cl::NDRange(n / perItem, n)); },
            12.0 * n * n, nullptr);
}

void BM_Waves(benchmark::State& state) {
    const int n = int(state.range(0));
    WaveField waves(cl(), {.size = n});
    measure(state, [&] { waves.step(1.0 / 60); }, 4.0 * n * n,
            [&] { benchmark::DoNotOptimize(wavesReference(waves.config(), 1.0)); });
}

void BM_Noise(benchmark::State& state) {
    const int n = int(state.range(0));
    NoiseField noise(cl(), {.width = n, .height = n, .kind = NoiseKind::Perlin, .octaves = 4});
    const NoiseConfig& c = noise.config();
    measure(state, [&] { noise.step(1.0 / 60); }, 4.0 * n * n, [&] {
        std::vector<float> h(size_t(n) * n);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                h[size_t(y) * n + x] = hfx_noise_texel(0, 0, (x + 0.5f) / n, (y + 0.5f) / n, c.frequency, c.frequencyY(),
                                                       1, 1, 0.5f, c.octaves, c.lacunarity, c.gain, c.warp);
        benchmark::DoNotOptimize(h.data());
    });
}

void BM_Decals(benchmark::State& state) {
    // One step with 2000 bullet holes (radius 1% of the width) stamped into the map.
    const int n = int(state.range(0));
    const DecalConfig config{.width = n, .height = n};
    DecalMap map(cl(), config);
    std::mt19937 random(3);
    std::uniform_real_distribution<float> unit(0.0f, 0.999f);
    std::vector<BulletHole> holes;
    for (int i = 0; i < 2000; ++i) holes.push_back({.u = unit(random), .v = unit(random)});
    const std::vector<float> base(size_t(n) * n, config.baseHeight);
    // Memory: base and damage in, damage and height out, per texel.
    measure(state, [&] {
        map.addBulletHoles(holes);
        map.step(1.0 / 60);
    }, 16.0 * n * n, [&] {
        std::vector<float> damage(base.size(), 0.0f);
        decalsReference(config, base, damage, holes);
        for (size_t i = 0; i < damage.size(); ++i) damage[i] = std::clamp(base[i] + damage[i], 0.0f, 1.0f);
        benchmark::DoNotOptimize(damage.data());
    });
}

/// DamageLog::add into a full log (every add evicts or merges): the O(1) insertion, per impact.
void BM_DamageLogAdd(benchmark::State& state) {
    DamageLog log({.budget = int(state.range(0))});
    SplitMix64 random(4);
    auto impact = [&] {
        return ImpactEvent{.u = float(random.uniform(0.0, 0.999)), .v = float(random.uniform(0.0, 0.999)),
                           .seed = random.nextBits()};
    };
    for (int i = 0; i < 4 * log.budget(); ++i) log.add(impact());
    std::vector<ImpactEvent> batch(4096);
    for (auto _ : state) {
        state.PauseTiming();
        for (ImpactEvent& e : batch) e = impact();
        state.ResumeTiming();
        for (const ImpactEvent& e : batch) benchmark::DoNotOptimize(log.add(e));
    }
    state.SetItemsProcessed(state.iterations() * int64_t(batch.size()));
    state.counters["merged_share"] = double(log.merged()) / double(log.added());
}

/// The wall's decal pass at {size, budget}: a full log (one impact in 50 an explosion with 40
/// debris) expanded into stamps with their heal curves, binned and rebuilt into heights, scorched
/// albedo and shading channels.
void BM_DecalRebuild(benchmark::State& state) {
    const int n = int(state.range(0)), budget = int(state.range(1));
    DamageLog log({.budget = budget});
    SplitMix64 random(6);
    for (int i = 0; i < budget; ++i)
        log.add({.u = float(random.uniform(0.0, 0.999)), .v = float(random.uniform(0.0, 0.999)),
                 .radius = i % 50 == 0 ? 0.05f : 0.012f, .kind = i % 50 == 0 ? ImpactKind::Explosion : ImpactKind::Bullet,
                 .seed = std::uint64_t(i)});
    DecalMap map(cl(), {.width = n, .height = n});
    state.counters["stamps"] = double(log.stamps().size());
    // Memory per texel: base, damage in and out, height out (floats); base albedo in, albedo and
    // channels out (RGBA8).
    measure(state, [&] {
        log.advance(1.0 / 60);
        map.addBulletHoles(log.stamps());
        map.rebuild();
    }, 28.0 * n * n, {});
}

void BM_Pyramid(benchmark::State& state) {
    const int n = int(state.range(0));
    const auto heights = randomHeights(n);
    cl::Buffer input(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, heights.size() * 4,
                     const_cast<float*>(heights.data()));
    BoundsPyramid pyramid(cl(), n, n, EdgeMode::Wrap);
    measure(state, [&] { pyramid.build(input); }, 4.0 * n * n * (1.0 + 2.0 * 4.0 / 3.0), // heights in, (max, min) pairs out
            [&] { benchmark::DoNotOptimize(pyramidReference(heights, n, n)); });
}

void BM_Gas(benchmark::State& state) {
    // A full step: jets, confinement, advection of u, v and dye (semi-Lagrangian, or MacCormack
    // when the second argument is 1), 40 pressure sweeps (the single-thread reference's solve).
    const int n = int(state.range(0));
    const GasConfig config{.width = n, .height = n, .pressure = GasPressure::Jacobi, .pressureIterations = 40,
                           .vorticity = 0.2f,
                           .maccormack = state.range(1) != 0, .conserveDye = false, .jetSpeed = 3.0f,
                           .initialBands = 4.0f};
    GasField gas(cl(), config);
    GasReference reference{config, {}, {}, {}};
    gas.readState(reference.u, reference.v, reference.dye);
    // Per step each of ~60 passes reads and writes a few fields: count the pressure sweeps
    // (2 floats in, 1 out per texel) and the advections (3 fields, ~3 passes of 4 floats).
    const double bytes = (40 * 12.0 + 3 * 3 * 16.0) * n * n;
    measure(state, [&] { gas.step(0.5); }, bytes, n <= 512 ? std::function<void()>([&] { reference.step(0.5f); })
                                                            : std::function<void()>());
}

/// The planet's gas step (GasPlanetConfig's gas: 512x256, jets, confinement, the dye's
/// relaxation) at 30 steps a second, its advection semi-Lagrangian (0) or MacCormack's (1, the
/// planet's default): what the sharper edges cost a frame; on the sphere's metric (1, the
/// planet's: the frame's turns, the metric's weights, the dye's polar filter) or the flat map (0);
/// its pressure solved exactly (jacobi 0, the planet's: the rows' two FFTs and a tridiagonal solve
/// per wavenumber) or by 30 Jacobi sweeps (1, the planet's until 2026-11-29); with the planet's
/// spin (rotation 1, the planet's: the beta term's two more FFTs and solve) or without (0; the
/// flat map cannot spin); on the CPU device's grid (grid 1) or a GPU's, 1024x512 (grid 2, where
/// the column solves' one work-item per wavenumber walks 512 rows one after another, and Jacobi
/// takes 120 sweeps).
void BM_PlanetGas(benchmark::State& state) {
    GasConfig config = GasPlanetConfig{}.gas;
    config.maccormack = state.range(0) != 0;
    config.sphere = state.range(1) != 0;
    config.pressure = state.range(2) != 0 ? GasPressure::Jacobi : GasPressure::Exact;
    config.pressureIterations = 30; // (scaledGas: 120 on the GPU's grid, as the planet had them)
    if (state.range(3) == 0) config.rotation = 0.0f;
    GasField gas(cl(), scaledGas(config, float(state.range(4))));
    for (int s = 0; s < 10; ++s) gas.step(1.0 / 30.0); // the jets under way
    cl().queue().finish();
    for (auto _ : state) {
        gas.step(1.0 / 30.0);
        cl().queue().finish();
    }
}

/// The planet's cloud-top detail a frame (FlowDetail: its layers advected a step, each cell's
/// finest octave derived, then its heights written), at 2 and 4 texels per cell of the planet's
/// 512x256 gas (a CPU device's and a GPU's scale), after 3 simulated seconds of its jets have
/// sheared the layers; the gas's own step is BM_PlanetGas. The kernel band-limits each texel's
/// noise to the octaves its squeezed lattice can show (FlowMath.h's hfx_flow_cell_finest),
/// evaluating no faded one. On the sphere's map (sphere 1, the planet's) its noise is read at the
/// sphere's points (hfx_flow_noise_sphere); on the flat map (0), on the map's.
void BM_PlanetDetail(benchmark::State& state) {
    GasPlanetConfig planet;
    planet.gas.sphere = state.range(1) != 0;
    if (!planet.gas.sphere) planet.gas.rotation = 0.0f; // a flat map cannot spin
    GasField gas(cl(), planet.gas);
    FlowDetailConfig config = planet.detail;
    config.scale = int(state.range(0));
    FlowDetail detail(cl(), gas, config);
    for (int s = 0; s < 90; ++s) {
        gas.step(1.0 / 30.0);
        detail.step(1.0 / 30.0);
    }
    cl().queue().finish();
    for (auto _ : state) {
        detail.step(1.0 / 30.0);
        detail.run();
        cl().queue().finish();
    }
}

/// The planet's polar filter a frame (PolarFilter at 0.75 degrees, what a flat gas's planet sets:
/// GasPlanetConfig::polarSmoothing), on the drawn heights at 2 and 4 texels per cell of its
/// 512x256 gas: each filtered row's prefix sums, then every texel's box. Against
/// BM_PlanetDetail, which writes the same heights.
void BM_PlanetPolarFilter(benchmark::State& state) {
    const GasPlanetConfig planet;
    const int scale = int(state.range(0)), width = planet.gas.width * scale, height = planet.gas.height * scale;
    std::vector<float> field(size_t(width) * height);
    SplitMix64 random(3);
    for (float& h : field) h = float(random.next());
    cl::Buffer in(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, field.size() * sizeof(float), field.data());
    PolarFilter polar(cl(), width, height, 0.75f);
    for (auto _ : state) {
        polar.run(in);
        cl().queue().finish();
    }
}

/// The planet's gas step with its 32 storms' upkeep (storm lengths of GasPlanetConfig's 0.025
/// widths, spread over the map): two pushing splats a storm, a storm's radius each, as storms were
/// kept spinning before 2026-11-29 (0), or each held as an oval vortex with its colour fed
/// (GasField::addVortex and a dye-target splat) and their centres' wind read once a step, as the
/// planet reads it once a frame (1); the same with the colour fed over the oval in three spiral
/// arms and the wind read a cell either side of each centre too, for its spin (2, the planet's
/// since the storms' arms).
void BM_PlanetStorms(benchmark::State& state) {
    const GasPlanetConfig planet;
    GasConfig config = planet.gas;
    GasField gas(cl(), config);
    const bool held = state.range(0) != 0, arms = state.range(0) == 2;
    std::vector<glm::vec2> centres;
    for (int i = 0; i < 32; ++i) centres.emplace_back(float(i) / 32.0f, 0.2f + 0.6f * float(i % 8) / 8.0f);
    // With arms the wind is read a cell either side of each centre too (the spin).
    std::vector<glm::vec2> samples;
    for (const glm::vec2 c : centres)
        for (const glm::vec2 d : {glm::vec2(0.0f), {1.0f, 0.0f}, {-1.0f, 0.0f}, {0.0f, 1.0f}, {0.0f, -1.0f}})
            if (arms || d == glm::vec2(0.0f))
                samples.push_back(c + d / glm::vec2(float(config.width), float(config.height)));
    auto upkeep = [&] {
        const float a = planet.stormRadius, b = a / planet.stormAspect;
        if (held) (void)gas.velocityAt(samples);
        for (const glm::vec2 c : centres) {
            if (held) {
                gas.addVortex({.u = c.x, .v = c.y, .radius = a, .aspect = planet.stormAspect, .speed = config.jetSpeed,
                               .driftX = 5.0f, .rate = planet.stormHold});
                GasSplat feed{.u = c.x, .v = c.y, .radius = b, .dye = 0.1f, .dyeTarget = 0.8f};
                if (arms)
                    feed.aspect = planet.stormAspect,
                    feed.arms = {.count = planet.stormArms, .target = 0.4f, .contrast = planet.stormArmContrast,
                                 .turned = 10.0f * c.x, .winding = planet.stormWinding, .sweep = 0.05f};
                gas.addSplat(feed);
            } else {
                const float dv = 0.5f * a * float(config.width) / float(config.height);
                gas.addSplat({.u = c.x, .v = c.y + dv, .radius = a, .forceX = 18.0f});
                gas.addSplat({.u = c.x, .v = c.y - dv, .radius = a, .forceX = -18.0f});
            }
        }
    };
    for (int s = 0; s < 10; ++s) {
        upkeep();
        gas.step(1.0 / 30.0);
    }
    cl().queue().finish();
    for (auto _ : state) {
        upkeep();
        gas.step(1.0 / 30.0);
        cl().queue().finish();
    }
}

/// The ocean step at {size, cascades, choppiness 0/1}: spectrum, one batched inverse FFT per
/// cascade (h alone, or h, Dx, Dy), the Lagrangian pass (J, foam, the packed grid) and the
/// Eulerian resample (Newton steps with choppiness, a copy without).
void BM_Ocean(benchmark::State& state) {
    const int n = int(state.range(0)), cascades = int(state.range(1));
    const float choppiness = float(state.range(2));
    OceanConfig config{.size = n, .cascades = cascades, .choppiness = choppiness};
    config.sea.wind.windSpeed = 10.0f;
    OceanField ocean(cl(), config);
    // No single-threaded reference of the whole step (OceanQuery is one for part of it: see
    // BM_OceanQuery). Bytes per texel and cascade: the half spectra out (1 or 3 complex), the
    // FFT's passes (about 4 reads and writes of them), the fields in and J, foam and its young
    // part in and out, the packed grid (8 floats, written and read), height, metres, foam colour
    // out.
    const double fields = choppiness > 0.0f ? 3.0 : 1.0;
    const double bytes =
        cascades * double(n) * n * (fields * 8.0 * 5.0 + fields * 4.0 + 4.0 * 24.0);
    measure(state, [&] { ocean.step(1.0 / 60); }, bytes, {});
}

/// OceanQuery::heights of 256 points on the default sea (4 cascades of 256^2, choppy): at a new
/// time each batch (the grids: spectra, 12 FFTs, the packed grids; then the points) and at the
/// same time (the points alone: 4 bilinear corners x 4 cascades x up to 4 Newton steps each).
void BM_OceanQuery(benchmark::State& state) {
    const bool newTime = state.range(0) != 0;
    OceanConfig config;
    config.sea.wind.windSpeed = 10.0f;
    OceanField ocean(cl(), config);
    OceanQuery query(ocean);
    std::vector<glm::vec2> points;
    for (int i = 0; i < 256; ++i) points.emplace_back(3.7f * float(i), 1.3f * float(i * i % 97));
    std::vector<float> out(points.size());
    double t = 0.0;
    query.heights(points, t, out);
    for (auto _ : state) {
        if (newTime) t += 1.0 / 60;
        query.heights(points, t, out);
        benchmark::DoNotOptimize(out.data());
    }
    state.counters["us_per_point"] = benchmark::Counter(double(points.size()),
                                                        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}


/// A pick through the middle of 1280x720 onto a 256² relief at 60 degrees: {mesh} 0 pickSurface
/// on a plane's frame (the trace alone), 1 pickMesh on that plane (2 triangles), 2 pickMesh on
/// makeSphere's 9,216 triangles, 3 the same under a triplanar mapping, 4 a MeshPicker of that
/// sphere (its hierarchy built before the timing). CPU only, one thread.
void BM_Pick(benchmark::State& state) {
    const int kind = int(state.range(0));
    const HeightFieldTracer heights(sumOfSines(256, {{0.3, 4, 1, 0.0}, {0.1, -7, 11, 1.0}}), 256, 256, EdgeMode::Wrap);
    const PlaneConfig plane{.size = 2.0f};
    const MeshData mesh = kind <= 1 ? makePlane(plane) : makeSphere({});
    SurfaceMaterial material{.depthScale = 0.05f};
    if (kind == 3) material.triplanar = {.scale = 1.5f};
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 3.0f, 0.4f, kind <= 1 ? 0.52f : 0.2f);
    camera.aspect = 16.0f / 9.0f;
    const SurfaceFrame frame = SurfaceFrame::ofPlane(plane);
    const Ray ray = camera.rayThroughPixel(640.5, 360.5, 1280, 720);
    const MeshPicker picker(mesh);
    for (auto _ : state) {
        if (kind == 0) benchmark::DoNotOptimize(pickSurface(ray, frame, heights, material.depthScale));
        else if (kind == 4) benchmark::DoNotOptimize(picker.pick(ray, glm::mat4(1.0f), heights, material));
        else benchmark::DoNotOptimize(pickMesh(ray, mesh, glm::mat4(1.0f), heights, material));
    }
}

/// The ocean's transform, a batch of 3 inverse real 2D FFTs (h, Dx, Dy) at {size}, by VkFFT on
/// the device (InverseRealFft), against FFTW's single-threaded plan of the same transforms.
/// (clFFT, which the ocean used before, took 1.08x VkFFT's time at 256², 1.27x at 512² and 1.74x
/// at 1024² on PoCL with 2 cores, timed alternately in one run: docs/BENCHMARKS.md.)
void BM_InverseFft(benchmark::State& state) {
    const int n = int(state.range(0)), batch = 3;
    InverseRealFft fft(cl(), n, batch);
    std::vector<float> values(fft.spectrumBytes() / sizeof(float));
    std::mt19937 random(7);
    std::normal_distribution<float> normal;
    for (float& v : values) v = normal(random);
    cl::Buffer spectrum(cl().context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, fft.spectrumBytes(), values.data());
    cl::Buffer fields(cl().context(), CL_MEM_READ_WRITE, fft.fieldBytes());
    // The reference: FFTW's c2r of the same layout (it also overwrites its input).
    std::vector<fftwf_complex> in(size_t(batch) * size_t(n / 2 + 1) * size_t(n));
    std::vector<float> out(size_t(batch) * size_t(n) * size_t(n));
    const int dims[2] = {n, n};
    fftwf_plan plan = fftwf_plan_many_dft_c2r(2, dims, batch, in.data(), nullptr, 1, (n / 2 + 1) * n, out.data(),
                                              nullptr, 1, n * n, FFTW_ESTIMATE);
    // Memory sees the spectra read and the fields written about twice each (two passes).
    const double bytes = 2.0 * double(fft.spectrumBytes() + fft.fieldBytes());
    measure(state, [&] { fft.enqueue(spectrum, fields); }, bytes, [&] { fftwf_execute(plan); });
    fftwf_destroy_plan(plan);
}

/// The host's time to issue one POM draw of a 64² surface into a 64x64 target (the GL context's
/// own work waited for outside the timing) under GlStatePolicy Restore (0) or Defaults (1): the
/// ~120 state queries and restores a restoring draw makes. On a driver that runs GL on a thread
/// of its own each query also waits for that thread, which this does not measure.
void BM_DrawIssue(benchmark::State& state) {
    // Outlives every benchmark, as the tests' context does (no driver teardown at exit).
    static GlContext* gl = createHeadlessContext({.width = 64, .height = 64}).release();
    gl->makeCurrent();
    constexpr int field = 64;
    SurfaceTextures textures({.width = field, .height = field, .mipmaps = false, .normalDepth = 0.1f});
    textures.uploadTexels(sobelReference(sumOfSines(field, {{0.3, 2, 1, 0.0}}), field, 0.1f).data());
    const Mesh plane(makePlane({.size = 2.0f}));
    const Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.6f, 0.55f, 0.6f);
    RenderTarget target(64, 64);
    SurfaceRenderer renderer;
    renderer.setColorOutput(ColorOutput::Display);
    target.bind();
    setGlStatePolicy(state.range(0) != 0 ? GlStatePolicy::Defaults : GlStatePolicy::Restore);
    for (auto _ : state) {
        renderer.draw(plane, glm::mat4(1.0f), textures, {.depthScale = 0.1f}, camera, DirectionalLight{});
        state.PauseTiming();
        glFinish();
        state.ResumeTiming();
    }
    setGlStatePolicy(GlStatePolicy::Restore);
}

BENCHMARK(BM_Sobel)->Arg(512)->Arg(2048)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SobelKernel)->Args({512, 1})->Args({512, 4})->Args({2048, 1})->Args({2048, 4})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Decals)->Arg(512)->Arg(2048)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DamageLogAdd)->Arg(256)->Arg(4096)->ArgNames({"budget"});
BENCHMARK(BM_DecalRebuild)
    ->ArgsProduct({{512, 2048}, {64, 256, 1024}})
    ->ArgNames({"size", "budget"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Pyramid)->Arg(512)->Arg(2048)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Waves)->Arg(512)->Arg(2048)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Noise)->Arg(512)->Arg(2048)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Ocean)
    ->ArgsProduct({{512, 1024}, {1, 2, 3, 4}, {0, 1}})
    ->ArgNames({"size", "cascades", "chop"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Pick)->DenseRange(0, 4)->ArgNames({"mesh"})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_InverseFft)->Arg(256)->Arg(512)->Arg(1024)->ArgNames({"size"})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OceanQuery)->Arg(1)->Arg(0)->ArgNames({"new_t"})->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_GasPressureKernel)->Args({512, 1})->Args({512, 4})->Args({2048, 1})->Args({2048, 4})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanetGas)->Args({0, 1, 0, 1, 1})->Args({1, 1, 0, 1, 1})->Args({1, 0, 0, 0, 1})->Args({1, 1, 0, 0, 1})->Args({1, 1, 1, 0, 1})->Args({1, 1, 0, 1, 2})->Args({1, 1, 1, 0, 2})->ArgNames({"maccormack", "sphere", "jacobi", "rotation", "grid"})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanetDetail)->Args({2, 1})->Args({4, 1})->Args({2, 0})->Args({4, 0})->ArgNames({"scale", "sphere"})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanetPolarFilter)->Arg(2)->Arg(4)->ArgNames({"scale"})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanetStorms)->Arg(0)->Arg(1)->Arg(2)->ArgNames({"held"})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DrawIssue)->Arg(0)->Arg(1)->ArgNames({"defaults"})->Iterations(2000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Gas)->Args({512, 0})->Args({512, 1})->Args({2048, 0})->UseRealTime()->Unit(benchmark::kMillisecond);
} // namespace
} // namespace hfx::test

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    std::printf("OpenCL: %s\nmemcpy bandwidth (1 thread, read + write): %.2f GB/s\n", hfx::test::cl().description().c_str(),
                hfx::test::memcpyBandwidth() / 1e9);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
}
