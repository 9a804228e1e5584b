// Without a usable GL context the loader says so, and what to install, instead of crashing on
// the first GL call. (A process of its own: the core tests make no context.)

#include "hfx/core/Error.h"
#include "hfx/core/GlLoader.h"

#include <gtest/gtest.h>

namespace hfx {
namespace {

GlProc nothing(const char*) { return nullptr; }

TEST(GlLoader, NoContextIsAClearError) {
    try {
        loadGl(&nothing);
        FAIL() << "loading GL without a context succeeded";
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("OpenGL"), std::string::npos) << m;
        EXPECT_NE(m.find("install"), std::string::npos) << m;
    }
}

} // namespace
} // namespace hfx
