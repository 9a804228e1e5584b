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
