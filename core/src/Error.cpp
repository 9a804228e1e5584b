#include "hfx/core/Error.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace hfx::detail {

const char* sourceName(const char* file) {
    // HFX_SOURCE_ROOT: the tree's root with a trailing slash (core/CMakeLists.txt, this file only).
    static constexpr const char* root = HFX_SOURCE_ROOT;
    if (std::strncmp(file, root, std::strlen(root)) == 0) return file + std::strlen(root);
    if (file[0] == '/') return file;
    const char* name = file;
    while (std::strncmp(name, "../", 3) == 0 || std::strncmp(name, "./", 2) == 0) name += name[1] == '/' ? 2 : 3;
    return name;
}

void checkFailed(const char* file, int line, const char* expr, const std::string& values) {
    std::fprintf(stderr, "%s:%d: HFX_CHECK failed: %s%s%s\n", sourceName(file), line, expr,
                 values.empty() ? "" : " with ", values.c_str());
    std::abort();
}

} // namespace hfx::detail
