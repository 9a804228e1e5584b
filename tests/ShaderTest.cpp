#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/ShaderProgram.h"

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

} // namespace
} // namespace hfx::test
