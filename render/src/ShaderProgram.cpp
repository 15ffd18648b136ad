#include "ShaderProgram.hpp"

#include <algorithm>
#include <set>
#include <sstream>

namespace spatter::render_detail {

namespace {

constexpr int kMaxIncludeDepth = 8;

int findSource(const ShaderLibrary& lib, const std::string& name) {
    for (size_t i = 0; i < lib.count; ++i)
        if (name == lib.files[i].name) return int(i);
    return -1;
}

std::string sourceList(const ShaderLibrary& lib) {
    std::string s;
    for (size_t i = 0; i < lib.count; ++i)
        s += (i ? ", " : "") + std::to_string(i) + " = " + lib.files[i].name;
    return s;
}

// Appends file `index` to `out` with its includes expanded (each file once); `lines`: with #line
// directives.
Status expand(const ShaderLibrary& lib, int index, std::set<int>& included, int depth, bool lines,
              std::string& out) {
    const ShaderSource* kShaderSources = lib.files;
    if (depth > kMaxIncludeDepth)
        return fail(std::string("shader ") + kShaderSources[index].name + ": includes nest too deep");
    std::istringstream in(kShaderSources[index].text);
    std::string line;
    int lineNo = 0;
    if (lines) out += "#line 1 " + std::to_string(index) + "\n";
    while (std::getline(in, line)) {
        ++lineNo;
        const size_t first = line.find_first_not_of(" \t");
        if (first != std::string::npos && line.compare(first, 8, "#include") == 0) {
            const size_t a = line.find('"', first), b = a == std::string::npos ? a : line.find('"', a + 1);
            if (b == std::string::npos)
                return fail(std::string("shader ") + kShaderSources[index].name + ":" +
                            std::to_string(lineNo) + ": malformed #include");
            const std::string name = line.substr(a + 1, b - a - 1);
            const int inc = findSource(lib, name);
            if (inc < 0)
                return fail(std::string("shader ") + kShaderSources[index].name + ":" +
                            std::to_string(lineNo) + ": no embedded file '" + name + "'");
            if (included.insert(inc).second) {
                if (Status s = expand(lib, inc, included, depth + 1, lines, out); !s) return s;
            }
            if (lines) out += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(index) + "\n";
            continue;
        }
        out += line;
        out += '\n';
    }
    return {};
}

Result<GlShader> compile(const ShaderLibrary& lib, GLenum type, const std::string& file,
                         const std::string& text) {
    GlShader shader(glCreateShader(type));
    const char* src = text.c_str();
    glShaderSource(shader.get(), 1, &src, nullptr);
    glCompileShader(shader.get());
    GLint ok = GL_FALSE;
    glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(std::max(len, 1)), '\0');
        GLsizei written = 0;
        glGetShaderInfoLog(shader.get(), GLsizei(log.size()), &written, log.data());
        log.resize(size_t(std::max(written, 0)));
        return fail("shader " + file + " does not compile (source strings: " + sourceList(lib) + "):\n" +
                    log);
    }
    return shader;
}

} // namespace

Result<std::string> expandShader(const ShaderLibrary& library, const std::string& file,
                                 const std::vector<std::string>& defines) {
    const int index = findSource(library, file);
    if (index < 0) return fail("no embedded shader file '" + file + "'");
    std::string out = "#version 450 core\n";
    for (const std::string& d : defines)
        out += "#define " + d + " 1\n";
    std::set<int> included{index};
    if (Status s = expand(library, index, included, 0, true, out); !s) return fail(s.error());
    return out;
}

Result<std::string> includeText(const ShaderLibrary& library, const std::string& file) {
    const int index = findSource(library, file);
    if (index < 0) return fail("no embedded shader file '" + file + "'");
    std::string out;
    std::set<int> included{index};
    if (Status s = expand(library, index, included, 0, false, out); !s) return fail(s.error());
    return out;
}

Result<GlProgram> buildProgram(const ShaderLibrary& library, const std::vector<ShaderStage>& stages,
                               const std::vector<std::string>& defines) {
    GlProgram program(glCreateProgram());
    std::vector<GlShader> shaders;
    std::string names;
    for (const ShaderStage& st : stages) {
        Result<std::string> text = expandShader(library, st.file, defines);
        if (!text) return fail(text.error());
        Result<GlShader> sh = compile(library, st.type, st.file, text.value());
        if (!sh) return fail(sh.error());
        glAttachShader(program.get(), sh->get());
        shaders.push_back(std::move(sh.value()));
        names += (names.empty() ? "" : " + ") + std::string(st.file);
    }
    glLinkProgram(program.get());
    for (const GlShader& sh : shaders)
        glDetachShader(program.get(), sh.get());
    GLint ok = GL_FALSE;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(std::max(len, 1)), '\0');
        GLsizei written = 0;
        glGetProgramInfoLog(program.get(), GLsizei(log.size()), &written, log.data());
        log.resize(size_t(std::max(written, 0)));
        return fail("shader program " + names + " does not link:\n" + log);
    }
    return program;
}

} // namespace spatter::render_detail
