#pragma once
// Text sources (GLSL, OpenCL C) are embedded in the libraries at build time. For live editing,
// an environment variable may name a folder whose file of the same name wins over the copy.
//
// Owns the loaded text. Thread: any.

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace hfx {

struct SourceFile {
    std::string name;   ///< file name, used in error messages ("surface.frag")
    std::string text;
    std::string origin; ///< "embedded" or the path it was read from
    int firstLine = 1;  ///< the text's first line in its file (a piece of it between #include lines)
};

/// The parts of a shader stage composed from its top file, in order: each line
/// `#include "path"` is replaced by the parts of that file, and `#include <slot>` by those of the
/// file `slots` names for the slot (the caller's choice: the technique's tracer, the shading
/// model). A file is included once per stage (a later include of it adds nothing); includes are
/// textual and unconditional (not inside #if). The text around an include stays a part of its
/// own file with its own line numbers (SourceFile::firstLine), so a compile error names the file
/// and line. `load` returns a file by its path. Throws hfx::Error naming the file and line of an
/// include that is malformed, names a slot `slots` lacks, or closes a cycle.
using SourceLoader = std::function<SourceFile(std::string_view)>;
std::vector<SourceFile> expandIncludes(const SourceFile& top, const SourceLoader& load,
                                       const std::map<std::string, std::string, std::less<>>& slots = {});

/// Returns `name` from `overrideDirEnv`'s folder when that variable is set and the file exists
/// there, else the embedded text. Throws hfx::Error when neither has it.
SourceFile loadSource(std::string_view name, std::string_view embedded, const char* overrideDirEnv);

/// Reads a whole file; throws hfx::Error naming the path when it cannot.
std::string readTextFile(const std::string& path);

} // namespace hfx
