// The three users as a game would use them: picking on the displaced wall against the analytic
// hit, the stamp landing where the pick said, the ocean's live wind, the planet's colours from
// the gas, and the procedural wall's tiling.

#include "support/Fixtures.h"

#include "hfx/compute/ColorRamp.h"
#include "hfx/compute/shared/ColorMath.h"
#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/tools/ImageFiles.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/Random.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/BrickWall.h"
#include "hfx/effects/DecalWallEffect.h"
#include "hfx/effects/GasPlanetEffect.h"
#include "hfx/effects/OceanEffect.h"
#include "hfx/effects/SineWavesEffect.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <vector>

namespace hfx::test {
namespace {

class Users : public DeviceTest {};

/// A wall like the decals scene's: 4 x 4 world units, texcoords 0..2, standing in the XY plane
/// facing +Z (the plane rotated 90 degrees about X), so u = (x + 2) / 2 and v = (y + 2) / 2.
constexpr PlaneConfig kWall{.size = 4.0f, .texcoordScale = 2.0f, .subdivisions = 1};
const glm::mat4 kWallModel = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0));

TEST_F(Users, PickingHitsTheDisplacedSurfaceAndTheStampLandsThere) {
    constexpr int N = 256;
    constexpr float level = 0.6f, depthScale = 0.06f;
    const std::string heightMap = outputPath("users_flat_wall.exr");
    writeImage(heightMap, Image{N, N, 1, std::vector<float>(N * N, level)});
    // Float32 texels: the stored height is the stamped one, to the bit.
    DecalWallConfig config{.maps = readSurfaceMaps(heightMap, "", ""), .surface = {.format = SurfaceFormat::Float32}};
    config.material.depthScale = depthScale;
    DecalWallEffect wall(cl(), config);

    const Camera camera = [] {
        Camera c = Camera::orbit({0.2f, -0.1f, 0.0f}, 3.0f, 0.9f, 0.35f);
        c.aspect = 16.0f / 9.0f;
        return c;
    }();
    // The surface lies (1 - h) * depthScale texture units = 2 world units each, below the wall.
    const double sunk = (1.0 - level) * depthScale * 2.0;
    const SurfaceFrame frame = SurfaceFrame::ofPlane(kWall, kWallModel);
    for (const auto& pixel : {glm::dvec2(640.5, 360.5), glm::dvec2(300.5, 500.5), glm::dvec2(1000.5, 200.5)}) {
        const Ray ray = camera.rayThroughPixel(pixel.x, pixel.y, 1280, 720);
        const double t = (-sunk - ray.origin.z) / ray.direction.z;
        const glm::dvec3 p = ray.origin + t * ray.direction;
        const glm::dvec2 expected((p.x + 2.0) / 2.0, (p.y + 2.0) / 2.0);
        const auto hit = wall.pick(ray, frame);
        ASSERT_TRUE(hit.has_value()) << pixel.x << "," << pixel.y;
        EXPECT_LT(glm::length(hit->uv - expected) * N, 1.0) << "pick off by more than a texel at pixel " << pixel.x
                                                            << "," << pixel.y;
        EXPECT_NEAR(hit->height, level, 1e-6);
        // The flat polygon would be far off: the relief matters at this angle.
        const double tFlat = -ray.origin.z / ray.direction.z;
        const glm::dvec3 q = ray.origin + tFlat * ray.direction;
        EXPECT_GT(glm::length(glm::dvec2((q.x + 2.0) / 2.0, (q.y + 2.0) / 2.0) - expected) * N, 2.0);
    }

    // Shoot where the centre pixel picked; the crater's deepest texel is there, within a texel.
    const auto hit = wall.pick(camera.rayThroughPixel(640.5, 360.5, 1280, 720), frame);
    ASSERT_TRUE(hit);
    wall.shoot(hit->uv.x, hit->uv.y);
    wall.update(1.0 / 30.0);
    const std::vector<float> heights = wall.readHeights();
    int deepest = 0;
    for (int i = 1; i < N * N; ++i)
        if (heights[i] < heights[deepest]) deepest = i;
    ASSERT_LT(heights[deepest], level - 0.1f) << "no crater was stamped";
    const glm::dvec2 landed((deepest % N + 0.5) / N, (deepest / N + 0.5) / N);
    glm::dvec2 aimed = hit->uv - glm::floor(hit->uv);
    EXPECT_LT(glm::length(landed - aimed) * N, 1.0) << "stamp landed at " << landed.x << "," << landed.y
                                                    << ", aimed at " << aimed.x << "," << aimed.y;
    // The textures follow the damage the same update: the crater's texel in the GL surface.
    const std::vector<float> texels = readSurface(wall.textures());
    EXPECT_FLOAT_EQ(texels[size_t(deepest) * 4 + 3], heights[deepest]);
}

TEST_F(Users, DecalWallKeepsTheNormalMapWhereUndamagedAndBendsItInCraters) {
    constexpr int N = 256; // the bullet's radius, 0.012 widths, spans 3 texels
    const std::string heightMap = outputPath("users_nm_height.exr"), normalMap = outputPath("users_nm_normal.png");
    writeImage(heightMap, Image{N, N, 1, std::vector<float>(N * N, 0.7f)});
    // A tilted normal everywhere: (0.3, -0.2, ~0.93), stored as 0.5 + 0.5 n in 8 bits.
    Image normals{N, N, 3, std::vector<float>(N * N * 3)};
    for (int i = 0; i < N * N; ++i) {
        normals.pixels[i * 3 + 0] = 0.5f + 0.5f * 0.3f;
        normals.pixels[i * 3 + 1] = 0.5f - 0.5f * 0.2f;
        normals.pixels[i * 3 + 2] = 0.5f + 0.5f * 0.933f;
    }
    writeImage(normalMap, normals);
    const Image stored = readImage(normalMap); // the 8-bit values the wall will see
    glm::vec3 expected(2.0f * stored.at(0, 0, 0) - 1.0f, 2.0f * stored.at(0, 0, 1) - 1.0f, 2.0f * stored.at(0, 0, 2) - 1.0f);
    expected = glm::normalize(expected);

    // Float32 texels: the map's normal, to a float's rounding.
    DecalWallEffect wall(cl(), {.maps = readSurfaceMaps(heightMap, normalMap, ""),
                                .surface = {.format = SurfaceFormat::Float32}});
    std::vector<float> texels = readSurface(wall.textures());
    for (int i = 0; i < N * N; ++i)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(texels[i * 4 + c], expected[c], 1e-6f) << "texel " << i;

    wall.shoot(0.5, 0.5);
    wall.update(1.0 / 30.0);
    texels = readSurface(wall.textures());
    const auto at = [&](int x, int y) { return glm::vec3(texels[(y * N + x) * 4], texels[(y * N + x) * 4 + 1], texels[(y * N + x) * 4 + 2]); };
    // Far from the crater: the map exactly. On its flanks: bent, still unit length; the flank
    // towards +u tilts the normal towards -u relative to the map (the bowl rises to the right).
    EXPECT_LT(glm::length(at(5, 5) - expected), 1e-6f);
    const glm::vec3 flank = at(N / 2 + 1, N / 2);
    EXPECT_NEAR(glm::length(flank), 1.0f, 1e-5f);
    EXPECT_LT(flank.x / flank.z, expected.x / expected.z - 0.05f);

    // A deeper material leaves the stored normals alone (the renderer rescales them): undamaged
    // texels still hold the map exactly.
    SurfaceMaterial deeper = wall.material();
    deeper.depthScale = 0.12f;
    wall.setMaterial(deeper);
    wall.update(1.0 / 30.0);
    texels = readSurface(wall.textures());
    EXPECT_LT(glm::length(at(5, 5) - expected), 1e-6f);

    // A normal map that does not match the heights is refused, naming it.
    const std::string small = outputPath("users_nm_small.png");
    writeImage(small, Image{16, 16, 3, std::vector<float>(16 * 16 * 3, 0.5f)});
    try {
        DecalWallEffect bad(cl(), {.maps = readSurfaceMaps(heightMap, small, "")});
        FAIL() << "a mismatched normal map was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(small), std::string::npos) << e.what();
    }
}

TEST_F(Users, PickingMissesOutsideThePatchAndLookingAway) {
    DecalWallEffect wall(cl(), {.bricks = {.size = 128}});
    const SurfaceFrame frame = SurfaceFrame::ofPlane(kWall, kWallModel);
    // Behind the wall, looking away from it.
    EXPECT_FALSE(wall.pick({{0, 0, 3}, {0, 0, 1}}, frame));
    // Parallel to the wall.
    EXPECT_FALSE(wall.pick({{0, 0, 3}, {1, 0, 0}}, frame));
    const HeightFieldTracer flat(std::vector<float>(64, 1.0f), 8, 8, EdgeMode::Wrap);
    EXPECT_FALSE(pickSurface({{10, 0, 3}, {0, 0, -1}}, frame, flat, 0.05, {0, 0, 2, 2}));
    EXPECT_TRUE(pickSurface({{0, 0, 3}, {0, 0, -1}}, frame, flat, 0.05, {0, 0, 2, 2}));
    // A ray from a cursor outside the window's numbers, or a frame from a broken model matrix, is
    // refused by name, not missed.
    EXPECT_EQ(messageOf([&] { pickSurface({{0, std::nan(""), 3}, {0, 0, -1}}, frame, flat, 0.05); }),
              "pickSurface: the ray must be finite and have a direction, got origin (0, nan, 3) and direction (0, 0, -1)");
    EXPECT_NE(messageOf([&] { pickSurface({{0, 0, 3}, {0, 0, 0}}, frame, flat, 0.05); }).find("direction (0, 0, 0)"),
              std::string::npos);
    SurfaceFrame broken = frame;
    broken.normal.x = std::nan("");
    EXPECT_NE(messageOf([&] { pickSurface({{0, 0, 3}, {0, 0, -1}}, broken, flat, 0.05); })
                  .find("pickSurface: the surface frame must be finite"),
              std::string::npos);
    EXPECT_THROW(wall.shoot(std::nan(""), 0.5), Error);
}

TEST_F(Users, AClientWallThatAddsTheServersImpactsAtTheirTimesDrawsTheServersWall) {
    // A server's wall takes impacts as they come; a client's hears of them a few seconds late and
    // adds each at its time (impactAt): after the same updates both walls hold the same stamps,
    // their heal curves read at the same ages (the roughness heals from 5 s), and heights.
    DecalWallEffect server(cl(), {.bricks = {.size = 64}}), client(cl(), {.bricks = {.size = 64}});
    SplitMix64 random(5);
    std::vector<std::pair<ImpactEvent, double>> heard;
    for (int frame = 0; frame < 12; ++frame) {
        const ImpactEvent e{.u = float(random.next()), .v = float(random.next()), .radius = 0.05f,
                            .kind = frame % 4 == 0 ? ImpactKind::Explosion : ImpactKind::Bullet, .seed = random.nextBits()};
        server.impact(e);
        heard.emplace_back(e, server.damage().now());
        if (frame % 3 == 2) { // a burst
            for (const auto& [impact, time] : heard) client.impactAt(impact, time);
            heard.clear();
        }
        server.update(2.0);
        client.update(2.0);
    }
    const std::vector<BulletHole> a = server.damage().stamps(), b = client.damage().stamps();
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(BulletHole)), 0) << "the heal curves' ages differ";
    EXPECT_EQ(server.readHeights(), client.readHeights());
    EXPECT_NE(messageOf([&] { client.impactAt({}, client.damage().now() + 1.0); }).find("DamageLog::addAt"),
              std::string::npos);
}

TEST_F(Users, AClientJoiningLateLoadsTheServersSnapshotFromAStreamAndDrawsTheServersWall) {
    // A client that joins after the fighting started gets the server's damage as one message
    // (saveDamage into a string stream) and loads it (loadDamage from one): after the same
    // updates both walls hold the same heights to the bit. A message cut short is refused naming
    // the stream and the line, and the client keeps the damage it had.
    DecalWallEffect server(cl(), {.bricks = {.size = 64}}), client(cl(), {.bricks = {.size = 64}});
    SplitMix64 random(8);
    for (int frame = 0; frame < 10; ++frame) {
        server.impact({.u = float(random.next()), .v = float(random.next()), .radius = 0.05f,
                       .kind = frame % 4 == 0 ? ImpactKind::Explosion : ImpactKind::Bullet, .seed = random.nextBits()});
        server.update(1.5);
    }
    client.impact({.u = 0.5f, .v = 0.5f, .radius = 0.08f}); // what the client had before it joined
    client.update(0.1);
    std::ostringstream message;
    server.saveDamage(message, "the server's snapshot");
    const std::string text = message.str();
    ASSERT_GT(server.damage().size(), 5);

    // Cut inside an impact's line, and at the end of one (where only the count can tell).
    const size_t middle = text.size() / 2;
    for (const size_t end : {middle, text.rfind('\n', middle) + 1}) {
        std::istringstream cut(text.substr(0, end));
        const std::string refusal = messageOf([&] { client.loadDamage(cut, "the server's snapshot"); });
        EXPECT_EQ(refusal.rfind("the server's snapshot:", 0), 0u) << refusal;
        ASSERT_EQ(client.damage().size(), 1) << "a failed load changed the client's damage";
    }

    std::istringstream whole(text);
    client.loadDamage(whole, "the server's snapshot");
    EXPECT_EQ(client.damage().size(), server.damage().size());
    EXPECT_NE(server.readHeights(), DecalWallEffect(cl(), {.bricks = {.size = 64}}).readHeights());
    for (int frame = 0; frame < 3; ++frame) {
        server.update(4.0);
        client.update(4.0);
        const std::vector<BulletHole> a = server.damage().stamps(), b = client.damage().stamps();
        ASSERT_EQ(a.size(), b.size());
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(BulletHole)), 0) << "frame " << frame;
        EXPECT_EQ(server.readHeights(), client.readHeights()) << "frame " << frame;
    }
}

TEST_F(Users, AFreshCratersEmbersGlowInCracksAndCool) {
    // An explosion's bowl is hot (the shading channels' heat, which the lit model emits lit or
    // not) and cools over DamageLook::glow's 3 s. Seen with the sun behind the wall, whose face
    // then has the ambient light alone, the crater's floor is a crust of dim red plates with
    // cracks that glow orange; the plates darken first as it cools (their heat falls with the
    // crater's twice over: hfx_decal_crust), and once cooled it is as dark as soot.
    DecalWallEffect wall(cl(), {.bricks = {.size = 256}});
    wall.explode(0.0, 0.0, 7); // texcoords (1, 1): the middle of kWall
    wall.update(1.0 / 30.0);
    const Mesh mesh(makePlane(kWall));
    Camera camera;
    camera.position = {0.0f, 0.0f, 1.2f};
    camera.target = {0.0f, 0.0f, 0.0f};
    camera.aspect = 1.0f;
    const DirectionalLight behind{.direction = {0.0f, 0.3f, -1.0f}};
    SurfaceRenderer renderer;
    constexpr int kSize = 128;
    RenderTarget target(kSize, kSize);
    target.bind();
    struct Floor {
        glm::vec3 crack{0.0f}; // its brightest pixel (red)
        float plate = 0.0f;    // its median red
    };
    auto floor = [&](const char* name) { // the pixels within 5 of the middle (the bowl is about 10 across)
        target.clear();
        renderer.draw(mesh, kWallModel, wall.textures(), wall.material(), camera, behind,
                      {.technique = Technique::ParallaxOcclusion});
        const Image color = target.readColor();
        writeImage(outputPath(std::string("users_embers_") + name + ".png"), color);
        Floor f;
        std::vector<float> reds;
        for (int y = kSize / 2 - 5; y <= kSize / 2 + 5; ++y)
            for (int x = kSize / 2 - 5; x <= kSize / 2 + 5; ++x) {
                if ((x - kSize / 2) * (x - kSize / 2) + (y - kSize / 2) * (y - kSize / 2) > 25) continue;
                const glm::vec3 c(color.at(x, y, 0), color.at(x, y, 1), color.at(x, y, 2));
                if (c.r > f.crack.r) f.crack = c;
                reds.push_back(c.r);
            }
        std::nth_element(reds.begin(), reds.begin() + std::ptrdiff_t(reds.size() / 2), reds.end());
        f.plate = reds[reds.size() / 2];
        std::printf("the crater's floor %s: cracks %.3f %.3f %.3f, plates %.3f red\n", name, f.crack.r, f.crack.g,
                    f.crack.b, f.plate);
        return f;
    };
    const Floor hot = floor("fresh");
    wall.update(1.2);
    const Floor cooling = floor("cooling");
    wall.update(2.5); // past the glow curve's end
    const Floor cold = floor("cold");
    EXPECT_GT(hot.crack.r, 0.8f) << "a fresh crater's cracks do not glow";
    EXPECT_GT(hot.crack.r - hot.crack.b, 0.4f) << "embers glow orange, not white";
    EXPECT_GT(hot.crack.r, 1.3f * hot.plate) << "the floor glows evenly: no cracks";
    // (Measured: the cracks over the plates 1.52 fresh, 1.89 cooling; with plates kept at 0.48 of
    // the heat as the crater cools, 1.66 cooling.)
    EXPECT_GT(cooling.crack.r / cooling.plate, 1.17f * hot.crack.r / hot.plate) << "the plates do not darken first";
    EXPECT_LT(cold.crack.r, 0.3f) << "the crater still glows after its curve's end";
}

TEST_F(Users, DecalWallRefusesBadMapsAndKeepsNoHalfState) {
    const std::string bad = outputPath("users_missing_wall.png");
    try {
        DecalWallEffect wall(cl(), {.maps = readSurfaceMaps(bad, "", "")});
        FAIL() << "a missing height map was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
    // Colours without heights, and heights that do not fit their size, are refused by name.
    SurfaceMaps colourOnly;
    colourOnly.color = Image{4, 4, 3, std::vector<float>(48, 0.5f)};
    EXPECT_NE(messageOf([&] { DecalWallEffect(cl(), {.maps = colourOnly}); }).find("height"), std::string::npos);
    SurfaceMaps short_{.width = 8, .height = 8, .heights = std::vector<float>(10, 0.5f)};
    EXPECT_NE(messageOf([&] { DecalWallEffect(cl(), {.maps = short_}); }).find("8x8"), std::string::npos);
    EXPECT_THROW(DecalWallEffect(cl(), {.bricks = {.size = 100, .rows = 7}}), Error);
}

TEST_F(Users, OceanWindChangesTheSeaAndItsDepthAndBadWindChangesNothing) {
    OceanEffectConfig config;
    config.ocean.size = 64;
    config.ocean.cascades = 1;
    OceanEffect ocean(cl(), config);
    const float calmDepth = ocean.material().depthScale;
    EXPECT_NEAR(calmDepth, 8.0f * ocean.ocean().sigmaMeters() / ocean.ocean().config().patchMeters, 1e-6f);
    const std::vector<float> before = readSurface(ocean.textures());
    ocean.setWind(4.0f, 1.2f); // blends in over config.windBlendSeconds (4 s)
    EXPECT_EQ(ocean.material().depthScale, calmDepth) << "the new sea takes over at once";
    EXPECT_EQ(readSurface(ocean.textures()), before);
    ocean.update(2.0);
    const float midway = ocean.material().depthScale;
    EXPECT_LT(midway, calmDepth);
    ocean.update(2.5);
    // A light wind raises a much lower sea (the spectrum's energy grows steeply with the wind
    // while its peak fits in the patch): shallower relief, reached through the blend.
    EXPECT_LT(ocean.material().depthScale, calmDepth / 4.0f);
    EXPECT_LT(ocean.material().depthScale, midway);
    EXPECT_NEAR(ocean.material().depthScale,
                std::max(8.0f * ocean.ocean().sigmaMeters() / ocean.ocean().config().patchMeters, 1e-5f), 1e-7f)
        << "the depth follows the sea (not below 1e-5: a patch of 64 texels hardly resolves a 4 m/s sea)";
    EXPECT_NE(readSurface(ocean.textures()), before);
    const float stormDepth = ocean.material().depthScale;
    EXPECT_THROW(ocean.setWind(-3.0f, 0.0f), Error);
    EXPECT_THROW(ocean.setWind(10.0f, std::nanf("")), Error);
    EXPECT_EQ(ocean.material().depthScale, stormDepth);
    EXPECT_EQ(ocean.ocean().config().sea.wind.windSpeed, 4.0f);
    // The spectrum is the one a fresh ocean of that patch with that wind would draw.
    OceanConfig same = ocean.ocean().config();
    same.sea.wind.windSpeed = 4.0f;
    same.sea.wind.direction = 1.2f;
    EXPECT_EQ(ocean.ocean().cascade(0).h0, OceanField::spectrumAmplitudes(same, 0));
}

TEST_F(Users, PlanetColoursComeFromTheGasThroughTheRamp) {
    GasPlanetConfig config;
    config.gas.width = 64;
    config.gas.height = 32;
    config.gas.initialBands = 4.0f;
    config.stormsPerSecond = 5.0f;
    config.surface.format = SurfaceFormat::Float32; // the stored heights are the ramp's inputs
    GasPlanetEffect planet(cl(), config);
    for (int i = 0; i < 3; ++i) planet.update(1.0 / 30.0);
    const std::vector<float> surface = readSurface(planet.textures());
    const int texels = planet.surfaceWidth() * planet.surfaceHeight();
    std::vector<unsigned char> albedo(size_t(texels) * 4);
    glGetTextureImage(planet.textures().albedo(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(albedo.size()), albedo.data());
    const std::vector<float> stops = ColorRamp::pack(config.palette);
    int distinct = 0;
    for (int i = 0; i < texels; ++i) {
        ASSERT_TRUE(std::isfinite(surface[i * 4 + 3]));
        unsigned char expected[4];
        hfx_ramp_rgba8(surface[i * 4 + 3], stops.data(), int(config.palette.size()), expected);
        for (int c = 0; c < 4; ++c) ASSERT_EQ(albedo[i * 4 + c], expected[c]) << "texel " << i << " channel " << c;
        distinct += albedo[i * 4] != albedo[0];
    }
    EXPECT_GT(distinct, 64) << "the planet is one colour";
    // The longitude wraps and the poles clamp.
    GLint wrapS = 0, wrapT = 0;
    glGetTextureParameteriv(planet.textures().surface(), GL_TEXTURE_WRAP_S, &wrapS);
    glGetTextureParameteriv(planet.textures().surface(), GL_TEXTURE_WRAP_T, &wrapT);
    EXPECT_EQ(wrapS, GL_REPEAT);
    EXPECT_EQ(wrapT, GL_CLAMP_TO_EDGE);
    EXPECT_THROW(GasPlanetEffect(cl(), {.gas = {.width = 64, .height = 32, .edges = EdgeMode::Wrap}}), Error);
}

TEST_F(Users, OverlappedUpdatesGiveTheSameFieldsIntoTheOtherTextures) {
    SineWavesEffect sequential(cl(), {.waves = {.size = 64}});
    SineWavesEffect overlapped(cl(), {.waves = {.size = 64}});
    for (int frame = 0; frame < 3; ++frame) {
        const GLuint drawn = overlapped.textures().surface();
        const std::vector<float> drawnTexels = readSurface(overlapped.textures());
        overlapped.beginUpdate(1.0 / 30.0); // a draw of `drawn` would go here
        overlapped.endUpdate();
        sequential.update(1.0 / 30.0);
        // Double buffered: the new field went into the other texture; the drawn one is intact.
        EXPECT_NE(overlapped.textures().surface(), drawn);
        std::vector<float> still(drawnTexels.size());
        glGetTextureImage(drawn, 0, GL_RGBA, GL_FLOAT, GLsizei(still.size() * sizeof(float)), still.data());
        EXPECT_EQ(still, drawnTexels) << "frame " << frame;
        EXPECT_EQ(readSurface(overlapped.textures()), readSurface(sequential.textures())) << "frame " << frame;
    }
    // A begin without its end is finished by the next update; two begins never overlap.
    overlapped.beginUpdate(1.0 / 30.0);
    overlapped.beginUpdate(1.0 / 30.0);
    overlapped.update(1.0 / 30.0);
    sequential.update(1.0 / 30.0);
    sequential.update(1.0 / 30.0);
    sequential.update(1.0 / 30.0);
    EXPECT_EQ(readSurface(overlapped.textures()), readSurface(sequential.textures()));
    EXPECT_DOUBLE_EQ(overlapped.time(), sequential.time());
}

TEST_F(Users, SmallerFormatsStoreWhatTheyNameAndStayCloseToFloat) {
    SineWavesEffect full(cl(), {.waves = {.size = 64}, .surface = {.format = SurfaceFormat::Float32}});
    SineWavesEffect half(cl(), {.waves = {.size = 64}, .surface = {.format = SurfaceFormat::Float16}});
    SineWavesEffect bytes(cl(), {.waves = {.size = 64}, .surface = {.format = SurfaceFormat::Unorm8}});
    for (int i = 0; i < 3; ++i) { // the second and third go through the other texture pair
        full.update(0.1);
        half.update(0.1);
        bytes.update(0.1);
    }
    auto internalFormat = [](const SurfaceTextures& t) {
        GLint format = 0;
        glGetTextureLevelParameteriv(t.surface(), 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
        return format;
    };
    EXPECT_EQ(internalFormat(half.textures()), GL_RGBA16F);
    EXPECT_EQ(internalFormat(bytes.textures()), GL_RGBA8);
    const std::vector<float> a = readSurface(full.textures()), h = readSurface(half.textures()),
                             b = readSurface(bytes.textures());
    double worstHalf = 0.0, worstNormal = 0.0, worstHeight = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        worstHalf = std::max(worstHalf, double(std::abs(a[i] - h[i])));
        // unorm8 stores n/2 + 1/2: decode as the shader does.
        const double decoded = i % 4 == 3 ? b[i] : b[i] * 2.0 - 1.0;
        (i % 4 == 3 ? worstHeight : worstNormal) =
            std::max(i % 4 == 3 ? worstHeight : worstNormal, std::abs(a[i] - decoded));
    }
    EXPECT_GT(worstHalf, 0.0) << "no rounding at all: the texture is not half float";
    EXPECT_LT(worstHalf, 1e-3) << "half floats hold [0,1] values to 2^-11";
    // Rounding to nearest: half a step of 1/255, doubled for the normal's n/2 + 1/2.
    EXPECT_GT(worstHeight, 0.0) << "no rounding at all: the texture is not 8-bit";
    EXPECT_LE(worstHeight, 0.5 / 255 + 1e-6);
    EXPECT_LE(worstNormal, 1.0 / 255 + 1e-6);
}

TEST_F(Users, ColorRampKernelMatchesTheSharedMathIncludingNaN) {
    const std::vector<ColorStop> stops = {{0.1f, {0, 0, 0}}, {0.5f, {1, 0.5f, 0}}, {0.9f, {0.2f, 0.4f, 1}}};
    constexpr int W = 40, H = 10;
    std::vector<float> field(W * H);
    for (int i = 0; i < W * H; ++i) field[i] = -0.2f + 1.4f * float(i) / (W * H);
    field[7] = std::nanf("");
    cl::Buffer input(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, field.size() * sizeof(float), field.data());
    ColorRamp ramp(cl(), W, H, stops);
    ramp.run(input);
    std::vector<cl_uchar4> out(W * H);
    cl().queue().enqueueReadBuffer(ramp.output(), CL_TRUE, 0, out.size() * sizeof(cl_uchar4), out.data());
    const std::vector<float> packed = ColorRamp::pack(stops);
    for (int i = 0; i < W * H; ++i) {
        unsigned char expected[4];
        hfx_ramp_rgba8(field[i], packed.data(), 3, expected);
        for (int c = 0; c < 4; ++c) ASSERT_EQ(out[i].s[c], expected[c]) << i;
    }
    // Analytic points: the middle stop exactly, halfway between the first two, below and above.
    unsigned char mid[4], half[4], below[4], above[4];
    hfx_ramp_rgba8(0.5f, packed.data(), 3, mid);
    hfx_ramp_rgba8(0.3f, packed.data(), 3, half);
    hfx_ramp_rgba8(-5.0f, packed.data(), 3, below);
    hfx_ramp_rgba8(5.0f, packed.data(), 3, above);
    EXPECT_EQ(mid[0], 255);
    EXPECT_EQ(mid[1], 128);
    EXPECT_EQ(half[0], 128);
    EXPECT_EQ(below[0], 0);
    EXPECT_EQ(above[2], 255);
    EXPECT_EQ(out[7].s[0], 0) << "NaN takes the first colour";
    EXPECT_THROW(ColorRamp(cl(), W, H, {{0.5f, {0, 0, 0}}, {0.4f, {1, 1, 1}}}), Error);
    EXPECT_THROW(ColorRamp(cl(), W, H, {{0.5f, {0, 0, 0}}}), Error);
    EXPECT_THROW(ColorRamp(cl(), W, H, {{0.0f, {0, 0, 2}}, {1.0f, {1, 1, 1}}}), Error);
}

TEST(BrickWall, TilesAndStaysInRange) {
    const BrickWallMaps wall = makeBrickWall({.size = 128});
    double jumpAcross = 0.0, jumpInside = 0.0;
    for (int y = 0; y < 128; ++y) {
        jumpAcross = std::max(jumpAcross, double(std::abs(wall.heights[y * 128 + 127] - wall.heights[y * 128])));
        jumpInside = std::max(jumpInside, double(std::abs(wall.heights[y * 128 + 64] - wall.heights[y * 128 + 63])));
    }
    for (float h : wall.heights) ASSERT_TRUE(h >= 0.0f && h <= 1.0f);
    // Across the wrap the wall is as continuous as anywhere inside it.
    EXPECT_LE(jumpAcross, std::max(jumpInside, 0.45) + 1e-6);
    EXPECT_THROW(makeBrickWall({.size = 32}), Error);
}

} // namespace
} // namespace hfx::test
