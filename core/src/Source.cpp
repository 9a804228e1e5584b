#include "hfx/core/Source.h"

#include "hfx/core/Error.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace hfx {

std::string readTextFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(str("cannot open '", path, "'"));
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

SourceFile loadSource(std::string_view name, std::string_view embedded,
                      const char* overrideDirEnv) {
    if (const char* dir = overrideDirEnv ? std::getenv(overrideDirEnv) : nullptr; dir && *dir) {
        const std::filesystem::path path = std::filesystem::path(dir) / name;
        if (std::filesystem::exists(path))
            return {std::string(name), readTextFile(path.string()), path.string()};
    }
    if (embedded.empty())
        throw Error(str("no source named '", name, "' is embedded in this build"));
    return {std::string(name), std::string(embedded), "embedded"};
}

} // namespace hfx
