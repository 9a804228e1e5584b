// One impact API across the three users: a wall, a sea and a gas giant stand in one world; an
// impact fired at each changes that surface alone, at the texel the exact pick found on the
// surface as drawn.

#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/effects/DecalWallEffect.h"
#include "hfx/effects/GasPlanetEffect.h"
#include "hfx/effects/Impacts.h"
#include "hfx/effects/OceanEffect.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace hfx::test {
namespace {

class Impacts : public DeviceTest {};

TEST_F(Impacts, EachImpactChangesOnlyTheSurfaceItHitsAtThePickedTexel) {
    // The wall: a 2 x 2 plane facing +Z at z = -5.
    DecalWallEffect wall(cl(), {.bricks = {.size = 64}});
    const PlaneConfig wallPlane{.size = 2.0f};
    const glm::mat4 wallModel = glm::rotate(glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -5.0f}), glm::radians(90.0f),
                                            glm::vec3(1.0f, 0.0f, 0.0f));
    // The sea: 400 m of water 20 m below, its texcoords in patches.
    OceanEffect ocean(cl(), {.ocean = {.size = 64, .cascades = 1}});
    const float patch = ocean.ocean().config().patchMeters;
    const PlaneConfig seaPlane{.size = 400.0f, .texcoordScale = 400.0f / patch};
    const glm::mat4 seaModel = glm::translate(glm::mat4(1.0f), {0.0f, -20.0f, 0.0f});
    // The planet: radius 1 at (10, 0, -5).
    GasPlanetEffect planet(cl(), {.gas = {.width = 64, .height = 32, .initialBands = 4.0f}, .stormsPerSecond = 0.0f});
    const glm::dvec3 planetCentre(10.0, 0.0, -5.0);

    WallImpacts wallTarget(wall, SurfaceFrame::ofPlane(wallPlane, wallModel), {0.0, 0.0, 1.0, 1.0});
    OceanImpacts seaTarget(ocean, SurfaceFrame::ofPlane(seaPlane, seaModel));
    PlanetImpacts planetTarget(planet, makeSphere({}), glm::translate(glm::mat4(1.0f), glm::vec3(planetCentre)));
    ImpactReceiver* targets[] = {&wallTarget, &seaTarget, &planetTarget};
    auto state = [&] { return std::tuple{wall.damage().size(), ocean.ringCount(), planet.gas().pendingSplats().size()}; };
    ASSERT_EQ(state(), std::tuple(0, 0, size_t(0)));

    // At the wall, from in front of it.
    const Impact atWall{.origin = {0.2, 0.1, 0.0}, .direction = {0.0, 0.0, -1.0}, .seed = 3};
    const auto wallHit = routeImpact(atWall, targets);
    ASSERT_TRUE(wallHit);
    EXPECT_EQ(wallHit->receiver, 0u);
    EXPECT_EQ(state(), std::tuple(1, 0, size_t(0)));
    const ImpactEvent logged = wall.damage().events().at(0);
    EXPECT_NEAR(logged.u, wallHit->hit.uv.x, 1e-6);
    EXPECT_NEAR(logged.v, wallHit->hit.uv.y, 1e-6);
    EXPECT_NEAR(logged.nz, 1.0f, 1e-6f) << "the wall faces +Z";
    // The pick is the drawn surface: on the path, between the polygon and the relief's depth.
    EXPECT_NEAR(wallHit->hit.world.x, 0.2, 1e-9);
    EXPECT_LE(wallHit->hit.world.z, -5.0 + 1e-9);
    EXPECT_GE(wallHit->hit.world.z, -5.0 - wall.material().depthScale * 2.0 - 1e-9);
    // It lands there: after the update the heights at that texel are lower than before.
    const std::vector<float> before = wall.readHeights();
    wall.update(0.1);
    const std::vector<float> after = wall.readHeights();
    const int x = int(logged.u * 64), y = int(logged.v * 64);
    EXPECT_LT(after[size_t(y) * 64 + x], before[size_t(y) * 64 + x] - 0.05f) << "a crater at the picked texel";

    // At the sea, down past the wall's edge.
    const Impact atSea{.origin = {0.0, 0.0, 0.0}, .direction = {0.0, -1.0, -0.2}, .kind = ImpactKind::Explosion};
    const auto seaHit = routeImpact(atSea, targets);
    ASSERT_TRUE(seaHit);
    EXPECT_EQ(seaHit->receiver, 1u);
    EXPECT_EQ(state(), std::tuple(1, 1, size_t(0)));
    const WaterRing& ring = ocean.material().water.rings[0];
    EXPECT_NEAR(ring.centre.x, seaHit->hit.uv.x, 1e-5);
    EXPECT_NEAR(ring.centre.y, seaHit->hit.uv.y, 1e-5);
    // The hit lies on the water as drawn: 20 m down, within the relief's depth below the plane.
    const double seaDepth = ocean.material().depthScale * patch;
    EXPECT_LE(seaHit->hit.world.y, -20.0 + 1e-6);
    EXPECT_GE(seaHit->hit.world.y, -20.0 - seaDepth - 1e-6);
    // ... exactly: the drawn height there, h = 0.5 + M / (8 sigma), from the CPU query.
    OceanQuery query(ocean.ocean());
    const glm::vec2 metres(float(seaHit->hit.uv.x * patch), float(seaHit->hit.uv.y * patch));
    const double M = query.heights(std::span(&metres, 1), ocean.time()).at(0);
    const double drawn = -20.0 + (0.5 + M / (8.0 * ocean.ocean().cascade(0).sigma) - 1.0) * seaDepth;
    EXPECT_NEAR(seaHit->hit.world.y, drawn, 1e-3) << "metres";

    // At the planet.
    const Impact atPlanet{.origin = {0.0, 0.0, 0.0}, .direction = planetCentre + glm::dvec3(0.0, 0.2, 0.0), .energy = 2.0f};
    const auto planetHit = routeImpact(atPlanet, targets);
    ASSERT_TRUE(planetHit);
    EXPECT_EQ(planetHit->receiver, 2u);
    EXPECT_EQ(state(), std::tuple(1, 1, size_t(3))) << "a storm: two pushes and its dye";
    const double r = glm::length(planetHit->hit.world - planetCentre);
    EXPECT_LE(r, 1.0 + 1e-9);
    EXPECT_GE(r, 0.9);
    EXPECT_NEAR(planet.gas().pendingSplats().back().u, planetHit->hit.uv.x, 1e-6) << "the storm's centre";

    // A path that meets nothing changes nothing; a bad impact is refused.
    EXPECT_FALSE(routeImpact({.origin = {0.0, 0.0, 0.0}, .direction = {0.0, 1.0, 0.0}}, targets));
    EXPECT_EQ(messageOf([&] { routeImpact({.direction = {0.0, 0.0, 0.0}}, targets); }),
              "Impact.direction must be finite and not zero, got (0, 0, 0)");
    EXPECT_EQ(messageOf([&] { routeImpact({.origin = {std::nan(""), 0.0, 1.0}}, targets); }),
              "Impact.origin must be finite, got (nan, 0, 1)");
    EXPECT_NE(messageOf([&] { routeImpact({.energy = -1.0f}, targets); }).find("energy"), std::string::npos);
    EXPECT_EQ(state(), std::tuple(1, 1, size_t(3)));
}

// The nearer surface takes the impact when two lie on its path.
TEST_F(Impacts, TheNearestSurfaceOnThePathTakesIt) {
    DecalWallEffect near(cl(), {.bricks = {.size = 64}}), far(cl(), {.bricks = {.size = 64}});
    const PlaneConfig plane{.size = 2.0f};
    auto facing = [](float z) {
        return glm::rotate(glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, z}), glm::radians(90.0f), glm::vec3(1, 0, 0));
    };
    WallImpacts a(far, SurfaceFrame::ofPlane(plane, facing(-8.0f))), b(near, SurfaceFrame::ofPlane(plane, facing(-3.0f)));
    ImpactReceiver* targets[] = {&a, &b};
    const auto hit = routeImpact({.origin = {0.1, 0.1, 0.0}, .direction = {0.0, 0.0, -1.0}}, targets);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->receiver, 1u);
    EXPECT_EQ(near.damage().size(), 1);
    EXPECT_EQ(far.damage().size(), 0);
}

} // namespace
} // namespace hfx::test
