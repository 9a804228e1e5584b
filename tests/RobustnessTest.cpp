// Bad input at the module's entry points: each call is refused with a message naming the
// problem, and the object it was made on is left exactly as it was.

#include "support/Fields.h"
#include "support/Fixtures.h"

#include "hfx/compute/StaticField.h"
#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/DecalWallEffect.h"
#include "hfx/effects/GasPlanetEffect.h"
#include "hfx/effects/ImageSurface.h"
#include "hfx/effects/OceanEffect.h"
#include "hfx/effects/PlanetRings.h"
#include "hfx/effects/SineWavesEffect.h"
#include "hfx/effects/SurfacePipeline.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/effects/tracer/TexelShadowPass.h"

#if defined(HFX_WITH_OPENIMAGEIO)
#include <OpenImageIO/imageio.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <limits>
#include <utility>

namespace hfx::test {
namespace {

class Robustness : public DeviceTest {};

TEST_F(Robustness, BadTimeStepsAndDepthScalesChangeNothing) {
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    SineWavesEffect water(cl(), {.waves = {.size = 64}});
    OceanEffect ocean(cl(), {.ocean = {.size = 64, .cascades = 1}});
    DecalWallEffect wall(cl(), {.bricks = {.size = 64}});
    GasPlanetEffect planet(cl(), {.gas = {.width = 32, .height = 16, .initialBands = 2.0f}});
    for (Effect* effect : std::initializer_list<Effect*>{&water, &ocean, &wall, &planet}) {
        effect->update(0.02);
        const std::vector<float> before = readSurface(effect->textures());
        const SurfaceMaterial material = effect->material();
        for (double dt : {0.0, -0.1, nan, inf}) {
            const std::string m = messageOf([&] { effect->update(dt); });
            EXPECT_NE(m.find("dt"), std::string::npos) << m;
        }
        for (float depth : {-0.1f, 2.0f, float(nan)}) {
            SurfaceMaterial bad = material;
            bad.depthScale = depth;
            const std::string m = messageOf([&] { effect->setMaterial(bad); });
            EXPECT_NE(m.find("depthScale"), std::string::npos) << m;
        }
        EXPECT_EQ(readSurface(effect->textures()), before);
        EXPECT_EQ(effect->material(), material);
    }
    EXPECT_EQ(water.time(), 0.02);
}

TEST_F(Robustness, TexelShadowsNeedFittingBoundsAndHoldOnlyTheirHeightsAndLight) {
    // The texel shadows are the bounds' walk: bounds of another size are refused by name. A bad
    // light is refused before anything is drawn and leaves the last texel shadows as they were;
    // they hold only the texels and the light they were drawn from (the exact tracer redraws them
    // when either changes).
    constexpr int N = 32;
    const std::vector<float> heights = sumOfSines(N, {{0.3, 2, 1, 0.0}});
    const ShadowLight light = ShadowLight::of({0.05f, 0.02f}, 2.0f);
    ShadowLight bad = light;
    bad.penumbra = 2.0f;
    StaticField field(cl(), N, N, EdgeMode::Wrap, heights);
    SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
    surface.run(field.buffer());
    const SurfaceTextures& drawn = surface.textures();
    TexelShadowPass pass;
    TexelShadows shadows;
    HeightBounds other(N / 2, N, EdgeMode::Wrap), bounds(drawn.config());
    std::string m = messageOf([&] { pass.draw(drawn, other, light, 1, shadows); });
    EXPECT_NE(m.find("height bounds are 16x32"), std::string::npos) << m;
    EXPECT_EQ(shadows.texture(), 0u);

    pass.draw(drawn, bounds, light, 1, shadows);
    ASSERT_NE(shadows.texture(), 0u);
    EXPECT_EQ(shadows.light(), light);
    EXPECT_TRUE(shadows.holds(drawn, light, 1));
    EXPECT_FALSE(shadows.holds(drawn, light, 2));
    EXPECT_FALSE(shadows.holds(drawn, ShadowLight::of({0.05f, 0.03f}, 2.0f), 1));
    m = messageOf([&] { pass.draw(drawn, bounds, bad, 1, shadows); });
    EXPECT_NE(m.find("ShadowLight.penumbra"), std::string::npos) << m;
    EXPECT_EQ(shadows.light(), light);
    EXPECT_TRUE(shadows.holds(drawn, light, 1));
    surface.run(field.buffer());
    surface.run(field.buffer()); // the same pair again, with new texels
    ASSERT_EQ(&surface.textures(), &drawn);
    EXPECT_FALSE(shadows.holds(surface.textures(), light, 1)) << "texel shadows outlived their heights";
}

TEST_F(Robustness, TheTexelShadowPassDrawsTheSameTexelsWhateverStateTheCallerLeftAndPutsItBack) {
    // The pass runs before a hier draw, wherever the caller is in its own drawing: a
    // framebuffer bound with a small viewport, blending that zeroes what is drawn, a scissor
    // around one texel, buffer 0's red masked off and an image of the caller's on the unit the
    // pass reads the pyramid from and on the one it writes the texels through must neither change
    // a texel nor survive the pass's own state into the caller's.
    constexpr int N = 32;
    const std::vector<float> heights = sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.2, -1, 3, 0.4}});
    const ShadowLight light = ShadowLight::of({0.6f, 0.25f}, 2.0f); // low: long shadows
    StaticField field(cl(), N, N, EdgeMode::Wrap, heights);
    auto texels = [&](const TexelShadows& shadows) {
        std::vector<float> t(size_t(N) * N, -1.0f);
        HFX_GL_CHECK(glGetTextureImage(shadows.texture(), 0, GL_RED, GL_FLOAT, GLsizei(t.size() * sizeof(float)),
                                       t.data()));
        return t;
    };
    const auto config = SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false});
    SurfacePipeline reference(cl(), config), surface(cl(), config);
    for (SurfacePipeline* s : {&reference, &surface}) s->run(field.buffer());
    TexelShadowPass pass;
    TexelShadows referenceShadows, shadows;
    HeightBounds referenceBounds(config.width, config.height, config.edges), bounds(N, N, EdgeMode::Wrap);
    pass.draw(reference.textures(), referenceBounds, light, 1, referenceShadows); // from a clean state
    const std::vector<float> clean = texels(referenceShadows);
    ASSERT_GT(*std::max_element(clean.begin(), clean.end()), 0.1f) << "the light must cast some shadow";

    RenderTarget caller(40, 24);
    caller.bind();
    glViewport(3, 2, 17, 9);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ZERO, GL_ZERO);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 1, 1);
    glColorMaski(0, GL_FALSE, GL_TRUE, GL_TRUE, GL_TRUE);
    const GlTexture image = GlTexture::create();
    HFX_GL_CHECK(glTextureStorage2D(image.id(), 1, GL_R32F, 4, 4));
    glBindImageTexture(0, image.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glBindImageTexture(HFX_IMAGE_PASS_OUTPUT, image.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
    GLint boundBefore = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &boundBefore);
    TexelShadowPass fresh; // the same heights, a fresh pass: nothing built before
    fresh.draw(surface.textures(), bounds, light, 1, shadows);
    for (const auto& [unit, access] :
         {std::pair{0u, GLenum(GL_WRITE_ONLY)}, std::pair{GLuint(HFX_IMAGE_PASS_OUTPUT), GLenum(GL_READ_ONLY)}}) {
        SCOPED_TRACE(unit);
        GLint imageName = 0, imageAccess = 0, imageFormat = 0;
        glGetIntegeri_v(GL_IMAGE_BINDING_NAME, unit, &imageName);
        glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, unit, &imageAccess);
        glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, unit, &imageFormat);
        glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
        EXPECT_EQ(GLuint(imageName), image.id());
        EXPECT_EQ(GLenum(imageAccess), GLenum(access));
        EXPECT_EQ(GLenum(imageFormat), GLenum(GL_R32F));
    }
    GLint bound = 0, viewport[4];
    GLboolean mask[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
    glGetIntegerv(GL_VIEWPORT, viewport);
    glGetBooleani_v(GL_COLOR_WRITEMASK, 0, mask);
    const bool blend = glIsEnabled(GL_BLEND), scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    EXPECT_EQ(texels(shadows), clean);
    EXPECT_EQ(bound, boundBefore);
    EXPECT_EQ(viewport[0], 3);
    EXPECT_EQ(viewport[1], 2);
    EXPECT_EQ(viewport[2], 17);
    EXPECT_EQ(viewport[3], 9);
    EXPECT_TRUE(blend);
    EXPECT_TRUE(scissor);
    EXPECT_FALSE(mask[0]);
    EXPECT_TRUE(mask[1] && mask[2] && mask[3]);
}

TEST(TexelShadowsPay, FromEnoughPixelsPerTexelHeldOnJustBelowAndNeverOnBadCounts) {
    const double texels = 256.0 * 256.0;
    EXPECT_TRUE(texelShadowsPay(1.8 * texels, texels, false));
    EXPECT_FALSE(texelShadowsPay(1.6 * texels, texels, false)); // the decal wall at 512²: even
    EXPECT_TRUE(texelShadowsPay(1.6 * texels, texels, true));   // held on near the line
    EXPECT_FALSE(texelShadowsPay(1.4 * texels, texels, true));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const auto& [pixels, count] : {std::pair{nan, texels}, std::pair{1e6, nan}, std::pair{1e6, 0.0},
                                        std::pair{-1.0, texels}, std::pair{1e6, -5.0}})
        EXPECT_FALSE(texelShadowsPay(pixels, count, true)) << pixels << " pixels, " << count << " texels";
}

TEST(TexelShadowStride, EverySampleWhereThatPaysElseTheFewestWithinThePixelBudgetElseNone) {
    constexpr int N = 1024;
    const double texels = double(N) * N;
    EXPECT_EQ(texelShadowStride(1.8 * texels, N, N, 0.0f, 0), 1);
    // The noise plane at 1024²: 0.45 pixels per texel, about 0.67 pixels apart on each axis.
    EXPECT_EQ(texelShadowStride(0.45 * texels, N, N, 0.0f, 0), 0); // no budget: walk
    EXPECT_EQ(texelShadowStride(0.45 * texels, N, N, 1.0f, 0), 0); // every 2nd: 1.34 px apart
    EXPECT_EQ(texelShadowStride(0.45 * texels, N, N, 1.5f, 0), 2); // and 1.8 px per sample pays
    // The decal wall at 1024²: 0.40 per texel; every 2nd sample does not pay (1.6 per sample),
    // every 4th does, 2.53 px apart.
    EXPECT_EQ(texelShadowStride(0.40 * texels, N, N, 2.0f, 0), 0);
    EXPECT_EQ(texelShadowStride(0.40 * texels, N, N, 3.0f, 0), 4);
    EXPECT_EQ(texelShadowStride(0.40 * texels, N, N, 2.0f, 2), 2); // held on at 1.6 per sample
    EXPECT_EQ(texelShadowStride(1.6 * texels, N, N, 0.0f, 1), 1);
    // Only strides that divide the field: a 64x48 field seen on 30 pixels would need every 16th
    // sample (48 = 16 * 3), a 64x40 one gets none (40 has no factor 16).
    EXPECT_EQ(texelShadowStride(30.0, 64, 48, 64.0f, 0), 16);
    EXPECT_EQ(texelShadowStride(30.0, 64, 40, 64.0f, 0), 0);
    EXPECT_EQ(texelShadowStride(0.45 * texels, N, N, std::numeric_limits<float>::quiet_NaN(), 0), 0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const auto& [pixels, width] : {std::pair{nan, N}, std::pair{0.0, N}, std::pair{1e6, 0}, std::pair{-1.0, N}})
        EXPECT_EQ(texelShadowStride(pixels, width, N, 64.0f, 0), 0) << pixels << " pixels, width " << width;
}

TEST_F(Robustness, TexelShadowStridesThatDoNotDivideTheFieldAreRefusedByNameAndTheOthersTakeTheWalksSamples) {
    constexpr int N = 32;
    StaticField field(cl(), N, N, EdgeMode::Wrap, sumOfSines(N, {{0.3, 2, 1, 0.0}}));
    SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
    surface.run(field.buffer());
    const ShadowLight light = ShadowLight::of({0.05f, 0.02f}, 2.0f);
    TexelShadowPass pass;
    TexelShadows shadows;
    HeightBounds bounds(surface.textures().config());
    SurfaceRenderer renderer;
    const Mesh plane(makePlane());
    RenderTarget target(64, 64);
    target.bind();
    DirectionalLight sun;
    sun.direction = {0.3f, 0.8f, 0.2f};
    const SurfaceMaterial material{.depthScale = 0.1f};
    for (const int stride : {3, 64, -2}) {
        std::string m = messageOf([&] { pass.draw(surface.textures(), bounds, light, stride, shadows); });
        EXPECT_NE(m.find("stride"), std::string::npos) << m;
        EXPECT_NE(m.find("32x32"), std::string::npos) << m;
        m = messageOf([&] {
            renderer.draw(plane, glm::mat4(1.0f), surface.textures(), material, Camera{}, sun,
                          {.technique = Technique::Hierarchical, .texelShadows = TexelShadowChoice::On,
                           .texelStride = stride});
        });
        EXPECT_NE(m.find("DrawOptions::texelStride"), std::string::npos) << m;
        EXPECT_NE(m.find("32x32"), std::string::npos) << m;
    }
    EXPECT_EQ(shadows.texture(), 0u);
    // A good one draws a 16x16 target.
    pass.draw(surface.textures(), bounds, light, 2, shadows);
    ASSERT_NE(shadows.texture(), 0u);
    EXPECT_EQ(shadows.stride(), 2);
    GLint width = 0;
    glGetTextureLevelParameteriv(shadows.texture(), 0, GL_TEXTURE_WIDTH, &width);
    EXPECT_EQ(width, 16);

    // Every stride's texels are the stride-1 walks at their samples, whether the target fills the
    // pass's groups (16x16 lanes: texelshadows.comp's local_size) or is smaller than one: 32x32 is 2x2 groups,
    // 8x8 and 1x1 part of one. A low light, whose long shadows the comparison can see.
    const ShadowLight low = ShadowLight::of({0.6f, 0.25f}, 2.0f);
    auto texels = [](const TexelShadows& t, int size) {
        std::vector<float> v(size_t(size) * size, -1.0f);
        HFX_GL_CHECK(glGetTextureImage(t.texture(), 0, GL_RED, GL_FLOAT, GLsizei(v.size() * sizeof(float)), v.data()));
        return v;
    };
    TexelShadows full;
    pass.draw(surface.textures(), bounds, low, 1, full);
    const std::vector<float> every = texels(full, N);
    ASSERT_GT(*std::max_element(every.begin(), every.end()), 0.1f) << "the light must cast some shadow";
    for (const int stride : {4, 32}) {
        SCOPED_TRACE(stride);
        TexelShadows spaced;
        pass.draw(surface.textures(), bounds, low, stride, spaced);
        const int n = N / stride;
        const std::vector<float> some = texels(spaced, n);
        int differ = 0;
        for (int b = 0; b < n; ++b)
            for (int a = 0; a < n; ++a)
                differ += some[size_t(b) * n + a] != every[size_t(b * stride) * N + size_t(a * stride)];
        EXPECT_EQ(differ, 0) << "of " << n * n;
    }
}

TEST_F(Robustness, BadMaterialsCamerasLightsAndModelMatricesDrawNothing) {
    // Each makes a NaN or garbage the shaders would draw with: a material's field out of range, a
    // camera with no view direction, a light with none (normalised), a model matrix with a NaN or
    // a scale of 0 (the normals are turned by its inverse). Every draw, the planet's rings' too,
    // refuses them by name before it changes anything.
    SineWavesEffect water(cl(), {.waves = {.size = 64}});
    RenderTarget target(64, 64);
    target.bind();
    target.clear({0.25f, 0.5f, 0.75f, 1.0f});
    const Image before = target.readColor();
    SurfaceRenderer renderer;
    const Mesh plane(makePlane({}));
    const Camera camera = Camera::orbit({0, 0, 0}, 3.0f, 0.3f, 0.6f);
    for (const auto& [material, field] :
         {std::pair{SurfaceMaterial{.minSamples = 0}, "minSamples"}, std::pair{SurfaceMaterial{.maxSamples = 300}, "maxSamples"},
          std::pair{SurfaceMaterial{.depthScale = -0.01f}, "depthScale"},
          std::pair{SurfaceMaterial{.shadowSamples = 0}, "shadowSamples"},
          std::pair{SurfaceMaterial{.specularPower = std::nanf("")}, "specularPower"},
          std::pair{SurfaceMaterial{.silhouetteFade = 1.5f}, "silhouetteFade"},
          std::pair{SurfaceMaterial{.pixelBudget = -0.5f}, "pixelBudget"}}) {
        const std::string m =
            messageOf([&, &m = material] { renderer.draw(plane, glm::mat4(1.0f), water.textures(), m, camera, {}); });
        EXPECT_NE(m.find(field), std::string::npos) << m;
    }
    Camera noDirection = camera;
    noDirection.target = noDirection.position;
    const DirectionalLight light, dark{.direction = glm::vec3(0.0f)}, negative{.color = {1.0f, -0.1f, 1.0f}};
    glm::mat4 nanModel(1.0f), flattened(1.0f);
    nanModel[3][1] = std::nanf("");
    flattened[1][1] = 0.0f;
    const SurfaceMaterial material;
    PlanetRings rings; // composed over a copy of the frame, so a refused draw that went on would change it
    struct Case {
        const char* what;
        std::function<void()> draw;
        const char* expected;
    };
    const Case cases[] = {
        {"a camera on its target", [&] { renderer.draw(plane, glm::mat4(1.0f), water.textures(), material, noDirection, light); },
         "is its target: no view direction"},
        {"a light of no direction", [&] { renderer.draw(plane, glm::mat4(1.0f), water.textures(), material, camera, dark); },
         "DirectionalLight.direction must be finite and not zero, got (0, 0, 0)"},
        {"a negative light", [&] { renderer.draw(plane, glm::mat4(1.0f), water.textures(), material, camera, negative); },
         "DirectionalLight.color must be finite and not negative, got (1, -0.1, 1)"},
        {"a NaN model", [&] { renderer.draw(plane, nanModel, water.textures(), material, camera, light); },
         "the model matrix must be finite, got the columns (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, nan, 0, 1)"},
        {"a flattened model", [&] { renderer.draw(plane, flattened, water.textures(), material, camera, light); },
         "the model matrix scales some axis to 0"},
        {"a flat mesh, a flattened model", [&] { renderer.drawFlat(plane, flattened, camera, glm::vec4(1.0f), &light); },
         "the model matrix scales some axis to 0"},
        {"a flat mesh, a camera on its target", [&] { renderer.drawFlat(plane, glm::mat4(1.0f), noDirection, glm::vec4(1.0f)); },
         "is its target: no view direction"},
        {"the sky, a light of no direction", [&] { renderer.drawSky(camera, dark, WaterLook{}); }, "DirectionalLight.direction"},
        {"the rings, a camera on its target", [&] { rings.draw(glm::mat4(1.0f), noDirection, light); },
         "is its target: no view direction"},
        {"the rings, a negative light", [&] { rings.draw(glm::mat4(1.0f), camera, negative); },
         "DirectionalLight.color must be finite and not negative"},
        {"the rings, a NaN model", [&] { rings.draw(nanModel, camera, light); }, "the model matrix must be finite"},
        {"the rings, a flattened model", [&] { rings.draw(flattened, camera, light); },
         "the model matrix scales some axis to 0"},
    };
    for (const Case& c : cases) {
        const std::string m = messageOf(c.draw);
        EXPECT_NE(m.find(c.expected), std::string::npos) << c.what << ": " << m;
    }
    EXPECT_EQ(target.readColor().pixels, before.pixels) << "a refused draw left pixels behind";
}

TEST_F(Robustness, ImpactBatchesAreAllOrNoneAndBudgetsMustFitTheStampBatch) {
    // Every impact's stamps are rebuilt each frame: a budget whose explosions could overflow the
    // stamp batch is refused up front, naming both.
    const std::string tooBig =
        messageOf([&] { DecalWallEffect(cl(), {.bricks = {.size = 64}, .damage = {.budget = 256}, .maxStampsPerBatch = 1000}); });
    EXPECT_NE(tooBig.find("1000"), std::string::npos) << tooBig;
    EXPECT_NE(tooBig.find("budget"), std::string::npos) << tooBig;

    DecalWallEffect wall(cl(), {.bricks = {.size = 64}, .damage = {.budget = 16}});
    std::vector<ImpactEvent> storm(40);
    for (size_t i = 0; i < storm.size(); ++i) storm[i] = {.u = float(i) / 40.0f, .v = 0.5f, .radius = 0.02f};
    storm.back().u = 1.5f;
    const std::string m = messageOf([&] { wall.impacts(storm); });
    EXPECT_NE(m.find("outside the map"), std::string::npos) << m;
    EXPECT_EQ(wall.damage().size(), 0) << "a refused batch added nothing";
    storm.pop_back();
    wall.impacts(storm);
    EXPECT_EQ(wall.damage().size(), 16) << "the budget holds the newest 16";
    EXPECT_NE(messageOf([&] { wall.shoot(std::numeric_limits<double>::infinity(), 0.5); }).find("finite"),
              std::string::npos);
}

#if defined(HFX_WITH_OPENIMAGEIO) // 16-bit TIFF: written and read by OpenImageIO
TEST_F(Robustness, MapsOfEveryFormatLoadAndNonSquareSizesKeepTheirShape) {
    // A 16-bit, two-channel, non-square, non-power-of-two height map: the first channel is h.
    constexpr int W = 48, H = 30;
    Image map{W, H, 2, std::vector<float>(W * H * 2)};
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            map.at(x, y, 0) = float(x) / W;
            map.at(x, y, 1) = 1.0f;
        }
    const std::string path = outputPath("robust_height16.tif");
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(W, H, 2, OIIO::TypeDesc::UINT16);
    ASSERT_TRUE(out->open(path, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, map.pixels.data()));
    out->close();
    ImageSurface surface(cl(), {.maps = readSurfaceMaps(path, "", ""), .edges = EdgeMode::Clamp});
    EXPECT_EQ(surface.textures().config().width, W);
    EXPECT_EQ(surface.textures().config().height, H);
    const std::vector<float> texels = readSurface(surface.textures());
    EXPECT_NEAR(texels[(5 * W + 24) * 4 + 3], 24.0f / W, 1.0f / 65535.0f + 1e-6f);
}
#endif

TEST_F(Robustness, ZeroSizedAndEmptyFilesAreRefusedByName) {
    // A PNG whose header claims 0 x 0 pixels.
    const std::string zero = outputPath("robust_zero.png");
    {
        std::ofstream f(zero, std::ios::binary);
        const unsigned char png[] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                     0,    0,   0,   0,   0,    0,    0,    0,    8, 0, 0, 0,  0,   0x1e, 0xe0, 0x23, 0xce};
        f.write(reinterpret_cast<const char*>(png), sizeof png);
    }
    const std::string empty = outputPath("robust_empty.exr");
    std::ofstream(empty, std::ios::binary).close();
    for (const std::string& path : {zero, empty}) {
        const std::string m = messageOf([&] { ImageSurface(cl(), {.maps = readSurfaceMaps(path, "", "")}); });
        EXPECT_NE(m.find(path), std::string::npos) << m;
        EXPECT_EQ(m.find("(no error)"), std::string::npos);
    }
}

TEST_F(Robustness, KernelThatFailsToBuildFromAnOverrideNamesTheLogAndLine) {
    const std::string dir = outputPath("robust_kernels");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/colorize.cl") << "__kernel void colorize(__global float* x) {\n  x[0] = undefined_name;\n}\n";
    setenv("HFX_KERNEL_DIR", dir.c_str(), 1);
    std::string m;
    {
        ClContext fresh;
        m = messageOf([&] { ColorRamp(fresh, 4, 4, gasGiantPalette()); });
    }
    unsetenv("HFX_KERNEL_DIR");
    EXPECT_NE(m.find("colorize"), std::string::npos) << m;
    EXPECT_NE(m.find("undefined_name"), std::string::npos) << "the build log is missing: " << m;
}

} // namespace
} // namespace hfx::test
