// Small owners of OpenGL objects (programs, buffers, vertex arrays, textures) that delete them
// with their owner, and a shader compiler whose errors carry the GL info log. Internal to
// render/: the objects must be created and destroyed while their context is current.
#pragma once

#include <cstddef>
#include <string>
#include <utility>

#include "render/camera.h"
#include "render/gl.h"

namespace peensim::render::gl {

// One GL name with its delete function; movable, not copyable.
template <void (*Delete)(GLuint)>
class Name {
public:
    Name() = default;
    explicit Name(GLuint id) : id_(id) {}
    ~Name() {
        if (id_ != 0) Delete(id_);
    }
    Name(Name&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    Name& operator=(Name&& other) noexcept {
        if (this != &other) {
            if (id_ != 0) Delete(id_);
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }
    Name(const Name&) = delete;
    Name& operator=(const Name&) = delete;
    GLuint get() const { return id_; }

private:
    GLuint id_ = 0;
};

void delete_program(GLuint id);
void delete_buffer(GLuint id);
void delete_vertex_array(GLuint id);
void delete_texture(GLuint id);

using Program = Name<delete_program>;
using Buffer = Name<delete_buffer>;
using VertexArray = Name<delete_vertex_array>;
using Texture = Name<delete_texture>;

Buffer make_buffer();
VertexArray make_vertex_array();
Texture make_texture();

// Compiles and links a vertex + fragment shader pair. Throws std::runtime_error naming
// `what` with the compiler's log: a shader that does not build is a bug in render/, but the
// message must still say which shader and why.
Program make_program(const char* what, const char* vertex_source, const char* fragment_source);

// Uniform location; throws std::logic_error when the program has no active uniform `name`
// (a misspelt name would otherwise be ignored silently by GL).
GLint uniform(const Program& program, const char* name);

// The float copy GL wants (column-major, as Eigen stores it).
Eigen::Matrix4f to_float(const Mat4& m);

// Throws std::runtime_error "render: OpenGL error <code> <where>" when GL has an error flagged.
void check_errors(const char* where);

// How the bound vertex array reads the bound array buffer's attribute `index`: `components`
// values of `type` at byte `offset` of every record of `stride` bytes (GL_UNSIGNED_BYTE values are
// normalised to 0..1: colours). Records per vertex, or per instance (`Step::instance`).
enum class Step { vertex, instance };
void vertex_attribute(GLuint index, GLint components, GLenum type, std::size_t stride, std::size_t offset, Step step);

}  // namespace peensim::render::gl
