#pragma once
// Text sources (GLSL, OpenCL C) are embedded in the libraries at build time. For live editing,
// an environment variable may name a folder whose file of the same name wins over the copy.
//
// Owns the loaded text. Thread: any.

#include <string>
#include <string_view>

namespace hfx {

struct SourceFile {
    std::string name;   ///< file name, used in error messages ("surface.frag")
    std::string text;
    std::string origin; ///< "embedded" or the path it was read from
};

/// Returns `name` from `overrideDirEnv`'s folder when that variable is set and the file exists
/// there, else the embedded text. Throws hfx::Error when neither has it.
SourceFile loadSource(std::string_view name, std::string_view embedded, const char* overrideDirEnv);

/// Reads a whole file; throws hfx::Error naming the path when it cannot.
std::string readTextFile(const std::string& path);

} // namespace hfx
