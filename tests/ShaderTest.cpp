#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/GlObject.h"
#include "hfx/core/ShaderProgram.h"

#include <map>
#include <vector>

namespace hfx::test {
namespace {

class Shader : public GlTest {};

const SourceFile vertex{"ok.vert", "#version 450 core\nvoid main() { gl_Position = vec4(0); }\n",
                        "test"};

TEST_F(Shader, CompileErrorNamesFileAndLine) {
    const SourceFile broken{"broken.frag",
                            "#version 450 core\nout vec4 o;\n\nvoid main() {\n    o = undefinedThing;\n}\n",
                            "test"};
    try {
        ShaderProgram program(vertex, broken, {{"SOME_VARIANT", "1"}});
        FAIL() << "a broken shader compiled";
    } catch (const Error& e) {
        const std::string message = e.what();
        // Line 5 of the file, even though a #define was prepended.
        EXPECT_NE(message.find("broken.frag:5:"), std::string::npos) << message;
        EXPECT_NE(message.find("undefinedThing"), std::string::npos) << message;
    }
}

TEST_F(Shader, ComposedStagesNameTheFileAndLineOfAnError) {
    // Three files: a declaration, a broken helper on its line 3, the main with the #version
    // line last in the list (it still goes first in the composed text).
    const SourceFile decl{"decl.glsl", "// declarations\nfloat helperValue();\n", "test"};
    const SourceFile helper{"helper.glsl", "// a helper\nfloat helperValue() {\n    return missingName;\n}\n", "test"};
    const SourceFile main{"main.frag", "#version 450 core\nout vec4 o;\nvoid main() { o = vec4(helperValue()); }\n",
                          "test"};
    const std::string m = messageOf([&] { ShaderProgram({vertex}, {decl, helper, main}, {{"V", "1"}}); });
    EXPECT_NE(m.find("helper.glsl:3:"), std::string::npos) << m;
    EXPECT_NE(m.find("missingName"), std::string::npos) << m;
    // Fixed, the same composition builds; two #version lines are refused by name.
    const SourceFile fixed{"helper.glsl", "float helperValue() { return 1.0; }\n", "test"};
    EXPECT_EQ(messageOf([&] { ShaderProgram({vertex}, {decl, fixed, main}); }), "(no error)");
    const SourceFile second{"second.frag", "#version 450 core\n", "test"};
    EXPECT_NE(messageOf([&] { ShaderProgram({vertex}, {second, main}); }).find("second.frag"), std::string::npos);
}

/// A file table for the include tests: the loader throws for a name it lacks, as surfaceShader does.
SourceLoader tableOf(std::map<std::string, std::string> files) {
    return [files = std::move(files)](std::string_view name) {
        const auto it = files.find(std::string(name));
        if (it == files.end()) throw Error(str("no source named '", name, "'"));
        return SourceFile{it->first, it->second, "test"};
    };
}

TEST_F(Shader, IncludesComposeAStageAndAnErrorNamesTheIncludedFileAndLine) {
    // main.frag includes a declaration, a slot (the caller's helper) and the declaration again
    // (added once); the helper is broken on its line 3, main's own code after the includes.
    const SourceLoader load = tableOf({{"decl.glsl", "// declarations\nfloat helperValue();\n"},
                                       {"good.glsl", "float helperValue() { return 1.0; }\n"},
                                       {"bad.glsl", "// a helper\nfloat helperValue() {\n    return missingName;\n}\n"},
                                       {"main.frag", "#version 450 core\n#include \"decl.glsl\"\n#include <helper> // the caller's\n"
                                                     "  #  include \"decl.glsl\"\nout vec4 o;\nvoid main() { o = vec4(helperValue()); }\n"}});
    const std::vector<SourceFile> parts = expandIncludes(load("main.frag"), load, {{"helper", "good.glsl"}});
    ASSERT_EQ(parts.size(), 4u); // main's line 1, decl, good, main from line 5
    EXPECT_EQ(parts[1].name, "decl.glsl");
    EXPECT_EQ(parts[2].name, "good.glsl");
    EXPECT_EQ(parts[3].name, "main.frag");
    EXPECT_EQ(parts[3].firstLine, 5);
    EXPECT_EQ(messageOf([&] { ShaderProgram({vertex}, parts); }), "(no error)");
    const std::string m = messageOf([&] { ShaderProgram({vertex}, expandIncludes(load("main.frag"), load, {{"helper", "bad.glsl"}})); });
    EXPECT_NE(m.find("bad.glsl:3:"), std::string::npos) << m;
    EXPECT_NE(m.find("missingName"), std::string::npos) << m;
    // An error in the top file after its includes keeps the file's own line numbers.
    const SourceLoader late = tableOf({{"decl.glsl", "float helperValue() { return 1.0; }\n"},
                                       {"late.frag", "#version 450 core\n#include \"decl.glsl\"\nout vec4 o;\n"
                                                     "void main() { o = vec4(unknownToo); }\n"}});
    const std::string l = messageOf([&] { ShaderProgram({vertex}, expandIncludes(late("late.frag"), late)); });
    EXPECT_NE(l.find("late.frag:4:"), std::string::npos) << l;
}

TEST_F(Shader, AnIncludeCycleAMissingSlotOrAMalformedLineIsRefusedByFileAndLine) {
    const SourceLoader load = tableOf({{"a.glsl", "// a\n#include \"b.glsl\"\n"},
                                       {"b.glsl", "#include \"a.glsl\"\n"},
                                       {"slot.frag", "#version 450 core\n\n#include <tracer>\n"},
                                       {"odd.frag", "#version 450 core\n#include tracer.glsl\n"},
                                       {"gone.frag", "#version 450 core\n#include \"nowhere.glsl\"\n"}});
    const std::string cycle = messageOf([&] { expandIncludes(load("a.glsl"), load); });
    EXPECT_NE(cycle.find("b.glsl:1: #include cycle: a.glsl -> b.glsl -> a.glsl"), std::string::npos) << cycle;
    const std::string slot = messageOf([&] { expandIncludes(load("slot.frag"), load, {{"shading", "x.glsl"}}); });
    EXPECT_NE(slot.find("slot.frag:3: #include <tracer>"), std::string::npos) << slot;
    const std::string odd = messageOf([&] { expandIncludes(load("odd.frag"), load); });
    EXPECT_NE(odd.find("odd.frag:2: malformed #include 'tracer.glsl'"), std::string::npos) << odd;
    EXPECT_NE(messageOf([&] { expandIncludes(load("gone.frag"), load); }).find("nowhere.glsl"), std::string::npos);
}

TEST_F(Shader, LinkErrorCarriesTheLog) {
    const SourceFile noMain{"nomain.frag", "#version 450 core\nout vec4 o;\nvoid notMain() {}\n", "test"};
    EXPECT_THROW(ShaderProgram(vertex, noMain), Error);
}

TEST_F(Shader, MissingVersionLineIsRefused) {
    const SourceFile noVersion{"noversion.frag", "void main() {}\n", "test"};
    try {
        ShaderProgram program(vertex, noVersion);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("noversion.frag"), std::string::npos);
    }
}

TEST_F(Shader, DispatchOverCoversAGridWithTheProgramsOwnGroups) {
    // Groups of 8x4 lanes over a 13x7 grid: 2x2 groups, 128 lanes, each texel of the grid written
    // once by the lane at it (the lanes past its edges count and store nothing).
    const SourceFile grid{"grid.comp", R"(#version 450 core
layout(local_size_x = 8, local_size_y = 4) in;
layout(binding = 0, r32f) uniform writeonly image2D i_grid;
layout(std430, binding = 0) buffer Lanes { uint lanes; };
uniform ivec2 u_size;
void main() {
    atomicAdd(lanes, 1u);
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(p, u_size))) imageStore(i_grid, p, vec4(float(p.y * u_size.x + p.x + 1)));
}
)",
                          "test"};
    const ShaderProgram program = ShaderProgram::compute({grid});
    constexpr int width = 13, height = 7;
    GlTexture image = GlTexture::create();
    glTextureStorage2D(image.id(), 1, GL_R32F, 16, 8); // a texel past the grid on each axis stays 0
    const std::vector<float> zeros(16 * 8, 0.0f);
    glTextureSubImage2D(image.id(), 0, 0, 0, 16, 8, GL_RED, GL_FLOAT, zeros.data());
    GlBuffer lanes = GlBuffer::create();
    const GLuint none = 0;
    glNamedBufferStorage(lanes.id(), sizeof none, &none, GL_DYNAMIC_STORAGE_BIT);
    glBindImageTexture(0, image.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, lanes.id());
    program.use();
    program.set("u_size", glm::ivec2(width, height));
    program.dispatchOver(width, height);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glUseProgram(0);
    GLuint count = 0;
    glGetNamedBufferSubData(lanes.id(), 0, sizeof count, &count);
    EXPECT_EQ(count, 128u);
    std::vector<float> texels(16 * 8, -1.0f);
    glGetTextureImage(image.id(), 0, GL_RED, GL_FLOAT, GLsizei(texels.size() * sizeof(float)), texels.data());
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x)
            EXPECT_EQ(texels[size_t(y) * 16 + x], x < width && y < height ? float(y * width + x + 1) : 0.0f)
                << x << ", " << y;

    // A drawing program has no groups: refused by name, and no GL error left behind for the next call.
    const SourceFile fragment{"ok.frag", "#version 450 core\nout vec4 o;\nvoid main() { o = vec4(1); }\n", "test"};
    const ShaderProgram draw(vertex, fragment);
    const std::string m = messageOf([&] { draw.dispatchOver(4, 4); });
    EXPECT_NE(m.find("not a linked compute program"), std::string::npos) << m;
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

} // namespace
} // namespace hfx::test
