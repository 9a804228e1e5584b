#include "hfx/effects/BrickWall.h"

#include "hfx/core/Error.h"
#include "hfx/core/Random.h"

#include <algorithm>
#include <cmath>

namespace hfx {

void BrickWallConfig::validate() const {
    if (size < 64 || size > 8192) throw Error(str("BrickWallConfig.size must be in [64, 8192], got ", size));
    if (rows < 2 || rows % 2 != 0 || rows > size / 8 || size % rows != 0)
        throw Error(str("BrickWallConfig.rows must be even, divide size and be in [2, size/8], got ", rows));
    if (bricksPerRow < 1 || bricksPerRow > size / 8 || size % (2 * bricksPerRow) != 0)
        throw Error(str("BrickWallConfig.bricksPerRow must be in [1, size/8] with 2 * bricksPerRow dividing "
                        "size, got ", bricksPerRow));
    if (!(mortarHeight >= 0.0f && mortarHeight < 0.85f))
        throw Error(str("BrickWallConfig.mortarHeight must be in [0, 0.85), got ", mortarHeight));
}

namespace {

/// A hash of integer coordinates to [0,1): the same brick always gets the same numbers.
double hash(std::uint64_t seed, long long a, long long b) {
    SplitMix64 r(seed ^ (std::uint64_t(a) * 0x9e3779b97f4a7c15ull) ^ (std::uint64_t(b) * 0xc2b2ae3d27d4eb4full));
    r.nextBits();
    return r.next();
}

/// Value noise with a period of `period` lattice cells (tileable), smooth-stepped.
double valueNoise(std::uint64_t seed, double x, double y, int period) {
    const double fx = std::floor(x), fy = std::floor(y);
    const double sx = x - fx, sy = y - fy;
    const double ux = sx * sx * (3 - 2 * sx), uy = sy * sy * (3 - 2 * sy);
    auto at = [&](long long i, long long j) {
        return hash(seed, ((i % period) + period) % period, ((j % period) + period) % period);
    };
    const long long i = static_cast<long long>(fx), j = static_cast<long long>(fy);
    const double a = at(i, j), b = at(i + 1, j), c = at(i, j + 1), d = at(i + 1, j + 1);
    return (a + (b - a) * ux) + ((c + (d - c) * ux) - (a + (b - a) * ux)) * uy;
}

} // namespace

BrickWallMaps makeBrickWall(const BrickWallConfig& config) {
    config.validate();
    const int n = config.size;
    BrickWallMaps maps;
    maps.heights.resize(size_t(n) * n);
    maps.albedo = Image{n, n, 3, std::vector<float>(size_t(n) * n * 3)};
    const double brickW = double(n) / config.bricksPerRow, brickH = double(n) / config.rows;
    // A joint's half-width and the bevel, texels: shares of a course, so a map of more courses
    // keeps the bricks' proportions (8 courses: n / 170 and n / 110).
    const double mortar = std::max(1.5, brickH / 21.25);
    const double bevel = std::max(2.0, brickH / 13.75);
    // Noise with a whole number of lattice cells across the map, so it tiles with the bricks.
    auto noise = [n](std::uint64_t seed, double px, double py, int cells) {
        return valueNoise(seed, px * cells / n, py * cells / n, cells);
    };
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double px = x + 0.5, py = y + 0.5;
            const int row = static_cast<int>(std::floor(py / brickH));
            const double shift = (row % 2) * 0.5 * brickW;
            const double bx = std::fmod(px + shift, double(n));
            const int column = static_cast<int>(std::floor(bx / brickW));
            // Distance to the nearest joint, in texels.
            const double ex = std::min(bx - column * brickW, (column + 1) * brickW - bx);
            const double ey = std::min(py - row * brickH, (row + 1) * brickH - py);
            const double edge = std::min(ex, ey);
            const double r1 = hash(config.seed, row, column), r2 = hash(config.seed + 1, row, column);
            const double tilt = (r2 - 0.5) * 0.06 * ((bx - column * brickW) / brickW - 0.5);
            const double rough = 0.035 * noise(config.seed + 2, px, py, n / 8) +
                                 0.02 * noise(config.seed + 3, px, py, n / 2);
            const double face = 0.9 + 0.04 * (r1 - 0.5) + tilt + rough - 0.03;
            const double t = std::clamp((edge - mortar) / bevel, 0.0, 1.0);
            const double sandy = 0.03 * noise(config.seed + 4, px, py, n / 2);
            const double joint = config.mortarHeight + sandy;
            const double h = edge < mortar ? joint : joint + (face - joint) * std::sqrt(t * (2 - t));
            maps.heights[size_t(y) * n + x] = float(std::clamp(h, 0.0, 1.0));
            // Colour: bricks vary from orange-red to brown, mortar is pale grey; rows of the
            // image run top first, heights bottom first.
            const double grime = 0.85 + 0.3 * noise(config.seed + 5, px, py, n / 16);
            double red = (0.55 + 0.2 * r1) * grime, green = (0.22 + 0.1 * r2) * grime, blue = (0.14 + 0.05 * r1) * grime;
            if (edge < mortar + 0.5) red = green = blue = 0.62 + 2.0 * sandy;
            const int iy = n - 1 - y;
            maps.albedo.at(x, iy, 0) = float(std::clamp(red, 0.0, 1.0));
            maps.albedo.at(x, iy, 1) = float(std::clamp(green, 0.0, 1.0));
            maps.albedo.at(x, iy, 2) = float(std::clamp(blue, 0.0, 1.0));
        }
    return maps;
}

} // namespace hfx
