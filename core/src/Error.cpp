#include "hfx/core/Error.h"

#include <cstdio>
#include <cstdlib>

namespace hfx::detail {

void checkFailed(const char* file, int line, const char* expr, const std::string& values) {
    std::fprintf(stderr, "%s:%d: HFX_CHECK failed: %s%s%s\n", file, line, expr,
                 values.empty() ? "" : " with ", values.c_str());
    std::abort();
}

} // namespace hfx::detail
