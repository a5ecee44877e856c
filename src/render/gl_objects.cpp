#include "render/gl_objects.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace peensim::render::gl {

void delete_program(GLuint id) { glDeleteProgram(id); }
void delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
void delete_texture(GLuint id) { glDeleteTextures(1, &id); }

Buffer make_buffer() {
    GLuint id = 0;
    glGenBuffers(1, &id);
    return Buffer(id);
}

VertexArray make_vertex_array() {
    GLuint id = 0;
    glGenVertexArrays(1, &id);
    return VertexArray(id);
}

Texture make_texture() {
    GLuint id = 0;
    glGenTextures(1, &id);
    return Texture(id);
}

namespace {

std::string shader_log(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    return log.data();
}

GLuint compile(const char* what, GLenum type, const char* source) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = shader_log(shader);
        glDeleteShader(shader);
        throw std::runtime_error(std::string("render: the ") + what + (type == GL_VERTEX_SHADER ? " vertex" : " fragment") +
                                 " shader does not compile: " + log);
    }
    return shader;
}

}  // namespace

Program make_program(const char* what, const char* vertex_source, const char* fragment_source) {
    const GLuint vs = compile(what, GL_VERTEX_SHADER, vertex_source);
    GLuint fs = 0;
    try {
        fs = compile(what, GL_FRAGMENT_SHADER, fragment_source);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    Program program(glCreateProgram());
    glAttachShader(program.get(), vs);
    glAttachShader(program.get(), fs);
    glLinkProgram(program.get());
    glDeleteShader(vs);  // flagged; freed with the program
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        GLint length = 0;
        glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &length);
        std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program.get(), length, nullptr, log.data());
        throw std::runtime_error(std::string("render: the ") + what + " shaders do not link: " + log.data());
    }
    return program;
}

GLint uniform(const Program& program, const char* name) {
    const GLint location = glGetUniformLocation(program.get(), name);
    if (location < 0) throw std::logic_error(std::string("render: shader has no active uniform '") + name + "'");
    return location;
}

Eigen::Matrix4f to_float(const Mat4& m) { return m.cast<float>(); }

void vertex_attribute(GLuint index, GLint components, GLenum type, std::size_t stride, std::size_t offset, Step step) {
    glEnableVertexAttribArray(index);
    glVertexAttribPointer(index, components, type, type == GL_UNSIGNED_BYTE ? GL_TRUE : GL_FALSE, static_cast<GLsizei>(stride),
                          reinterpret_cast<const void*>(offset));
    glVertexAttribDivisor(index, step == Step::instance ? 1 : 0);
}

void check_errors(const char* where) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        throw std::runtime_error("render: OpenGL error " + std::to_string(error) + " " + where);
    }
}

}  // namespace peensim::render::gl
