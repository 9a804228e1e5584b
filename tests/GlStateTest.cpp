// What a draw does with the caller's GL state (hfx::GlStatePolicy): under Restore it reads what it
// will change and puts it back; under Defaults it reads none of it and leaves GL's defaults, for
// an engine that binds its own state before each draw, where every query of the state waits for
// a threaded driver. The same frame either way.

#include "support/Fields.h"
#include "support/Fixtures.h"
#include "support/References.h"

#include "hfx/core/Bindings.h"
#include "hfx/core/Gl.h"
#include "hfx/core/GlObject.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/GlStatePolicy.h"
#include "hfx/effects/PlanetRings.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace hfx::test {
namespace {

/// Counts the GL state queries made while it lives: every glGet* and glIs* entry point HFX's
/// draws call, wrapped through glad's pointers (not glGetError, which HFX polls only in a
/// HFX_GL_DEBUG build).
int gQueries = 0;
#define HFX_COUNTED(name, ret, params, args)                                                       \
    decltype(glad_##name) real_##name = nullptr;                                                   \
    ret GLAD_API_PTR counted_##name params {                                                       \
        ++gQueries;                                                                                \
        return real_##name args;                                                                   \
    }
HFX_COUNTED(glGetIntegerv, void, (GLenum a, GLint* b), (a, b))
HFX_COUNTED(glGetIntegeri_v, void, (GLenum a, GLuint i, GLint* b), (a, i, b))
HFX_COUNTED(glGetInteger64i_v, void, (GLenum a, GLuint i, GLint64* b), (a, i, b))
HFX_COUNTED(glGetBooleanv, void, (GLenum a, GLboolean* b), (a, b))
HFX_COUNTED(glGetBooleani_v, void, (GLenum a, GLuint i, GLboolean* b), (a, i, b))
HFX_COUNTED(glGetFloatv, void, (GLenum a, GLfloat* b), (a, b))
HFX_COUNTED(glGetDoublev, void, (GLenum a, GLdouble* b), (a, b))
HFX_COUNTED(glIsEnabled, GLboolean, (GLenum a), (a))
HFX_COUNTED(glIsProgram, GLboolean, (GLuint a), (a))
HFX_COUNTED(glIsTexture, GLboolean, (GLuint a), (a))
HFX_COUNTED(glGetNamedFramebufferAttachmentParameteriv, void, (GLuint f, GLenum a, GLenum p, GLint* v), (f, a, p, v))
HFX_COUNTED(glGetTextureLevelParameteriv, void, (GLuint t, GLint l, GLenum p, GLint* v), (t, l, p, v))
HFX_COUNTED(glGetTextureParameteriv, void, (GLuint t, GLenum p, GLint* v), (t, p, v))
#undef HFX_COUNTED

class CountedQueries {
public:
    CountedQueries() {
        gQueries = 0;
        swap();
    }
    ~CountedQueries() { swap(); }
    int count() const { return gQueries; }

private:
    static void swap() {
#define HFX_SWAP(name)                                                                             \
    if (!real_##name) real_##name = glad_##name;                                                   \
    glad_##name = glad_##name == counted_##name ? real_##name : counted_##name
        HFX_SWAP(glGetIntegerv);
        HFX_SWAP(glGetIntegeri_v);
        HFX_SWAP(glGetInteger64i_v);
        HFX_SWAP(glGetBooleanv);
        HFX_SWAP(glGetBooleani_v);
        HFX_SWAP(glGetFloatv);
        HFX_SWAP(glGetDoublev);
        HFX_SWAP(glIsEnabled);
        HFX_SWAP(glIsProgram);
        HFX_SWAP(glIsTexture);
        HFX_SWAP(glGetNamedFramebufferAttachmentParameteriv);
        HFX_SWAP(glGetTextureLevelParameteriv);
        HFX_SWAP(glGetTextureParameteriv);
#undef HFX_SWAP
    }
};

/// Sets the policy for its scope, and Restore (the default) after.
struct Policy {
    explicit Policy(GlStatePolicy p) { setGlStatePolicy(p); }
    ~Policy() { setGlStatePolicy(GlStatePolicy::Restore); }
};

/// State a caller might leave bound, none of it GL's default, on what a draw changes.
struct CallersState {
    CallersState() : texture(GlTexture::create()), vao(GlVertexArray::create()), block(GlBuffer::create()) {
        glTextureStorage2D(texture.id(), 1, GL_RGBA8, 4, 4);
        glNamedBufferStorage(block.id(), 256, nullptr, 0);
    }
    void bind() const {
        glBindTextureUnit(5, texture.id());
        glBindTextureUnit(HFX_UNIT_RING_SHINE, texture.id());
        glActiveTexture(GL_TEXTURE7);
        glBindVertexArray(vao.id());
        glBindBufferBase(GL_UNIFORM_BUFFER, HFX_BLOCK_RINGS, block.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, HFX_BUFFER_TRACE_INFO, block.id());
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT);
        glFrontFace(GL_CW);
        glDisable(GL_DEPTH_TEST);
        glDepthFunc(GL_ALWAYS);
        glEnable(GL_PROGRAM_POINT_SIZE);
    }
    GlTexture texture;
    GlVertexArray vao;
    GlBuffer block;
};

/// Where the bindings a draw changes differ from GL's defaults, by name (empty: none).
std::string notDefault() {
    std::string found;
    auto check = [&](bool fine, const std::string& what) {
        if (!fine) found += (found.empty() ? "" : ", ") + what;
    };
    GLint value = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &value);
    check(value == 0, "program");
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &value);
    check(value == 0, "vertex array");
    glGetIntegerv(GL_ACTIVE_TEXTURE, &value);
    check(value == GL_TEXTURE0, "active texture");
    for (int unit = 0; unit < HFX_TEXTURE_UNITS; ++unit) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &value);
        check(value == 0, "texture unit " + std::to_string(unit));
        glGetIntegerv(GL_SAMPLER_BINDING, &value);
        check(value == 0, "sampler " + std::to_string(unit));
    }
    glActiveTexture(GL_TEXTURE0);
    for (GLuint image = 0; image < HFX_IMAGE_UNITS; ++image) {
        glGetIntegeri_v(GL_IMAGE_BINDING_NAME, image, &value);
        check(value == 0, "image unit " + std::to_string(image));
    }
    for (GLuint block = 0; block <= HFX_BLOCK_SHADOWS; ++block) {
        glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, block, &value);
        check(value == 0, "uniform block " + std::to_string(block));
    }
    for (GLuint buffer = 0; buffer <= HFX_BUFFER_TRACE_LIGHTS; ++buffer) {
        glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, buffer, &value);
        check(value == 0, "storage buffer " + std::to_string(buffer));
    }
    check(!glIsEnabled(GL_DEPTH_TEST), "depth test");
    glGetIntegerv(GL_DEPTH_FUNC, &value);
    check(value == GL_LESS, "depth function");
    GLboolean mask = GL_FALSE, masks[4] = {};
    glGetBooleanv(GL_DEPTH_WRITEMASK, &mask);
    check(mask == GL_TRUE, "depth mask");
    for (GLuint buffer = 0; buffer < 8; ++buffer) {
        glGetBooleani_v(GL_COLOR_WRITEMASK, buffer, masks);
        check(masks[0] && masks[1] && masks[2] && masks[3], "colour mask " + std::to_string(buffer));
    }
    check(!glIsEnabled(GL_CULL_FACE), "face culling");
    glGetIntegerv(GL_CULL_FACE_MODE, &value);
    check(value == GL_BACK, "cull face");
    glGetIntegerv(GL_FRONT_FACE, &value);
    check(value == GL_CCW, "front face");
    check(!glIsEnabled(GL_PROGRAM_POINT_SIZE), "program point size");
    glGetIntegerv(GL_DRAW_INDIRECT_BUFFER_BINDING, &value);
    check(value == 0, "draw indirect buffer");
    glGetIntegerv(GL_DISPATCH_INDIRECT_BUFFER_BINDING, &value);
    check(value == 0, "dispatch indirect buffer");
    return found;
}

class GlState : public GlTest {};

TEST_F(GlState, UnderDefaultsADrawAsksNothingAndLeavesGlsDefaults) {
    // A relief lit and shadowed, its sky behind it, drawn with each kind of technique: under
    // Restore a draw reads about 120 values of the state it changes, and puts them back; under
    // Defaults, with the colour output set (ColorOutput::Auto reads the target's format), normal
    // mapping, POM and the sky read none, and hier only the viewport its passes cover (1 on
    // llvmpipe; 6 while the beam start was a fragment pass that put back the framebuffer, the
    // viewport, blending, the scissor test and colour buffer 0's mask); in the compute pass, also
    // whether the target can take it (the stencil test, multisampling: 3; 17 when its rays draw
    // asked for the masks it sets aside, which under Defaults it knows); at most 4 and 6, a
    // device's own passes aside, against about 120 restoring. After each draw the bindings
    // it changes hold GL's defaults, whatever the caller had bound, and the frame is the same as
    // under Restore. A planet's rings read the frame they compose over (its framebuffers,
    // viewport, read and draw buffers, multisampling) and leave GL's defaults too.
    constexpr int field = 64, W = 160, H = 96;
    constexpr float depthScale = 0.12f;
    SurfaceTextures textures({.width = field, .height = field, .mipmaps = false, .normalDepth = depthScale});
    const std::vector<float> texels =
        sobelReference(sumOfSines(field, {{0.3, 2, 1, 0.0}, {0.15, -1, 2, 0.7}}), field, depthScale);
    textures.uploadTexels(texels.data());
    textures.setAlbedo(Image{1, 1, 3, {0.6f, 0.5f, 0.4f}});
    const Mesh plane(makePlane({.size = 2.0f}));
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.6f, 0.55f, 0.6f);
    camera.aspect = float(W) / float(H);
    const DirectionalLight light{.direction = {0.5f, 0.6f, 0.3f}};
    const SurfaceMaterial material{.depthScale = depthScale, .lodThreshold = 100.0f};
    RenderTarget target(W, H);
    SurfaceRenderer renderer;
    renderer.setColorOutput(ColorOutput::Display);
    const CallersState callers;
    struct Case {
        const char* name;
        DrawOptions options;
        int most; ///< queries at most under Defaults
    };
    const Case cases[] = {
        {"normal mapping", {.technique = Technique::NormalMapping}, 0},
        {"pom", {.technique = Technique::ParallaxOcclusion}, 0},
        {"hier, texel shadows", {.technique = Technique::Hierarchical, .texelShadows = TexelShadowChoice::On,
                                 .tracePass = TracePass::InDraw}, 4},
        {"hier, compute pass", {.technique = Technique::Hierarchical, .tracePass = TracePass::Compute}, 6},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        // Each policy twice, the texels new before the first (as a dynamic field's are each
        // frame): the first draw builds what the surface keeps (its bounds, its texel shadows, in
        // passes inside the draw, whose own guards put back what the draw had bound); the second's
        // queries are counted.
        auto frame = [&](GlStatePolicy policy, int& queries, int& sky) {
            const Policy scoped(policy);
            textures.uploadTexels(texels.data());
            std::vector<Image> images;
            for (int round = 0; round < 2; ++round) {
                target.bind();
                target.clear();
                callers.bind();
                {
                    const CountedQueries counted;
                    renderer.drawSky(camera, light, WaterLook{});
                    sky = counted.count();
                }
                callers.bind();
                const CountedQueries counted;
                renderer.draw(plane, glm::mat4(1.0f), textures, material, camera, light, c.options);
                queries = counted.count();
                images.push_back(target.readColor());
            }
            return images;
        };
        int restoring = 0, restoringSky = 0, defaults = 0, defaultsSky = 0;
        const std::vector<Image> restored = frame(GlStatePolicy::Restore, restoring, restoringSky);
        const std::vector<Image> left = frame(GlStatePolicy::Defaults, defaults, defaultsSky);
        const std::string found = notDefault();
        double worst = 0.0;
        for (size_t round = 0; round < left.size(); ++round)
            for (size_t i = 0; i < left[round].pixels.size(); ++i)
                worst = std::max(worst, double(std::abs(left[round].pixels[i] - restored[round].pixels[i])));
        std::printf("[gl state] %s: %d queries a draw restoring (the sky %d), %d under Defaults (the sky %d); frames "
                    "differ by %.4f at most\n",
                    c.name, restoring, restoringSky, defaults, defaultsSky, worst);
        EXPECT_GT(restoring, 100) << "the count is not what a restoring draw reads";
        EXPECT_LE(defaults, c.most);
        EXPECT_EQ(defaultsSky, 0);
        EXPECT_EQ(found, "") << "not GL's defaults after the draw";
        EXPECT_LE(worst, 1.0 / 255.0) << "the frame changed with the policy";
    }

    PlanetRings rings;
    rings.setColorOutput(ColorOutput::Display);
    const glm::mat4 model = glm::translate(glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)), glm::vec3(0.0f, 0.4f, 0.0f));
    const Policy scoped(GlStatePolicy::Defaults);
    target.bind();
    callers.bind();
    const CountedQueries counted;
    rings.draw(model, camera, light);
    std::printf("[gl state] rings: %d queries under Defaults\n", counted.count());
    EXPECT_LE(counted.count(), 7);
    EXPECT_EQ(notDefault(), "") << "not GL's defaults after the rings";
}

TEST_F(GlState, UnderRestoreADrawPutsBackWhatTheCallerHadBound) {
    // The default policy's promise, the other side of the test above: the caller's bindings on
    // what a draw changes come back after it, for each kind of technique.
    constexpr int field = 32;
    SurfaceTextures textures({.width = field, .height = field, .mipmaps = false, .normalDepth = 0.1f});
    textures.uploadTexels(sobelReference(sumOfSines(field, {{0.3, 2, 1, 0.0}}), field, 0.1f).data());
    const Mesh plane(makePlane({.size = 2.0f}));
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.6f, 0.55f, 0.6f);
    RenderTarget target(96, 64);
    SurfaceRenderer renderer;
    const CallersState callers;
    for (const Technique technique : {Technique::NormalMapping, Technique::ParallaxOcclusion, Technique::Hierarchical}) {
        SCOPED_TRACE(techniqueInfo(technique).name);
        target.bind();
        callers.bind();
        renderer.draw(plane, glm::mat4(1.0f), textures, {.depthScale = 0.1f}, camera, DirectionalLight{},
                      {.technique = technique});
        GLint value = 0;
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &value);
        EXPECT_EQ(GLuint(value), callers.vao.id());
        glGetIntegerv(GL_ACTIVE_TEXTURE, &value);
        EXPECT_EQ(value, GL_TEXTURE7);
        glActiveTexture(GL_TEXTURE5);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &value);
        EXPECT_EQ(GLuint(value), callers.texture.id());
        glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, HFX_BLOCK_RINGS, &value);
        EXPECT_EQ(GLuint(value), callers.block.id());
        glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, HFX_BUFFER_TRACE_INFO, &value);
        EXPECT_EQ(GLuint(value), callers.block.id());
        glGetIntegerv(GL_CULL_FACE_MODE, &value);
        EXPECT_EQ(value, GL_FRONT);
        glGetIntegerv(GL_FRONT_FACE, &value);
        EXPECT_EQ(value, GL_CW);
        glGetIntegerv(GL_DEPTH_FUNC, &value);
        EXPECT_EQ(value, GL_ALWAYS);
        EXPECT_TRUE(glIsEnabled(GL_CULL_FACE));
        EXPECT_FALSE(glIsEnabled(GL_DEPTH_TEST));
        EXPECT_TRUE(glIsEnabled(GL_PROGRAM_POINT_SIZE));
        glActiveTexture(GL_TEXTURE0);
    }
}

} // namespace
} // namespace hfx::test
