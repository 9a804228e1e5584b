#include "hfx/core/ShaderProgram.h"

#include "hfx/core/Error.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstring>
#include <regex>
#include <sstream>

namespace hfx {
namespace {

/// The stage's text: the #version line (from the one part that has it), the defines, then each
/// part after "#line n k", n its first line in its file and k its index, with its own #version
/// line blanked so lines keep their numbers.
std::string compose(const std::vector<SourceFile>& parts, const std::vector<ShaderDefine>& defines) {
    const SourceFile* versioned = nullptr;
    for (const SourceFile& part : parts) {
        if (part.text.find("#version") == std::string::npos) continue;
        if (versioned)
            throw Error(str("shader parts ", versioned->name, " and ", part.name, " both have a #version line"));
        versioned = &part;
    }
    if (!versioned) {
        const std::string name = parts.empty() ? std::string("(no parts)") : parts.back().name;
        throw Error(str("shader ", name, " (", parts.empty() ? "" : parts.back().origin, ") has no #version line"));
    }
    const size_t versionStart = versioned->text.find("#version");
    const size_t versionEnd = versioned->text.find('\n', versionStart);
    std::string out = versioned->text.substr(versionStart, versionEnd - versionStart) + '\n';
    for (const ShaderDefine& d : defines) out += str("#define ", d.name, ' ', d.value, '\n');
    for (size_t k = 0; k < parts.size(); ++k) {
        std::string text = parts[k].text;
        if (&parts[k] == versioned) text.replace(versionStart, versionEnd - versionStart, "");
        out += str("#line ", parts[k].firstLine, ' ', k, '\n', text);
        if (!text.empty() && text.back() != '\n') out += '\n';
    }
    return out;
}

std::vector<std::string> namesOf(const std::vector<SourceFile>& parts) {
    std::vector<std::string> names;
    for (const SourceFile& p : parts) names.push_back(p.name);
    return names;
}

std::string shaderLog(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    log.resize(std::strlen(log.c_str()));
    return log;
}

GLuint compile(GLenum stage, const std::vector<SourceFile>& parts, const std::vector<ShaderDefine>& defines) {
    const std::string text = compose(parts, defines);
    const GLuint shader = glCreateShader(stage);
    const char* ptr = text.c_str();
    glShaderSource(shader, 1, &ptr, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string log = detail::annotateShaderLog(shaderLog(shader), namesOf(parts));
        glDeleteShader(shader);
        throw Error(str("shader ", parts.back().name, " (", parts.back().origin, ") failed to compile:\n", log));
    }
    return shader;
}

} // namespace

namespace detail {
std::string annotateShaderLog(const std::string& log, const std::vector<std::string>& fileNames) {
    static const std::regex mesa(R"(^\s*(\d+):(\d+)\(\d+\):\s*)");
    static const std::regex other(R"(^\s*(?:ERROR:\s*)?(\d+)[:(](\d+)\)?\s*:\s*)");
    std::istringstream in(log);
    std::string line, out;
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_search(line, m, mesa) || std::regex_search(line, m, other)) {
            const size_t k = std::stoul(m[1].str());
            const std::string file = k < fileNames.size() ? fileNames[k] : str("source ", k);
            line = str(file, ':', m[2].str(), ": ", m.suffix().str());
        }
        out += line + '\n';
    }
    return out;
}
} // namespace detail

ShaderProgram::ShaderProgram(const SourceFile& vertex, const SourceFile& fragment,
                             const std::vector<ShaderDefine>& defines)
    : ShaderProgram(std::vector<SourceFile>{vertex}, std::vector<SourceFile>{fragment}, defines) {}

namespace {
/// Links the compiled stages into `program` (deleting them), throwing the log on failure.
void link(GLuint program, std::initializer_list<GLuint> stages, const std::string& what) {
    for (GLuint s : stages) glAttachShader(program, s);
    glLinkProgram(program);
    for (GLuint s : stages) {
        glDetachShader(program, s);
        glDeleteShader(s);
    }
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program, length, nullptr, log.data());
        throw Error(str("program ", what, " failed to link:\n", log.c_str()));
    }
}
} // namespace

ShaderProgram::ShaderProgram(const std::vector<SourceFile>& vertex, const std::vector<SourceFile>& fragment,
                             const std::vector<ShaderDefine>& defines)
    : program_(GlProgram::create()) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex, defines);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, fragment, defines);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    link(program_.id(), {vs, fs}, str(vertex.back().name, " + ", fragment.back().name));
}

ShaderProgram ShaderProgram::compute(const std::vector<SourceFile>& parts, const std::vector<ShaderDefine>& defines) {
    ShaderProgram p;
    p.program_ = GlProgram::create();
    link(p.program_.id(), {compile(GL_COMPUTE_SHADER, parts, defines)}, parts.empty() ? "" : parts.back().name);
    return p;
}

GLint ShaderProgram::uniform(std::string_view name) const {
    auto it = uniforms_.find(name);
    if (it == uniforms_.end())
        it = uniforms_
                 .emplace(std::string(name),
                          glGetUniformLocation(program_.id(), std::string(name).c_str()))
                 .first;
    return it->second;
}

void ShaderProgram::dispatchOver(int width, int height) const {
    if (group_[0] == 0) glGetProgramiv(id(), GL_COMPUTE_WORK_GROUP_SIZE, group_);
    if (group_[0] <= 0 || group_[1] <= 0) {
        while (glGetError() != GL_NO_ERROR) {} // the query's GL_INVALID_OPERATION, named here instead
        throw Error(str("ShaderProgram::dispatchOver: program ", id(), " is not a linked compute program"));
    }
    HFX_GL_CHECK(glDispatchCompute(GLuint((std::max(width, 0) + group_[0] - 1) / group_[0]),
                                   GLuint((std::max(height, 0) + group_[1] - 1) / group_[1]), 1));
}

void ShaderProgram::set(std::string_view name, int v) const {
    glProgramUniform1i(id(), uniform(name), v);
}
void ShaderProgram::set(std::string_view name, float v) const {
    glProgramUniform1f(id(), uniform(name), v);
}
void ShaderProgram::set(std::string_view name, const glm::vec2& v) const {
    glProgramUniform2fv(id(), uniform(name), 1, glm::value_ptr(v));
}
void ShaderProgram::set(std::string_view name, const glm::ivec2& v) const {
    glProgramUniform2iv(id(), uniform(name), 1, glm::value_ptr(v));
}
void ShaderProgram::set(std::string_view name, const glm::vec3& v) const {
    glProgramUniform3fv(id(), uniform(name), 1, glm::value_ptr(v));
}
void ShaderProgram::set(std::string_view name, const glm::vec4& v) const {
    glProgramUniform4fv(id(), uniform(name), 1, glm::value_ptr(v));
}
void ShaderProgram::set(std::string_view name, const glm::mat3& v) const {
    glProgramUniformMatrix3fv(id(), uniform(name), 1, GL_FALSE, glm::value_ptr(v));
}
void ShaderProgram::set(std::string_view name, const glm::mat4& v) const {
    glProgramUniformMatrix4fv(id(), uniform(name), 1, GL_FALSE, glm::value_ptr(v));
}

} // namespace hfx
