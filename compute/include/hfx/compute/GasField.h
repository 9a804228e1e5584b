#pragma once
// A Navier-Stokes gas (Stam's stable fluids; Harris, GPU Gems ch. 38) on a staggered grid:
// semi-Lagrangian advection (MacCormack optional), implicit viscosity, vorticity confinement,
// pressure projection (solved exactly by FFT, or by Jacobi sweeps), advected dye, splats of force
// and dye, vortices the gas is held towards, and zonal jets for banded planets. x is periodic
// (longitude wraps); y is periodic or bounded by walls. The grid is flat, or a sphere's
// longitude-latitude map, whose metric the advection, the projection and the viscosity carry
// (GasConfig::sphere), and which may spin (GasConfig::rotation). The height field is the dye, so
// the gas's bands and vortices read as relief.
//
// Grid units: lengths in cells, velocities in cells per second (on a sphere, cells of latitude).
// See shared/GasMath.h.
// Thread: the thread that owns the ClContext.

#include "hfx/compute/HeightSource.h"
#include "hfx/compute/PolarFilter.h"
#include "hfx/compute/RealFft.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace hfx {

/// How the projection finds the pressure.
enum class GasPressure {
    /// Solved to rounding in one pass: each row's FFT (VkFFT, RealFft), then along y one
    /// tridiagonal solve per zonal wavenumber between walls (WrapU), or the columns' FFT too on a
    /// torus (Wrap); the wind comes out divergence-free at every scale. Needs an even width.
    Exact,
    /// pressureIterations Jacobi sweeps from zero: a partial solve, which leaves the large scales'
    /// divergence (6% of a random wind's on a sphere after 400 sweeps, most of it near the poles).
    Jacobi,
};

struct GasConfig {
    int width = 256;
    int height = 128;
    /// x always wraps (longitude). WrapU: walls at the top and bottom (poles); Wrap: a torus.
    EdgeMode edges = EdgeMode::WrapU;
    /// The grid is a sphere's longitude-latitude map (the walls of WrapU its poles; a 2:1 map has
    /// square cells at the equator): lengths are cells of latitude, u is the eastward wind in them
    /// and moves a point u / m cells of the grid along x, m = (2 height / width) cos(latitude)
    /// (metricAt), and the projection and the curvature of the wind's frame follow the sphere,
    /// so an eddy near a pole stays round on the sphere instead of round on the map (a planet's
    /// polar gas, which a flat grid draws as radial streaks); the polar rows' dye is filtered to
    /// the sphere's resolution (gasPolarWidths). The vorticity confinement, the splats and the
    /// held vortices' ovals keep the map's cells. Needs edges WrapU.
    bool sphere = false;
    /// Cells^2 per second. On a flat grid the wind's components diffuse implicitly
    /// (viscosityIterations Jacobi sweeps, before the projection); on the sphere its vorticity
    /// does, solved exactly on the projected wind (the rows' FFT and a tridiagonal solve per
    /// wavenumber; an even width), so a spherical harmonic of degree n keeps 1 / (1 + a n (n + 1)
    /// / R^2) of its wind a step (a = viscosity dt, R = height / pi cells).
    float viscosity = 0.0f;
    int viscosityIterations = 20; ///< the flat grid's sweeps
    GasPressure pressure = GasPressure::Exact;
    int pressureIterations = 40;  ///< GasPressure::Jacobi's sweeps
    float vorticity = 0.0f;       ///< confinement strength epsilon
    bool maccormack = false;      ///< second-order MacCormack advection (costlier: docs/history/tuning.md)
    bool conserveDye = true;      ///< rescale the dye after advection to keep its total
    float jetSpeed = 0.0f;        ///< zonal jets: u relaxes to jetSpeed sin(2 pi jetBands y / H)
    float jetBands = 3.0f;
    float jetRate = 0.05f;        ///< relaxation rate of the jets, per second
    /// The jets fade towards the walls as sin(pi y / H)^jetPolar (a planet's poles); 0: no fade.
    float jetPolar = 0.0f;
    /// After the forces, each velocity component is clamped to +-maxSpeed cells per second, so
    /// steps of any length stay bounded (the planet's large time scales); 0: no clamp.
    float maxSpeed = 0.0f;
    /// On a sphere: the planet's spin, radians per second of the gas's time. The vorticity
    /// equation's beta term, d zeta / dt = -beta v (beta = 2 rotation cos(latitude) / R), taken
    /// implicitly on the projected wind through the rows' FFT and a complex tridiagonal solve per
    /// wavenumber: a Rossby-Haurwitz wave drifts west at its angular speed (0.07% off at rotation
    /// dt 0.05), the term adds and takes no energy at any step (within 1% at rotation dt 5), eddies
    /// drift west, and jets whose curvature is below beta hold (Rayleigh-Kuo). Needs sphere and an
    /// even width; 0: no rotation.
    float rotation = 0.0f;
    float initialBands = 0.0f;    ///< dye starts as 0.5 + 0.45 sin(2 pi bands y / H) plus noise
    /// 0: every initial band alike. Up to 1: each zone and belt (each half period of the bands)
    /// gets its own depth, down to 1 - 0.6 variety of the full swing, and thinner bands inside it
    /// of up to 0.12 variety, drawn from the seed: belts and zones of different shades, as a
    /// gas giant's are.
    float bandVariety = 0.0f;
    /// Per second, in [0, 1]: the dye relaxes towards its initial bands (each row's starting
    /// value, without the noise) at this rate, as a giant's zones and belts are kept by up- and
    /// downwelling while storms and shear mix them; 0: it only mixes (and, in time, greys out).
    float dyeRate = 0.0f;
    std::uint64_t seed = 1;
    void validate() const;
};

/// Spiral arms in a colour a splat feeds (GasSplat::dyeTarget >= 0), as a storm's clouds wind
/// them: along each arm the colour fed moves towards `target`, most at the arm's crest, by a share
/// that grows from none at the centre to `contrast` at rho = 1 (rho as GasSplat's oval has it).
/// Arm k lies where the oval's angle phi = atan2(dy / b, dx / a) is turned + 2 pi k / count -
/// winding (1 - exp(-rho^2)): a vortex of streamfunction psi0 exp(-rho^2) (GasVortex) turns its
/// centre faster than its rim by that profile, so its clouds' arms trail by it. Beyond 3 radii
/// of the oval, where the splat's share is under 10^-4 of its centre's, they are their mean.
struct GasArms {
    int count = 0;          ///< 0: the colour fed is the same throughout; at most 8
    float target = 0.0f;    ///< the arms' colour, in [0, 1]
    float contrast = 0.0f;  ///< in [0, 1]
    float turned = 0.0f;    ///< radians, counter-clockwise (u right, v up)
    float winding = 0.0f;   ///< radians the rim lags: > 0 trails a counter-clockwise spin, < 0 a clockwise one
    /// Radians the arms turn during the step, `turned` being their angle midway: the colour fed
    /// is the arms' mean over the sweep, so a step long against the spin feeds them fainter
    /// rather than at an angle that jumps from step to step.
    float sweep = 0.0f;
};

/// Force and dye added around a point during the next step. Texcoords; radius in widths.
struct GasSplat {
    float u = 0.5f, v = 0.5f;
    float radius = 0.03f;
    float forceX = 0.0f, forceY = 0.0f; ///< cells per second^2, applied over the step
    float dye = 0.0f;                   ///< added at the centre, clamped to [0,1]
    /// In [0, 1]: the dye moves `dye` (a share in [0, 1]) of the way to this at the centre,
    /// instead of `dye` being added: a colour fed in without overshooting it. < 0: added.
    float dyeTarget = -1.0f;
    /// The dye's Gaussian an oval, exp(-rho^2) with rho^2 = dx^2 / a^2 + dy^2 / b^2, b = radius
    /// and a = aspect radius along u (in [1, 8]); the force's stays round, of `radius`.
    float aspect = 1.0f;
    GasArms arms; ///< with dyeTarget >= 0
};

/// A vortex the gas is held towards during the next step: each velocity face moves a share
/// 1 - exp(-rate dt), weighted by exp(-rho^2), of the way to the drift plus the wind of the
/// streamfunction psi0 exp(-rho^2), rho^2 = dx^2 / a^2 + dy^2 / b^2, a = radius along u and
/// b = a / aspect across it. Its streamlines are ellipses, its wind divergence-free; the fastest,
/// `speed`, blows along u across its minor axis, b / sqrt(2) from the centre (across the major
/// axis the wind peaks at speed / aspect). Texcoords; radius in widths.
struct GasVortex {
    float u = 0.5f, v = 0.5f;
    float radius = 0.03f;  ///< a, its half-length along u, in widths
    float aspect = 1.0f;   ///< a / b, in [1, 8]
    float speed = 0.0f;    ///< cells per second; > 0 turns counter-clockwise (u right, v up)
    float driftX = 0.0f, driftY = 0.0f; ///< cells per second: the wind it rides
    float rate = 1.0f;     ///< per second, >= 0
};

/// GasMath.h's metric table for `config`'s grid: m = (2H / W) sin(pi y / H) at y = t / 2 for t in
/// [0, 2H], then tan(latitude) / R at the same points (0 at the poles); 1s and 0s for a flat grid.
std::vector<float> gasMetricTable(const GasConfig& config);

/// The dye's polar filter on a sphere (GasField::step): each row's box along x, 1 / m - 1 cells
/// (none up to 60 degrees of latitude, 4.8 cells at 80); none on a flat grid (empty).
std::vector<float> gasPolarWidths(const GasConfig& config);

/// The zonal jet the wind relaxes to at v (0 at row 0's wall, 1 at the top), cells per second:
/// jetSpeed sin(2 pi jetBands v) sin(pi v)^jetPolar.
double gasJetAt(const GasConfig& config, double v);

class GasField final : public HeightSource {
public:
    GasField(ClContext& cl, const GasConfig& config);

    void step(double dt) override;
    void addSplat(const GasSplat& splat); ///< throws hfx::Error for a splat off the map
    /// Holds the gas towards `vortex` during the next step, after the jets (so a storm keeps its
    /// wind in a sheared band); throws hfx::Error naming a bad field.
    void addVortex(const GasVortex& vortex);
    /// The splats queued for the next step, in order.
    const std::vector<GasSplat>& pendingSplats() const { return splats_; }
    /// The velocity (cells per second) at each of `points` (texcoords, u wrapping, v in [0, 1]),
    /// bilinear from the faces as the advection reads it; waits for the device. Throws naming
    /// a point off the map.
    std::vector<glm::vec2> velocityAt(const std::vector<glm::vec2>& points);
    /// The same into `winds` (as many as `points`), allocating nothing once its buffers hold
    /// that many points: what a caller does every frame.
    void velocityAt(std::span<const glm::vec2> points, std::span<glm::vec2> winds);
    /// Runs only the pressure projection (tests, and after setting a velocity by hand). Between
    /// walls, each face row's mean v is taken away first: the projection's zonal part, exactly.
    void project();
    /// A cell of longitude's width in cells of latitude at texcoord v (GasMath.h's m, linear
    /// between half rows as the advection reads it): a point moves u / metricAt(v) cells along
    /// x a second. 1 everywhere on a flat grid.
    float metricAt(float v) const;

    /// Host access to the state (row-major W x H; see GasMath.h for where each lives).
    void setState(const std::vector<float>& u, const std::vector<float>& v, const std::vector<float>& dye);
    void readState(std::vector<float>& u, std::vector<float>& v, std::vector<float>& dye);
    /// The heights buffer() holds (row 0 at v = 0), waiting for the queue.
    std::vector<float> readHeights();
    /// The divergence the projection's Laplacian matches: outflow through each cell's faces, over
    /// its area (the sphere's when GasConfig::sphere).
    std::vector<float> readDivergence();

    const cl::Buffer& buffer() const override { return height_; }
    /// The velocity's faces on the device (cells per second; GasMath.h says where each lives),
    /// for passes that move with the gas (FlowDetail).
    const cl::Buffer& velocityX() const { return u_; }
    const cl::Buffer& velocityY() const { return v_; }
    /// The grid's metric table (GasMath.h): m at every half row, then tan(latitude) / R.
    const cl::Buffer& metric() const { return metric_; }
    /// The same table on the host.
    const std::vector<float>& metricTable() const { return metricTable_; }
    int width() const override { return config_.width; }
    int height() const override { return config_.height; }
    EdgeMode edges() const override { return config_.edges; }
    const GasConfig& config() const { return config_; }
    /// The dye's bands, one value a row (row 0 at v = 0): what GasConfig::dyeRate relaxes the
    /// dye towards (0 everywhere without initialBands).
    const std::vector<float>& bands() const { return bands_; }

private:
    /// Sets the kernel's arguments in order and enqueues it over every cell, or over `range`.
    template <typename... Args>
    void run(cl::Kernel& kernel, const Args&... args);
    template <typename... Args>
    void runOver(cl::NDRange range, cl::Kernel& kernel, const Args&... args);
    void advectField(cl::Buffer& field, float ox, float oy, float dt, bool wallRow);
    void writeHeight();

    ClContext& cl_;
    GasConfig config_;
    std::vector<GasSplat> splats_;
    std::vector<GasVortex> vortices_;
    std::vector<float> bands_;
    std::vector<float> metricTable_;
    std::unique_ptr<PolarFilter> polar_; ///< the dye's, on a sphere
    cl::Buffer samplePoints_, sampleWinds_; ///< velocityAt's, sampleCapacity_ points each
    size_t sampleCapacity_ = 0;
    std::vector<float> sampleCells_; ///< velocityAt's points in cells, uploaded from here
    cl::Buffer u_, v_, dye_, work_[4], p_, div_, curl_, height_, sumsBefore_, sumsAfter_, factor_, bandRows_,
        jetRows_, metric_, gridMetric_; ///< the grid's metric, and a flat one's (1s) for the vorticity confinement
    cl::Buffer departures_; ///< MacCormack's: each cell's departure point, two floats (gas.cl's advect_forward)
    /// GasPressure::Exact's elimination between walls (gas.cl's solve_columns) on the device.
    struct PressureColumns {
        cl::Buffer upper, pivots, lower, rhs;
    };
    cl::Buffer p2_;                ///< GasPressure::Jacobi's second pressure
    std::unique_ptr<RealFft> fft_; ///< the rows' transforms: GasPressure::Exact's, the spin's, the sphere's viscosity's
    cl::Buffer spectrum_, scratch_; ///< the transforms' spectrum; the spin's and viscosity's eliminations' c'
    PressureColumns pressureColumns_;
    cl::Kernel advect_, advectForward_, maccormack_, turn_, removeRowMean_, splat_, vortex_, sampleVelocity_, jets_,
        clampSpeed_, curlKernel_, confine_, diffuse_, divergence_, pressure_, project_, dyeHeight_, rowSums_,
        massFactor_, scale_, relaxDye_, solveColumns_, betaColumns_, addStream_, cornerLaplacian_, viscousColumns_;
};

} // namespace hfx
