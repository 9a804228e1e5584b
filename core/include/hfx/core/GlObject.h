#pragma once
// Move-only owners of GL object names. Each owns exactly one name, deletes it in the destructor
// (which never throws), and is empty (id() == 0) after a move or release(). They must be
// destroyed while the context that created them is current.
//
// Owns one GL object name each (deleted on destruction). Thread: the thread whose context
// made the object, with that context current.

#include "hfx/core/Gl.h"

#include <utility>

namespace hfx {

template <typename Traits>
class GlObject {
public:
    GlObject() = default;
    /// Creates a new object of this kind in the current context.
    static GlObject create() { return GlObject(Traits::create()); }
    /// Takes ownership of an existing name.
    static GlObject adopt(GLuint id) { return GlObject(id); }

    GlObject(GlObject&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    GlObject& operator=(GlObject&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;
    ~GlObject() { reset(); }

    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    /// Gives up ownership without deleting; the caller now owns the name.
    GLuint release() { return std::exchange(id_, 0); }
    void reset() {
        if (id_ != 0) Traits::destroy(std::exchange(id_, 0));
    }

private:
    explicit GlObject(GLuint id) : id_(id) {}
    GLuint id_ = 0;
};

namespace gltraits {
struct Buffer {
    static GLuint create() { GLuint id = 0; glCreateBuffers(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct VertexArray {
    static GLuint create() { GLuint id = 0; glCreateVertexArrays(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct Framebuffer {
    static GLuint create() { GLuint id = 0; glCreateFramebuffers(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct Renderbuffer {
    static GLuint create() { GLuint id = 0; glCreateRenderbuffers(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteRenderbuffers(1, &id); }
};
struct Texture2D {
    static GLuint create() { GLuint id = 0; glCreateTextures(GL_TEXTURE_2D, 1, &id); return id; }
    static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct Texture2DArray {
    static GLuint create() { GLuint id = 0; glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id); return id; }
    static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct Program {
    static GLuint create() { return glCreateProgram(); }
    static void destroy(GLuint id) { glDeleteProgram(id); }
};
struct Query {
    static GLuint create() { GLuint id = 0; glGenQueries(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};
struct Sampler {
    static GLuint create() { GLuint id = 0; glCreateSamplers(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteSamplers(1, &id); }
};
} // namespace gltraits

using GlBuffer = GlObject<gltraits::Buffer>;
using GlVertexArray = GlObject<gltraits::VertexArray>;
using GlFramebuffer = GlObject<gltraits::Framebuffer>;
using GlRenderbuffer = GlObject<gltraits::Renderbuffer>;
using GlTexture = GlObject<gltraits::Texture2D>;
using GlTextureArray = GlObject<gltraits::Texture2DArray>;
using GlProgram = GlObject<gltraits::Program>;
using GlQuery = GlObject<gltraits::Query>;
using GlSampler = GlObject<gltraits::Sampler>;

} // namespace hfx
