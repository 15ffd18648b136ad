#pragma once
// The few OpenGL helpers spatter's example hosts share: a program from the sources of its two
// stages, a 2D texture, a colour texture read back as an image, and a mesh's vertex array. A GL 4.5 context
// must be current.

#include <spatter/core/Image.hpp>
#include <spatter/core/Mesh.hpp>
#include <spatter/core/Result.hpp>

#include <epoxy/gl.h>

#include <string>

namespace example {

// The program of a vertex and a fragment stage; fails with the compiler's and linker's log.
spatter::Result<GLuint> linkProgram(const std::string& vertex, const std::string& fragment);

// A GL_TEXTURE_2D of one level in `format`.
GLuint texture(GLenum format, int width, int height);

// Level 0 of a colour texture as 8-bit RGBA, row 0 at the top.
spatter::Image readImage(GLuint texture, int width, int height);

// A vertex array of `mesh`'s positions (attribute 0) and normals (attribute 1), indexed by its
// indices, in three new buffers left in `buffers` (positions, normals, indices) for the caller to
// delete with the array.
GLuint meshVertexArray(const spatter::Mesh& mesh, GLuint (&buffers)[3]);

} // namespace example
