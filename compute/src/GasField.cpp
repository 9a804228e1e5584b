#include "hfx/compute/GasField.h"

#include "hfx/compute/shared/GasMath.h"

#include "hfx/core/Error.h"
#include "hfx/core/Random.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numbers>
#include <utility>

namespace hfx {

void GasConfig::validate() const {
    if (width < 4 || height < 4 || width > 8192 || height > 8192)
        throw Error(str("GasConfig size must be in 4..8192, got ", width, "x", height));
    if (edges == EdgeMode::Clamp)
        throw Error("GasConfig.edges must be wrap or wrap-u, got clamp: the gas always wraps in x (longitude)");
    if (!(viscosity >= 0.0f) || !std::isfinite(viscosity))
        throw Error(str("GasConfig.viscosity must be >= 0, got ", viscosity));
    if (sphere && edges != EdgeMode::WrapU)
        throw Error(str("GasConfig.sphere needs edges wrap-u (walls at the poles), got ", edgeModeName(edges)));
    if (sphere && viscosity > 0.0f && width % 2 != 0)
        throw Error(str("GasConfig.viscosity on a sphere needs an even width (its rows' real FFT), got ", width));
    if (viscosityIterations < 1 || viscosityIterations > 1000)
        throw Error(str("GasConfig.viscosityIterations must be in [1, 1000], got ", viscosityIterations));
    if (pressure != GasPressure::Exact && pressure != GasPressure::Jacobi)
        throw Error(str("GasConfig.pressure must be Exact or Jacobi, got ", int(pressure)));
    if (pressure == GasPressure::Exact && width % 2 != 0)
        throw Error(str("GasConfig.pressure Exact needs an even width (its rows' real FFT), got ", width,
                        ": use GasPressure::Jacobi"));
    if (pressureIterations < 1 || pressureIterations > 10000)
        throw Error(str("GasConfig.pressureIterations must be in [1, 10000], got ", pressureIterations));
    if (!(vorticity >= 0.0f) || !std::isfinite(vorticity))
        throw Error(str("GasConfig.vorticity must be >= 0, got ", vorticity));
    if (!std::isfinite(jetSpeed) || !(jetBands >= 0.0f) || !(jetRate >= 0.0f) || !std::isfinite(jetRate))
        throw Error(str("GasConfig jets must be finite and non-negative, got speed ", jetSpeed, " bands ",
                        jetBands, " rate ", jetRate));
    if (!(jetPolar >= 0.0f && jetPolar <= 16.0f))
        throw Error(str("GasConfig.jetPolar must be in [0, 16], got ", jetPolar));
    if (!(maxSpeed >= 0.0f) || !std::isfinite(maxSpeed))
        throw Error(str("GasConfig.maxSpeed must be >= 0 and finite, got ", maxSpeed));
    if (!(rotation >= 0.0f) || !std::isfinite(rotation))
        throw Error(str("GasConfig.rotation must be >= 0 and finite, got ", rotation));
    if (rotation > 0.0f && !sphere)
        throw Error(str("GasConfig.rotation needs sphere (its Coriolis parameter is the latitude's), got ", rotation,
                        " on a flat grid"));
    if (rotation > 0.0f && width % 2 != 0)
        throw Error(str("GasConfig.rotation needs an even width (its rows' real FFT), got ", width));
    if (!(initialBands >= 0.0f) || initialBands > float(height))
        throw Error(str("GasConfig.initialBands must be in [0, height], got ", initialBands));
    if (!(bandVariety >= 0.0f && bandVariety <= 1.0f))
        throw Error(str("GasConfig.bandVariety must be in [0, 1], got ", bandVariety));
    if (!(dyeRate >= 0.0f && dyeRate <= 1.0f))
        throw Error(str("GasConfig.dyeRate must be in [0, 1] per second, got ", dyeRate));
}

std::vector<float> gasMetricTable(const GasConfig& config) {
    const int H = config.height, points = 2 * H + 1;
    std::vector<float> table(size_t(2 * points), 1.0f);
    std::fill(table.begin() + points, table.end(), 0.0f);
    if (!config.sphere) return table;
    const double k = 2.0 * H / config.width, radius = H / std::numbers::pi;
    for (int t = 0; t < points; ++t) {
        const double a = std::numbers::pi * t / (2.0 * H); // pi y / H; latitude = a - pi / 2
        const bool pole = t == 0 || t == points - 1;
        table[size_t(t)] = pole ? 0.0f : float(k * std::sin(a));
        table[size_t(points + t)] = pole ? 0.0f : float(-std::cos(a) / std::sin(a) / radius);
    }
    return table;
}

double gasJetAt(const GasConfig& config, double v) {
    const double polar = double(config.jetPolar);
    const double fade = polar > 0.0 ? std::pow(std::sin(std::numbers::pi * v), polar) : 1.0;
    return double(config.jetSpeed) * std::sin(2.0 * std::numbers::pi * config.jetBands * v) * fade;
}

std::vector<float> gasPolarWidths(const GasConfig& config) {
    if (!config.sphere) return {};
    // A cell of latitude spans 1 / m cells of longitude (5.8 at 80 degrees): the box takes the
    // rows' x resolution down to about the y resolution, and leaves alone the rows where a cell
    // of latitude spans at most two of longitude.
    const std::vector<float> table = gasMetricTable(config);
    std::vector<float> widths(size_t(config.height));
    for (int j = 0; j < config.height; ++j)
        widths[size_t(j)] = std::clamp(1.0f / table[size_t(2 * j + 1)] - 1.0f, 0.0f, float(config.width));
    return widths;
}

namespace {

/// GasPressure::Exact's systems between walls (gas.cl's solve_columns), one for each zonal
/// wavenumber k (K = W/2 + 1 of them): the Jacobi sweep's equation (hfx_gas_pressure_weights),
/// Neumann at the walls, with the x neighbours' sum turned into its eigenvalue,
///   w1 p[j-1] + w2 p[j+1] - (w1 + w2 + w0 (2 - 2 cos(2 pi k / W))) p[j] = w3 div[j],
/// eliminated downward: the pivots' reciprocals and the upper diagonal over them (Thomas's c'),
/// row-major H x K; each row's weight of the row below, and the scale of its divergence (its area
/// w3 and the inverse transform's 1 / W). Every system with k > 0 is diagonally dominant, so the
/// elimination needs no pivoting; k = 0 is singular, and its pivots are left 0 (no pressure).
struct GasPressureColumns {
    std::vector<float> upper, pivots, lower, rhs;
};

GasPressureColumns gasPressureColumns(const GasConfig& config, const std::vector<float>& metric) {
    const int W = config.width, H = config.height, K = W / 2 + 1;
    GasPressureColumns c{std::vector<float>(size_t(H) * K, 0.0f), std::vector<float>(size_t(H) * K, 0.0f),
                         std::vector<float>(size_t(H)), std::vector<float>(size_t(H))};
    std::vector<std::array<float, 4>> weights(static_cast<size_t>(H));
    for (int j = 0; j < H; ++j) {
        hfx_gas_pressure_weights(metric.data(), H, j, 1, weights[size_t(j)].data());
        c.lower[size_t(j)] = weights[size_t(j)][1];
        c.rhs[size_t(j)] = weights[size_t(j)][3] / float(W);
    }
    for (int k = 1; k < K; ++k) {
        const double half = std::sin(std::numbers::pi * k / W), eigen = 4.0 * half * half; // 2 - 2 cos
        double before = 0.0; // c'[j-1]
        for (int j = 0; j < H; ++j) {
            const auto& w = weights[size_t(j)];
            const double pivot = -(double(w[1]) + w[2] + w[0] * eigen) - w[1] * before;
            before = w[2] / pivot;
            c.pivots[size_t(j) * K + k] = float(1.0 / pivot);
            c.upper[size_t(j) * K + k] = float(before);
        }
    }
    return c;
}

} // namespace

GasField::GasField(ClContext& cl, const GasConfig& config) : cl_(cl), config_(config) {
    config.validate();
    metricTable_ = gasMetricTable(config);
    const size_t n = size_t(config.width) * config.height, bytes = n * sizeof(float);
    clGuard("creating the gas", [&] {
        for (cl::Buffer* b : {&u_, &v_, &dye_, &work_[0], &work_[1], &work_[2], &work_[3], &p_, &div_, &curl_,
                              &height_})
            *b = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, bytes);
        if (config.maccormack) departures_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, 2 * bytes);
        sumsBefore_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, sizeof(float) * size_t(config.height));
        sumsAfter_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, sizeof(float) * size_t(config.height));
        factor_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, sizeof(float));
        metric_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                             sizeof(float) * metricTable_.size(), metricTable_.data());
        std::vector<float> grid = gasMetricTable({.width = config.width, .height = config.height});
        gridMetric_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * grid.size(),
                                 grid.data());
        const cl::Program& program = cl.program("gas.cl", edgeOptions(config.edges));
        advect_ = cl::Kernel(program, "advect");
        maccormack_ = cl::Kernel(program, "maccormack");
        advectForward_ = cl::Kernel(program, "advect_forward");
        turn_ = cl::Kernel(program, "turn");
        removeRowMean_ = cl::Kernel(program, "remove_row_mean");
        splat_ = cl::Kernel(program, "splat");
        vortex_ = cl::Kernel(program, "vortex");
        sampleVelocity_ = cl::Kernel(program, "sample_velocity");
        jets_ = cl::Kernel(program, "jets");
        clampSpeed_ = cl::Kernel(program, "clamp_speed");
        curlKernel_ = cl::Kernel(program, "curl");
        confine_ = cl::Kernel(program, "confine");
        diffuse_ = cl::Kernel(program, "diffuse");
        divergence_ = cl::Kernel(program, "divergence");
        const bool walls = config.edges == EdgeMode::WrapU;
        const bool sphereViscous = config.sphere && config.viscosity > 0.0f;
        if (config.pressure == GasPressure::Exact || config.rotation > 0.0f || sphereViscous) {
            fft_ = std::make_unique<RealFft>(cl, config.width, config.height,
                                             walls ? RealFft::Axes::Rows : RealFft::Axes::Both);
            spectrum_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, fft_->spectrumBytes());
        }
        if (config.rotation > 0.0f || sphereViscous) {
            scratch_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, fft_->spectrumBytes());
            addStream_ = cl::Kernel(program, "add_stream");
        }
        if (config.rotation > 0.0f) betaColumns_ = cl::Kernel(program, "beta_columns");
        if (sphereViscous) {
            cornerLaplacian_ = cl::Kernel(program, "corner_laplacian");
            viscousColumns_ = cl::Kernel(program, "viscous_columns");
        }
        if (config.pressure == GasPressure::Exact) {
            if (walls) {
                const GasPressureColumns c = gasPressureColumns(config, metricTable_);
                auto buffer = [&](const std::vector<float>& x) {
                    return cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * x.size(),
                                      const_cast<float*>(x.data()));
                };
                pressureColumns_ = {buffer(c.upper), buffer(c.pivots), buffer(c.lower), buffer(c.rhs)};
                solveColumns_ = cl::Kernel(program, "solve_columns");
            } else
                pressure_ = cl::Kernel(program, "pressure_modes");
        } else {
            p2_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, bytes);
            // Four cells per work-item where the rows allow it: faster, the same results
            // (BM_GasPressureKernel, docs/history/tuning.md).
            pressure_ = cl::Kernel(program, config.width % 4 == 0 ? "pressure4" : "pressure");
        }
        project_ = cl::Kernel(program, "project");
        dyeHeight_ = cl::Kernel(program, "dye_height");
        rowSums_ = cl::Kernel(program, "row_sums");
        massFactor_ = cl::Kernel(program, "mass_factor");
        scale_ = cl::Kernel(program, "scale");
        relaxDye_ = cl::Kernel(program, "relax_dye");
    });
    if (config.sphere) polar_ = std::make_unique<PolarFilter>(cl, config.width, config.height, gasPolarWidths(config));
    // Initial state: jets already blowing, banded dye with a little noise to seed the storms.
    std::vector<float> u(n), v(n, 0.0f), dye(n), rows(size_t(config.height), 0.0f), jets(size_t(config.height));
    SplitMix64 random(config.seed);
    const double twoPi = 2.0 * std::numbers::pi;
    // Each half period's depth and inner bands (their own stream: variety 0 draws nothing).
    const int halves = int(std::ceil(2.0 * config.initialBands)) + 1;
    std::vector<double> depth(size_t(halves), 1.0), inner(size_t(halves), 0.0);
    SplitMix64 bands(config.seed ^ 0x6a09e667f3bcc909ull);
    for (int k = 0; k < halves && config.bandVariety > 0.0f; ++k) {
        depth[size_t(k)] = 1.0 - 0.6 * config.bandVariety * bands.next();
        inner[size_t(k)] = 0.12 * config.bandVariety * bands.uniform(-1, 1);
    }
    for (int j = 0; j < config.height; ++j) {
        const double y = (j + 0.5) / config.height;
        const double swing = std::sin(twoPi * config.initialBands * y);
        const size_t half = std::min(size_t(2.0 * config.initialBands * y), size_t(halves - 1));
        const double band = 0.45 * depth[half] * swing +
                            inner[half] * std::abs(swing) * std::sin(3.0 * twoPi * config.initialBands * y);
        rows[size_t(j)] = config.initialBands > 0 ? float(std::clamp(0.5 + band, 0.0, 1.0)) : 0.0f;
        jets[size_t(j)] = float(gasJetAt(config, y)); // what the row's u relaxes to (gas.cl's jets)
        for (int i = 0; i < config.width; ++i) {
            u[size_t(j) * config.width + i] =
                float(config.jetSpeed * std::sin(twoPi * config.jetBands * y) * (1.0 + 0.05 * random.uniform(-1, 1)));
            dye[size_t(j) * config.width + i] =
                config.initialBands > 0 ? float(std::clamp(0.5 + band + 0.05 * random.uniform(-1, 1), 0.0, 1.0)) : 0.0f;
        }
    }
    bands_ = rows;
    clGuard("creating the gas's bands", [&] {
        bandRows_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(float) * rows.size(),
                               rows.data());
        jetRows_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * jets.size(),
                              jets.data());
    });
    setState(u, v, dye);
}

template <typename... Args>
void GasField::run(cl::Kernel& kernel, const Args&... args) {
    runOver(cl::NDRange(config_.width, config_.height), kernel, args...);
}

template <typename... Args>
void GasField::runOver(cl::NDRange range, cl::Kernel& kernel, const Args&... args) {
    setArgs(kernel, args...);
    cl_.enqueue(kernel, range);
}

void GasField::addSplat(const GasSplat& s) {
    if (!(s.u >= 0.0f && s.u < 1.0f && s.v >= 0.0f && s.v < 1.0f))
        throw Error(str("gas splat at (", s.u, ", ", s.v, ") is outside the map: texcoords must lie in [0, 1)"));
    if (!(s.radius > 0.0f) || s.radius > 1.0f)
        throw Error(str("gas splat radius must be in (0, 1] widths, got ", s.radius));
    if (!std::isfinite(s.forceX) || !std::isfinite(s.forceY) || !std::isfinite(s.dye))
        throw Error("gas splat force and dye must be finite");
    if (!(s.dyeTarget < 0.0f || s.dyeTarget <= 1.0f) || (s.dyeTarget >= 0.0f && !(s.dye >= 0.0f && s.dye <= 1.0f)))
        throw Error(str("gas splat dyeTarget must be < 0 (dye added) or in [0, 1] with a dye share in [0, 1], got ",
                        s.dyeTarget, " and ", s.dye));
    if (!(s.aspect >= 1.0f && s.aspect <= 8.0f))
        throw Error(str("gas splat aspect must be in [1, 8], got ", s.aspect));
    const GasArms& a = s.arms;
    if (a.count < 0 || a.count > 8) throw Error(str("gas splat arms.count must be in [0, 8], got ", a.count));
    if (a.count > 0 && s.dyeTarget < 0.0f)
        throw Error("gas splat arms need a dyeTarget in [0, 1]: they wind the colour it feeds");
    if (!(a.target >= 0.0f && a.target <= 1.0f) || !(a.contrast >= 0.0f && a.contrast <= 1.0f))
        throw Error(
            str("gas splat arms.target and arms.contrast must be in [0, 1], got ", a.target, " and ", a.contrast));
    if (!std::isfinite(a.turned) || !std::isfinite(a.winding) || !std::isfinite(a.sweep))
        throw Error(str("gas splat arms.turned, arms.winding and arms.sweep must be finite, got ", a.turned, ", ",
                        a.winding, " and ", a.sweep));
    splats_.push_back(s);
}

void GasField::addVortex(const GasVortex& vx) {
    if (!(vx.u >= 0.0f && vx.u < 1.0f && vx.v >= 0.0f && vx.v < 1.0f))
        throw Error(str("gas vortex at (", vx.u, ", ", vx.v, ") is outside the map: texcoords must lie in [0, 1)"));
    if (!(vx.radius > 0.0f) || vx.radius > 0.25f)
        throw Error(str("gas vortex radius must be in (0, 0.25] widths, got ", vx.radius));
    if (!(vx.aspect >= 1.0f && vx.aspect <= 8.0f))
        throw Error(str("gas vortex aspect must be in [1, 8], got ", vx.aspect));
    if (!std::isfinite(vx.speed) || !std::isfinite(vx.driftX) || !std::isfinite(vx.driftY))
        throw Error(str("gas vortex speed and drift must be finite, got ", vx.speed, ", ", vx.driftX, " and ", vx.driftY));
    if (!(vx.rate >= 0.0f) || !std::isfinite(vx.rate))
        throw Error(str("gas vortex rate must be >= 0 per second, got ", vx.rate));
    vortices_.push_back(vx);
}

std::vector<glm::vec2> GasField::velocityAt(const std::vector<glm::vec2>& points) {
    std::vector<glm::vec2> winds(points.size());
    velocityAt(points, winds);
    return winds;
}

void GasField::velocityAt(std::span<const glm::vec2> points, std::span<glm::vec2> winds) {
    static_assert(sizeof(glm::vec2) == 2 * sizeof(float), "the winds are read straight into glm::vec2s");
    if (winds.size() != points.size())
        throw Error(str("GasField::velocityAt: ", points.size(), " points and room for ", winds.size(), " winds"));
    const int W = config_.width, H = config_.height;
    sampleCells_.resize(2 * points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        const glm::vec2 p = points[i];
        if (!(std::isfinite(p.x) && p.y >= 0.0f && p.y <= 1.0f))
            throw Error(str("GasField::velocityAt: point ", i, " at (", p.x, ", ", p.y,
                            ") is off the map: u must be finite and v in [0, 1]"));
        sampleCells_[2 * i] = float((double(p.x) - std::floor(double(p.x))) * W);
        sampleCells_[2 * i + 1] = p.y * float(H);
    }
    if (points.empty()) return;
    clGuard("GasField::velocityAt", [&] {
        // The points' buffers are kept (a planet reads its storms' winds every frame), grown to the
        // next power of two that holds them.
        if (points.size() > sampleCapacity_) {
            sampleCapacity_ = std::bit_ceil(points.size());
            samplePoints_ = cl::Buffer(cl_.context(), CL_MEM_READ_ONLY, 2 * sampleCapacity_ * sizeof(float));
            sampleWinds_ = cl::Buffer(cl_.context(), CL_MEM_WRITE_ONLY, 2 * sampleCapacity_ * sizeof(float));
        }
        cl::CommandQueue& q = cl_.queue();
        // (Not waited for: the blocking read below finishes the queue before sampleCells_ changes.)
        q.enqueueWriteBuffer(samplePoints_, CL_FALSE, 0, sampleCells_.size() * sizeof(float), sampleCells_.data());
        const int n = int(points.size());
        runOver(cl::NDRange(points.size()), sampleVelocity_, u_, v_, samplePoints_, sampleWinds_, n, W, H);
        q.enqueueReadBuffer(sampleWinds_, CL_TRUE, 0, winds.size() * sizeof(glm::vec2), winds.data());
    });
}

void GasField::advectField(cl::Buffer& field, float ox, float oy, float dt, bool wallRow) {
    const int W = config_.width, H = config_.height, wall = wallRow ? 1 : 0;
    const float back = -dt;
    const cl::Buffer& m = metric_;
    if (!config_.maccormack) {
        run(advect_, u_, v_, m, field, work_[0], W, H, ox, oy, dt, wall);
    } else {
        run(advectForward_, u_, v_, m, field, work_[1], departures_, W, H, ox, oy, dt, wall);
        run(advect_, u_, v_, m, work_[1], work_[2], W, H, ox, oy, back, wall);
        run(maccormack_, field, work_[1], work_[2], departures_, work_[0], W, H, ox, oy, wall);
    }
}

void GasField::step(double dtSeconds) {
    if (!(dtSeconds > 0.0) || !std::isfinite(dtSeconds))
        throw Error(str("GasField::step: dt must be positive and finite, got ", dtSeconds));
    const float dt = float(dtSeconds);
    const int W = config_.width, H = config_.height;
    clGuard("GasField::step", [&] {
        cl::CommandQueue& q = cl_.queue();
        const size_t bytes = sizeof(float) * size_t(W) * H;
        auto rowSums = [&](const cl::Buffer& field, const cl::Buffer& sums) {
            runOver(cl::NDRange(size_t(H)), rowSums_, field, sums, W, H);
        };
        for (const GasSplat& s : splats_) {
            const float x = s.u * W, y = s.v * H, r = s.radius * W;
            // Only the cells within 6 radii (and the half cell of the faces' offsets): beyond, the
            // Gaussian is below 10^-15 of its peak, under a float's resolution of what it adds to
            // (PlanetWeather's vortex keeps its gas to the bit; at 4 radii, 10^-7, that chaotic
            // flow drifts elsewhere). A planet's storms are kept spinning by two splats each a
            // step, so a whole-grid splat cost it most of its step. The dye's oval reaches
            // `aspect` times as far along u.
            const int reachX = int(std::ceil(6.0f * r * s.aspect)) + 1, reachY = int(std::ceil(6.0f * r)) + 1;
            const int w = std::min(W, 2 * reachX + 1), h = std::min(H, 2 * reachY + 1);
            const int i0 = w == W ? 0 : int(std::floor(x)) - reachX, j0 = h == H ? 0 : int(std::floor(y)) - reachY;
            // The arms' mean over the sweep: the crest's harmonics scaled by sinc of half the
            // phase each sweeps (gas.cl's splat).
            const double p = 0.5 * s.arms.count * double(s.arms.sweep);
            const float sinc1 = p != 0.0 ? float(std::sin(p) / p) : 1.0f;
            const float sinc2 = p != 0.0 ? float(std::sin(2.0 * p) / (2.0 * p)) : 1.0f;
            runOver(cl::NDRange(size_t(w), size_t(h)), splat_, u_, v_, dye_, W, H, x, y, r, s.forceX, s.forceY, s.dye,
                    s.dyeTarget, dt, i0, j0, w, h, s.aspect, s.arms.count, s.arms.target, s.arms.contrast,
                    s.arms.turned, s.arms.winding, sinc1, sinc2);
        }
        splats_.clear();
        if (config_.jetSpeed != 0.0f && config_.jetRate > 0.0f) {
            const float share = float(1.0 - std::exp(-double(config_.jetRate) * dtSeconds));
            run(jets_, u_, jetRows_, W, H, share);
        }
        for (const GasVortex& vx : vortices_) {
            // Within 3 of its sizes (the weight and its wind there 10^-4 of their peaks) and the
            // faces' half cell: a planet holds each of its storms every step.
            const float x = vx.u * W, y = vx.v * H, a = vx.radius * W, b = a / vx.aspect;
            const float psi0 = vx.speed * b / 0.85776f; // the fastest wind, sqrt(2) e^-1/2 psi0 / b
            const float share = float(1.0 - std::exp(-double(vx.rate) * dtSeconds));
            const int reachX = int(std::ceil(3.0f * a)) + 1, reachY = int(std::ceil(3.0f * b)) + 1;
            const int w = std::min(W, 2 * reachX + 1), h = std::min(H, 2 * reachY + 1);
            const int i0 = w == W ? 0 : int(std::floor(x)) - reachX, j0 = h == H ? 0 : int(std::floor(y)) - reachY;
            runOver(cl::NDRange(size_t(w), size_t(h)), vortex_, u_, v_, metric_, W, H, x, y, a, b, psi0, vx.driftX,
                    vx.driftY, share, i0, j0, w, h);
        }
        vortices_.clear();
        if (config_.vorticity > 0.0f) {
            // On the map's cells (gridMetric_) even on a sphere: the confinement gives back what
            // the grid's own dissipation takes, at the grid's scale, and with the sphere's
            // metric it pumped the polar rows' grid-scale noise, whose x differences m divides
            // (|curl| 66 in the last row against 4 elsewhere, on 128x64).
            run(curlKernel_, u_, v_, gridMetric_, curl_, W, H);
            run(confine_, curl_, u_, v_, W, H, config_.vorticity, dt);
        }
        if (config_.maxSpeed > 0.0f) run(clampSpeed_, u_, v_, W, H, config_.maxSpeed);
        if (config_.sphere) { // the wind's frame turns as it moves (hfx_gas_turn), before it carries itself
            rowSums(u_, sumsBefore_);
            run(turn_, u_, v_, metric_, sumsBefore_, work_[0], work_[3], W, H, dt);
            std::swap(work_[0], u_);
            std::swap(work_[3], v_);
        }
        // Self-advection: both components read the old velocity, so the new u waits in work_[3].
        // Results change places with the state by swapping handles, not by copying.
        advectField(u_, 0.0f, 0.5f, dt, false);
        std::swap(work_[0], work_[3]);
        advectField(v_, 0.5f, 0.0f, dt, true);
        std::swap(work_[0], v_);
        std::swap(work_[3], u_);
        if (config_.viscosity > 0.0f && !config_.sphere) {
            const float a = config_.viscosity * dt;
            for (cl::Buffer* x : {&u_, &v_}) {
                const int wall = x == &v_ ? 1 : 0;
                q.enqueueCopyBuffer(*x, work_[1], 0, 0, bytes); // x0, the right-hand side
                for (int it = 0; it < config_.viscosityIterations; ++it) {
                    run(diffuse_, *x, work_[1], work_[2], W, H, a, wall);
                    std::swap(*x, work_[2]);
                }
            }
        }
        project();
        // On the projected wind, a change given by its streamfunction: `source`'s rows' transform,
        // solved per zonal wavenumber by `columns` (gas.cl's, whose arguments after the spectrum,
        // its scratch, the metric, W and H are `more` and the inverse transform's 1 / W), whose
        // wind add_stream adds (into p_, free again after the projection).
        auto addStreamOf = [&](const cl::Buffer& source, cl::Kernel& columns, auto... more) {
            fft_->forward(source, spectrum_);
            runOver(cl::NDRange(size_t(W / 2 + 1)), columns, spectrum_, scratch_, metric_, W, H, more...,
                    1.0f / float(W));
            fft_->inverse(spectrum_, p_);
            run(addStream_, u_, v_, p_, metric_, W, H);
        };
        if (config_.viscosity > 0.0f && config_.sphere) { // on the sphere the vorticity diffuses
            run(cornerLaplacian_, u_, v_, metric_, curl_, W, H);
            addStreamOf(curl_, viscousColumns_, config_.viscosity * dt);
        }
        if (config_.rotation > 0.0f) addStreamOf(v_, betaColumns_, dt, config_.rotation); // the planet's spin
        if (config_.conserveDye) rowSums(dye_, sumsBefore_);
        advectField(dye_, 0.5f, 0.5f, dt, false);
        std::swap(work_[0], dye_);
        if (config_.conserveDye) {
            rowSums(dye_, sumsAfter_);
            runOver(cl::NDRange(1), massFactor_, sumsBefore_, sumsAfter_, metric_, H, factor_);
            run(scale_, dye_, factor_, W, H);
        }
        if (polar_) {
            // On a sphere the polar rows' dye is filtered along x to the sphere's resolution: the
            // rows near a pole turn at u / m cells a second, so their differential rotation winds
            // the dye into stripes a few cells of longitude apart, far finer than a cell of
            // latitude (drawn as radial fur about the pole's cap). As the models of the atmosphere
            // on such grids filter their polar rows (Arakawa & Lamb 1977).
            polar_->run(dye_, work_[0]);
            std::swap(work_[0], dye_);
        }
        if (config_.dyeRate > 0.0f) {
            const float share = float(1.0 - std::exp(-double(config_.dyeRate) * dtSeconds));
            run(relaxDye_, dye_, bandRows_, W, H, share);
        }
        writeHeight();
    });
}

void GasField::project() {
    const int W = config_.width, H = config_.height;
    clGuard("GasField::project", [&] {
        cl::CommandQueue& q = cl_.queue();
        if (config_.edges == EdgeMode::WrapU) runOver(cl::NDRange(size_t(H)), removeRowMean_, v_, W, H);
        run(divergence_, u_, v_, metric_, div_, W, H);
        if (config_.pressure == GasPressure::Exact) {
            const int K = W / 2 + 1;
            fft_->forward(div_, spectrum_);
            if (config_.edges == EdgeMode::WrapU) {
                const PressureColumns& c = pressureColumns_;
                runOver(cl::NDRange(size_t(K)), solveColumns_, spectrum_, c.upper, c.pivots, c.lower, c.rhs, K, H);
            } else {
                runOver(cl::NDRange(size_t(K), size_t(H)), pressure_, spectrum_, W, H, 1.0f / (float(W) * float(H)));
            }
            fft_->inverse(spectrum_, p_);
            run(project_, u_, v_, p_, metric_, W, H);
            return;
        }
        q.enqueueFillBuffer(p_, 0.0f, 0, sizeof(float) * size_t(W) * H);
        const cl::NDRange sweep(W % 4 == 0 ? W / 4 : W, H);
        for (int it = 0; it < config_.pressureIterations; ++it) {
            runOver(sweep, pressure_, p_, div_, metric_, p2_, W, H);
            std::swap(p_, p2_);
        }
        run(project_, u_, v_, p_, metric_, W, H);
    });
}

float GasField::metricAt(float v) const {
    return hfx_gas_metric_at(metricTable_.data(), config_.height, v * float(config_.height));
}

void GasField::writeHeight() {
    const int W = config_.width, H = config_.height;
    run(dyeHeight_, dye_, height_, W, H);
}

void GasField::setState(const std::vector<float>& u, const std::vector<float>& v, const std::vector<float>& dye) {
    const size_t n = size_t(config_.width) * config_.height;
    if (u.size() != n || v.size() != n || dye.size() != n)
        throw Error(str("GasField::setState: fields must hold ", n, " values, got ", u.size(), ", ", v.size(),
                        ", ", dye.size()));
    for (const std::vector<float>* f : {&u, &v, &dye})
        for (float x : *f)
            if (!std::isfinite(x)) throw Error("GasField::setState: the state holds NaN or infinite values");
    clGuard("GasField::setState", [&] {
        cl::CommandQueue& q = cl_.queue();
        q.enqueueWriteBuffer(u_, CL_TRUE, 0, n * sizeof(float), u.data());
        q.enqueueWriteBuffer(v_, CL_TRUE, 0, n * sizeof(float), v.data());
        q.enqueueWriteBuffer(dye_, CL_TRUE, 0, n * sizeof(float), dye.data());
        writeHeight();
    });
}

std::vector<float> GasField::readHeights() {
    std::vector<float> heights(size_t(config_.width) * config_.height);
    clGuard("GasField::readHeights", [&] {
        cl_.queue().enqueueReadBuffer(buffer(), CL_TRUE, 0, heights.size() * sizeof(float), heights.data());
    });
    return heights;
}

void GasField::readState(std::vector<float>& u, std::vector<float>& v, std::vector<float>& dye) {
    const size_t n = size_t(config_.width) * config_.height;
    u.resize(n);
    v.resize(n);
    dye.resize(n);
    clGuard("GasField::readState", [&] {
        cl::CommandQueue& q = cl_.queue();
        q.enqueueReadBuffer(u_, CL_TRUE, 0, n * sizeof(float), u.data());
        q.enqueueReadBuffer(v_, CL_TRUE, 0, n * sizeof(float), v.data());
        q.enqueueReadBuffer(dye_, CL_TRUE, 0, n * sizeof(float), dye.data());
    });
}

std::vector<float> GasField::readDivergence() {
    const int W = config_.width, H = config_.height;
    std::vector<float> out(size_t(W) * H);
    clGuard("GasField::readDivergence", [&] {
        run(divergence_, u_, v_, metric_, div_, W, H);
        cl_.queue().enqueueReadBuffer(div_, CL_TRUE, 0, out.size() * sizeof(float), out.data());
    });
    return out;
}

} // namespace hfx
