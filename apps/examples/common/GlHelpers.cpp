#include "GlHelpers.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace example {

namespace {

// A compiled stage; its log is appended to `log` when it does not compile.
GLuint compile(GLenum stage, const std::string& source, std::string& log) {
    const GLuint s = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint compiled = GL_FALSE;
    glGetShaderiv(s, GL_COMPILE_STATUS, &compiled);
    if (!compiled) {
        char message[2048] = "";
        glGetShaderInfoLog(s, sizeof message, nullptr, message);
        log += message;
    }
    return s;
}

} // namespace

spatter::Result<GLuint> linkProgram(const std::string& vertex, const std::string& fragment) {
    std::string log;
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex, log), fs = compile(GL_FRAGMENT_SHADER, fragment, log);
    const GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint linked = GL_FALSE;
    glGetProgramiv(p, GL_LINK_STATUS, &linked);
    if (linked) return p;
    char message[2048] = "";
    glGetProgramInfoLog(p, sizeof message, nullptr, message);
    glDeleteProgram(p);
    return spatter::fail("a program does not build: " + log + message);
}

GLuint texture(GLenum format, int width, int height) {
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, width, height);
    return t;
}

spatter::Image readImage(GLuint texture, int width, int height) {
    spatter::Image image;
    image.width = width;
    image.height = height;
    const size_t row = size_t(width) * 4;
    std::vector<uint8_t> pixels(row * size_t(height));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    image.rgba.resize(pixels.size());
    for (int y = 0; y < height; ++y)
        std::copy_n(&pixels[size_t(height - 1 - y) * row], row, &image.rgba[size_t(y) * row]);
    return image;
}

GLuint meshVertexArray(const spatter::Mesh& mesh, GLuint (&buffers)[3]) {
    glCreateBuffers(3, buffers);
    glNamedBufferStorage(buffers[0], GLsizeiptr(mesh.positions.size() * sizeof(glm::vec3)),
                         mesh.positions.data(), 0);
    glNamedBufferStorage(buffers[1], GLsizeiptr(mesh.normals.size() * sizeof(glm::vec3)), mesh.normals.data(),
                         0);
    glNamedBufferStorage(buffers[2], GLsizeiptr(mesh.indices.size() * sizeof(uint32_t)), mesh.indices.data(),
                         0);
    GLuint vertexArray = 0;
    glCreateVertexArrays(1, &vertexArray);
    for (GLuint a = 0; a < 2; ++a) {
        glVertexArrayVertexBuffer(vertexArray, a, buffers[a], 0, sizeof(glm::vec3));
        glVertexArrayAttribFormat(vertexArray, a, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vertexArray, a, a);
        glEnableVertexArrayAttrib(vertexArray, a);
    }
    glVertexArrayElementBuffer(vertexArray, buffers[2]);
    return vertexArray;
}

} // namespace example
