#pragma once
// A linked GLSL program built from named sources. A stage may be composed of several files
// (common declarations, a technique, a shading model, the main), concatenated in order: exactly
// one of them carries the #version line, which goes first; variants come from #define lines
// placed after it. #line directives number each file's lines as its own and give it its own
// source-string number, so a compile error names the file and line it is in. Compile and link
// failures throw hfx::Error with the file name, line and the driver's log.
//
// Owns one GL program. Thread: the thread whose GL context is current.

#include "hfx/core/GlObject.h"
#include "hfx/core/Source.h"

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace hfx {

struct ShaderDefine {
    std::string name;
    std::string value = "1";
};

class ShaderProgram {
public:
    ShaderProgram() = default;
    /// Compiles and links; `defines` go to both stages.
    ShaderProgram(const SourceFile& vertex, const SourceFile& fragment,
                  const std::vector<ShaderDefine>& defines = {});
    /// Each stage from several files, concatenated in order (see above).
    ShaderProgram(const std::vector<SourceFile>& vertex, const std::vector<SourceFile>& fragment,
                  const std::vector<ShaderDefine>& defines = {});
    /// A compute program from several files.
    static ShaderProgram compute(const std::vector<SourceFile>& parts, const std::vector<ShaderDefine>& defines = {});

    GLuint id() const { return program_.id(); }
    void use() const { glUseProgram(program_.id()); }
    /// A compute program, current: dispatches as many of its work groups as cover width x height
    /// invocations (a grid's texels or pixels), the group's size read from the program's own
    /// local_size, which is then the one place that names it.
    void dispatchOver(int width, int height) const;

    /// Uniform location, cached; -1 (silently ignored by GL) when the linker removed it.
    GLint uniform(std::string_view name) const;
    void set(std::string_view name, int v) const;
    void set(std::string_view name, float v) const;
    void set(std::string_view name, const glm::vec2& v) const;
    void set(std::string_view name, const glm::ivec2& v) const;
    void set(std::string_view name, const glm::vec3& v) const;
    void set(std::string_view name, const glm::vec4& v) const;
    void set(std::string_view name, const glm::mat3& v) const;
    void set(std::string_view name, const glm::mat4& v) const;

private:
    // Transparent hashing: looking a uniform up by string_view allocates nothing per frame.
    struct NameHash {
        using is_transparent = void;
        size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
    };
    GlProgram program_;
    mutable GLint group_[3] = {0, 0, 0}; // a compute program's local_size, read when first dispatched
    mutable std::unordered_map<std::string, GLint, NameHash, std::equal_to<>> uniforms_;
};

namespace detail {
/// Rewrites "S:12(5): error: ..." (Mesa) or "S(12) : error ..." (others) as "file:12: error: ...",
/// where file is fileNames[S], the source-string number the composition's #line gave it.
std::string annotateShaderLog(const std::string& log, const std::vector<std::string>& fileNames);
} // namespace detail

} // namespace hfx
