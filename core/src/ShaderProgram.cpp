#include "hfx/core/ShaderProgram.h"

#include "hfx/core/Error.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstring>
#include <regex>
#include <sstream>

namespace hfx {
namespace {

std::string withDefines(const SourceFile& source, const std::vector<ShaderDefine>& defines) {
    const std::string& text = source.text;
    const size_t versionStart = text.find("#version");
    if (versionStart == std::string::npos)
        throw Error(str("shader ", source.name, " (", source.origin, ") has no #version line"));
    const size_t versionEnd = text.find('\n', versionStart);
    std::string out = text.substr(0, versionEnd + 1);
    for (const ShaderDefine& d : defines) out += str("#define ", d.name, ' ', d.value, '\n');
    // Count lines up to and including the #version line so the log speaks of the file's lines.
    const auto versionLine = std::count(text.begin(), text.begin() + versionEnd, '\n') + 1;
    out += str("#line ", versionLine + 1, '\n');
    if (versionEnd != std::string::npos) out += text.substr(versionEnd + 1);
    return out;
}

std::string shaderLog(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    log.resize(std::strlen(log.c_str()));
    return log;
}

GLuint compile(GLenum stage, const SourceFile& source, const std::vector<ShaderDefine>& defines) {
    const std::string text = withDefines(source, defines);
    const GLuint shader = glCreateShader(stage);
    const char* ptr = text.c_str();
    glShaderSource(shader, 1, &ptr, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string log = detail::annotateShaderLog(shaderLog(shader), source.name);
        glDeleteShader(shader);
        throw Error(str("shader ", source.name, " (", source.origin, ") failed to compile:\n",
                        log));
    }
    return shader;
}

} // namespace

namespace detail {
std::string annotateShaderLog(const std::string& log, const std::string& fileName) {
    static const std::regex mesa(R"(^\s*\d+:(\d+)\(\d+\):\s*)");
    static const std::regex other(R"(^\s*(?:ERROR:\s*)?\d+[:(](\d+)\)?\s*:\s*)");
    std::istringstream in(log);
    std::string line, out;
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_search(line, m, mesa) || std::regex_search(line, m, other))
            line = str(fileName, ':', m[1].str(), ": ", m.suffix().str());
        out += line + '\n';
    }
    return out;
}
} // namespace detail

ShaderProgram::ShaderProgram(const SourceFile& vertex, const SourceFile& fragment,
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
    glAttachShader(program_.id(), vs);
    glAttachShader(program_.id(), fs);
    glLinkProgram(program_.id());
    glDetachShader(program_.id(), vs);
    glDetachShader(program_.id(), fs);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(program_.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program_.id(), GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program_.id(), length, nullptr, log.data());
        throw Error(str("program ", vertex.name, " + ", fragment.name, " failed to link:\n",
                        log.c_str()));
    }
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
void ShaderProgram::set(std::string_view name, const glm::mat4& v) const {
    glProgramUniformMatrix4fv(id(), uniform(name), 1, GL_FALSE, glm::value_ptr(v));
}

} // namespace hfx
