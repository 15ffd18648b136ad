// MeshFileGuard for OBJ. OpenMesh's reader adds the "v" lines whose first three words read as floats
// and silently skips the others, so that every later face index names another vertex; it skips "vn"
// lines the same way, shifting normals. It reads each face corner "v[/vt[/vn]]" as iostreams read an
// int, skips a corner that is no number (and a whole face left with fewer than three different
// vertices, which has no area when no corner was skipped), and stores the corner's texture coordinate and
// normal at vertex v without checking v (an unparsable v leaves it an uninitialised int). The guard reads
// every line once, strictly: a file it accepts is read by OpenMesh with every vertex and every face.

#include "MeshFileGuardFormats.hpp"
#include "MeshFileWords.hpp"
#include "RegularFile.hpp"
#include "TextLineReader.hpp"

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

namespace spatter::detail {

namespace {

// A corner's index into the "v", "vt" or "vn" lines, which may come before or after the faces.
struct ObjIndexRange {
    explicit ObjIndexRange(const char* kind) : name(kind) {}

    const char* name;
    int64_t lines = 0; // the lines of this kind so far
    struct Forward {   // a corner naming a line further on, the largest so far when it came
        size_t line;
        std::string corner;
        int64_t index;
    };
    std::vector<Forward> forward;
};

struct ObjCheck {
    ObjIndexRange positions{"vertex"}, texCoords{"texture coordinate"}, normals{"normal"};
    std::vector<int64_t> faceVertices; // reused from face to face
    std::string directory;             // where the reader looks for material libraries
    size_t line = 0;

    Error at(const std::string& problem) const {
        return fail("line " + std::to_string(line) + ": " + problem);
    }
};

// The first `needed` words of a "v", "vt" or "vn" line (after `keyword`) must be finite numbers.
Status checkObjNumbers(std::string_view keyword, std::string_view rest, unsigned needed, const char* what,
                       const ObjCheck& c) {
    for (unsigned i = 0; i < needed; ++i) {
        const std::string_view word = nextWord(rest);
        if (word.empty() || word[0] == '#')
            return c.at("'" + std::string(keyword) + "' line has " + std::to_string(i) +
                        (i == 1 ? " number, " : " numbers, ") + std::to_string(needed) + " needed");
        float value;
        if (const NumberWord kind = readFloatWord(word, value); kind != NumberWord::Finite)
            return c.at(std::string(what) + " '" + excerpt(word) + "' " + numberWordProblem(kind));
    }
    return {};
}

// Checks a corner's index of one kind: a negative one counts back from the lines so far, a positive
// one beyond them is checked once all lines are known.
Status checkObjIndex(int64_t value, std::string_view corner, ObjIndexRange& range, const ObjCheck& c,
                     int64_t& index) {
    index = value < 0 ? range.lines + value + 1 : value;
    const int64_t largest = range.forward.empty() ? range.lines : range.forward.back().index;
    if (index > largest) range.forward.push_back({c.line, std::string(corner), index});
    if (index < 1)
        return c.at("face corner '" + excerpt(corner) + "' refers to " + range.name + " " +
                    std::to_string(index) + " of " + std::to_string(range.lines));
    return {};
}

Status checkObjForwardIndices(const ObjIndexRange& range) {
    for (const ObjIndexRange::Forward& f : range.forward) // the first corner past the last line
        if (f.index > range.lines)
            return fail("line " + std::to_string(f.line) + ": face corner '" + excerpt(f.corner) +
                        "' refers to " + range.name + " " + std::to_string(f.index) + " of " +
                        std::to_string(range.lines));
    return {};
}

Status checkObjCorner(std::string_view corner, ObjCheck& c) {
    std::string_view parts[3];
    size_t count = 0;
    for (std::string_view rest = corner;; ++count) {
        const size_t slash = rest.find('/');
        if (count == 3) return c.at("face corner '" + excerpt(corner) + "' has more than v/vt/vn");
        parts[count] = rest.substr(0, slash);
        if (slash == std::string_view::npos) break;
        rest.remove_prefix(slash + 1);
    }
    int64_t value = 0, index = 0;
    if (!readIntegerWord(parts[0], value)) {
        if (count == 0) return c.at("face corner '" + excerpt(corner) + "' is not an integer vertex index");
        return c.at("face corner '" + excerpt(corner) + "' has no vertex index" +
                    (parts[0].empty() ? "" : " ('" + excerpt(parts[0]) + "' is not an integer)"));
    }
    if (Status s = checkObjIndex(value, corner, c.positions, c, index); !s) return s;
    c.faceVertices.push_back(index);
    ObjIndexRange* ranges[3] = {nullptr, &c.texCoords, &c.normals};
    for (size_t k = 1; k <= count && k < 3; ++k) {
        if (parts[k].empty()) continue; // "v//vn" and "v/" leave a part out
        if (!readIntegerWord(parts[k], value))
            return c.at("face corner '" + excerpt(corner) + "': " + ranges[k]->name + " index '" +
                        excerpt(parts[k]) + "' is not an integer");
        if (Status s = checkObjIndex(value, corner, *ranges[k], c, index); !s) return s;
    }
    return {};
}

Status checkObjFace(std::string_view rest, ObjCheck& c) {
    c.faceVertices.clear();
    for (std::string_view corner = nextWord(rest); !corner.empty(); corner = nextWord(rest)) {
        if (corner[0] == '#') break; // a comment to the end of the line
        if (c.faceVertices.size() == kMaxFaceCorners)
            return c.at("face has more than " + std::to_string(kMaxFaceCorners) + " corners");
        if (Status s = checkObjCorner(corner, c); !s) return s;
    }
    // A face of fewer than three different vertices, which the reader skips, has no area: no surface
    // is lost (the degenerate faces of exported meshes load).
    const size_t corners = c.faceVertices.size();
    if (corners < 3) return c.at("face has " + std::to_string(corners) + " corners, at least 3 needed");
    return {};
}

// The reader opens and reads the material library the line names: a FIFO would wait for a writer and
// a device (/dev/zero) would never end. A directory or a missing file it skips with a warning.
Status checkObjMaterialLibrary(std::string_view rest, const ObjCheck& c) {
    const std::string name(trimLine(rest)), library = c.directory + name;
    const std::string problem = regularFileProblem(library);
    if (problem.empty() || problem == "file not found" || problem == "is a directory") return {};
    return c.at("material library '" + excerpt(name, 64) + "' " + problem);
}

Status checkObjLine(std::string_view line, ObjCheck& c) {
    std::string_view rest = trimLine(line);
    if (rest.empty() || rest[0] == '#' || std::isspace(static_cast<unsigned char>(rest[0]))) return {};
    const std::string_view keyword = nextWord(rest);
    if (keyword == "v") {
        ++c.positions.lines;
        return checkObjNumbers(keyword, rest, 3, "vertex coordinate", c);
    }
    if (keyword == "vt") {
        ++c.texCoords.lines;
        return checkObjNumbers(keyword, rest, 2, "texture coordinate", c);
    }
    if (keyword == "vn") {
        ++c.normals.lines;
        return checkObjNumbers(keyword, rest, 3, "normal coordinate", c);
    }
    if (keyword == "f") return checkObjFace(rest, c);
    if (keyword == "mtllib") return checkObjMaterialLibrary(rest, c);
    return {};
}

} // namespace

Status checkObjForOpenMesh(std::ifstream& in, const std::string& path) {
    ObjCheck c;
    const size_t slash = path.rfind('/');
    c.directory = slash == std::string::npos ? "./" : path.substr(0, slash + 1);
    TextLineReader lines(in);
    for (std::string_view line; lines.next(line);) {
        c.line = lines.lineNumber();
        if (Status s = checkObjLine(line, c); !s) return s;
    }
    for (const ObjIndexRange* range : {&c.positions, &c.texCoords, &c.normals})
        if (Status s = checkObjForwardIndices(*range); !s) return s;
    return {};
}

} // namespace spatter::detail
