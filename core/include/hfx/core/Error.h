#pragma once
// Errors: a failure of the environment or of input (missing file, no OpenCL platform, a shader
// or kernel that does not build, a bad parameter) throws hfx::Error carrying the whole story.
// A programmer's contract violation is HFX_CHECK: always on, prints the values, aborts.
//
// Thread: any. Every HFX failure is an hfx::Error carrying its message.

#include <locale>
#include <sstream>
#include <stdexcept>
#include <string>

namespace hfx {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

namespace detail {
[[noreturn]] void checkFailed(const char* file, int line, const char* expr, const std::string& values);
/// `file` (a __FILE__) as a path from the source tree's root ("effects/src/SurfaceRenderer.cpp"),
/// however the compiler was handed it: absolute, or relative to the object's folder as ccache's
/// CCACHE_BASEDIR makes it ("../../effects/src/SurfaceRenderer.cpp"). A path outside the tree is
/// returned as it is.
const char* sourceName(const char* file);

template <typename A, typename B>
std::string describe(const char* op, const A& a, const B& b) {
    std::ostringstream s;
    s.imbue(std::locale::classic());
    s << a << ' ' << op << ' ' << b;
    return s.str();
}
} // namespace detail

/// `config` after its validate() (which throws hfx::Error naming the bad field): for member
/// initialiser lists that must refuse a configuration before anything is made from it.
template <typename Config>
const Config& validated(const Config& config) {
    config.validate();
    return config;
}

/// Concatenates its arguments with operator<<, for error messages (and the kernels' build
/// options): in the classic locale, whatever the program's global one, so a number reads the
/// same to a compiler and in a log ("1234.5", never "1.234,5").
template <typename... Args>
std::string str(const Args&... args) {
    std::ostringstream s;
    s.imbue(std::locale::classic());
    (s << ... << args);
    return s.str();
}

} // namespace hfx

#define HFX_CHECK(cond)                                                                            \
    do {                                                                                           \
        if (!(cond)) ::hfx::detail::checkFailed(__FILE__, __LINE__, #cond, {});                    \
    } while (0)

#define HFX_CHECK_OP(a, op, b)                                                                     \
    do {                                                                                           \
        const auto& hfxA_ = (a);                                                                   \
        const auto& hfxB_ = (b);                                                                   \
        if (!(hfxA_ op hfxB_))                                                                     \
            ::hfx::detail::checkFailed(__FILE__, __LINE__, #a " " #op " " #b,                      \
                                       ::hfx::detail::describe(#op, hfxA_, hfxB_));                \
    } while (0)

#define HFX_CHECK_EQ(a, b) HFX_CHECK_OP(a, ==, b)
