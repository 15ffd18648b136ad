#pragma once
// Shader programs built from the GLSL files embedded at build time (shaders/, through the generated
// ShaderSources.hpp). Every stage gets "#version 450 core", then one "#define NAME 1" per variant
// feature, then its file with each `#include "file"` line replaced by that file (once per stage).
// `#line` directives keep compiler messages pointing at the right file and line: source-string
// number k is the k-th embedded file, listed in the error text.

#include "GlObjects.hpp"

#include "spatter/core/Result.hpp"

#include <string>
#include <vector>

namespace spatter::render_detail {

struct ShaderStage {
    GLenum type;      // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER
    const char* file; // name of the embedded file, e.g. "decal.frag"
};

// The complete text of `file` for the given defines, or an error naming a missing file or include.
Result<std::string> expandShader(const std::string& file, const std::vector<std::string>& defines);

// Compiles and links; errors carry the file names and the driver's log.
Result<GlProgram> buildProgram(const std::vector<ShaderStage>& stages,
                               const std::vector<std::string>& defines);

} // namespace spatter::render_detail
