// Always-on contract checks and the debug build's GL error polling: both name what failed.
// This file turns HFX_GL_CHECK on for itself, whatever the library was built with.
#ifndef HFX_GL_DEBUG
#define HFX_GL_DEBUG 1
#endif

#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/GlFence.h"

namespace hfx::test {
namespace {

class GlCheck : public GlTest {};

TEST_F(GlCheck, AFailingCallIsAnErrorNamingTheCallAndWhereItStands) {
    // Binding a name that glGenTextures never made is GL_INVALID_OPERATION in a core context.
    const std::string m = messageOf([] { HFX_GL_CHECK(glBindTexture(GL_TEXTURE_2D, 987654)); });
    EXPECT_NE(m.find("GL_INVALID_OPERATION"), std::string::npos) << m;
    EXPECT_NE(m.find("glBindTexture(GL_TEXTURE_2D, 987654)"), std::string::npos) << m;
    // The file from the tree's root, however the compiler was handed it (ccache hands it
    // relative to the object's folder).
    EXPECT_NE(m.find(" at tests/GlCheckTest.cpp:"), std::string::npos) << m;
    // A good call passes, and the failed one left no error behind for the next check.
    EXPECT_EQ(messageOf([] { HFX_GL_CHECK(glBindTexture(GL_TEXTURE_2D, 0)); }), "(no error)");
}

TEST_F(GlCheck, AFenceIsDoneOnceGlHasRunWhatCameBeforeItAndAnEmptyOneNever) {
    GlFence none;
    EXPECT_FALSE(none);
    EXPECT_FALSE(none.done());
    GlFence fence = GlFence::insert();
    ASSERT_TRUE(fence);
    glFinish(); // everything before it has run
    EXPECT_TRUE(fence.done());
    EXPECT_TRUE(fence.done()) << "asked again";
    none = std::move(fence); // the fence moves, its owner empties
    EXPECT_TRUE(none.done());
    EXPECT_FALSE(fence.done()); // NOLINT(bugprone-use-after-move): moved-from is empty
}

TEST(Check, AViolatedContractAbortsPrintingBothValues) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const int two = 2;
    EXPECT_DEATH(HFX_CHECK_EQ(two + 1, 4), "HFX_CHECK failed: two \\+ 1 == 4.*3 == 4");
    EXPECT_DEATH(HFX_CHECK(two > 5), "tests/GlCheckTest.cpp:[0-9]+: HFX_CHECK failed: two > 5");
}

TEST(Check, SourceFilesAreNamedFromTheTreesRoot) {
    EXPECT_STREQ(detail::sourceName("../../effects/src/SurfaceRenderer.cpp"), "effects/src/SurfaceRenderer.cpp");
    EXPECT_STREQ(detail::sourceName("./core/src/Mesh.cpp"), "core/src/Mesh.cpp");
    EXPECT_STREQ(detail::sourceName(HFX_SOURCE_DIR "/core/src/Mesh.cpp"), "core/src/Mesh.cpp");
    EXPECT_STREQ(detail::sourceName("/elsewhere/engine/Render.cpp"), "/elsewhere/engine/Render.cpp");
    EXPECT_STREQ(detail::sourceName("Render.cpp"), "Render.cpp");
    EXPECT_STREQ(detail::sourceName(__FILE__), "tests/GlCheckTest.cpp") << __FILE__;
}

} // namespace
} // namespace hfx::test
