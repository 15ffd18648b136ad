// OBJ, PLY, OFF and STL through OpenMesh's readers, as one static object.

#include "spatter/core/SceneLoader.hpp"

#include "MeshFileGuard.hpp"
#include "RegularFile.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <cstdio>
#include <filesystem>

namespace spatter {

namespace {

using ReadMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// Silences OpenMesh's own error stream while reading: problems are reported through the Result.
struct QuietOpenMesh {
    QuietOpenMesh() { omerr().disable(), omlog().disable(), omout().disable(); }
    ~QuietOpenMesh() { omerr().enable(), omlog().enable(), omout().enable(); }
};

} // namespace

Status writeObj(const Mesh& mesh, const std::string& path, const std::string& comment) {
    if (comment.find_first_of("\r\n") != std::string::npos)
        return fail("cannot write '" + path + "': the comment spans more than one line");
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return fail("cannot write '" + path + "'");
    if (!comment.empty()) std::fprintf(f, "# %s\n", comment.c_str());
    for (const glm::vec3& p : mesh.positions)
        std::fprintf(f, "v %.9g %.9g %.9g\n", double(p.x), double(p.y), double(p.z));
    const bool normals = !mesh.normals.empty() && mesh.normals.size() == mesh.positions.size();
    if (normals)
        for (const glm::vec3& n : mesh.normals)
            std::fprintf(f, "vn %.9g %.9g %.9g\n", double(n.x), double(n.y), double(n.z));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t a = mesh.indices[t] + 1, b = mesh.indices[t + 1] + 1, c = mesh.indices[t + 2] + 1;
        if (normals)
            std::fprintf(f, "f %u//%u %u//%u %u//%u\n", a, a, b, b, c, c);
        else
            std::fprintf(f, "f %u %u %u\n", a, b, c);
    }
    const bool ok = std::ferror(f) == 0;
    return std::fclose(f) == 0 && ok ? Status() : Status(fail("cannot write '" + path + "'"));
}

Result<Scene> loadMeshFile(const std::string& path) {
    std::error_code ec;
    if (std::string problem = detail::regularFileProblem(path); !problem.empty())
        return fail(path + ": " + problem);
    if (std::filesystem::file_size(path, ec) == 0) return fail(path + ": file is empty");
    if (Status st = detail::checkMeshFileForOpenMesh(path); !st) return fail(path + ": " + st.error());

    ReadMesh om;
    om.request_vertex_normals();
    om.request_vertex_texcoords2D();
    OpenMesh::IO::Options opt;
    opt += OpenMesh::IO::Options::VertexNormal;
    opt += OpenMesh::IO::Options::VertexTexCoord;
    bool read = false;
    try {
        QuietOpenMesh quiet;
        read = OpenMesh::IO::read_mesh(om, path, opt);
    } catch (const std::exception& e) {
        return fail(path + ": cannot be read as a mesh (" + e.what() + ")");
    }
    if (!read) return fail(path + ": cannot be read as a mesh (unsupported or malformed file)");
    if (om.n_faces() == 0) return fail(path + ": contains no faces");

    Mesh mesh;
    mesh.positions.reserve(om.n_vertices());
    for (const auto& v : om.vertices()) {
        const auto& p = om.point(v);
        mesh.positions.emplace_back(p[0], p[1], p[2]);
    }
    const bool hasNormals = opt.check(OpenMesh::IO::Options::VertexNormal);
    const bool hasUvs = opt.check(OpenMesh::IO::Options::VertexTexCoord);
    if (hasUvs)
        for (const auto& v : om.vertices()) {
            const auto& t = om.texcoord2D(v);
            mesh.uvs.emplace_back(t[0], t[1]);
        }
    mesh.indices.reserve(om.n_faces() * 3);
    for (const auto& f : om.faces()) {
        // TriMesh triangulates polygons on import, so each face has three vertices.
        for (const auto& v : f.vertices())
            mesh.indices.push_back(uint32_t(v.idx()));
    }
    if (hasNormals) {
        for (const auto& v : om.vertices()) {
            const auto& n = om.normal(v);
            mesh.normals.emplace_back(n[0], n[1], n[2]);
        }
        repairNormals(mesh);
    } else {
        computeNormals(mesh);
    }
    if (Status s = validateMesh(mesh); !s) return fail(path + ": " + s.error());

    Scene scene;
    scene.source = path;
    SceneObject object;
    object.name = std::filesystem::path(path).stem().string();
    object.mesh = shareMesh(std::move(mesh));
    scene.objects.push_back(std::move(object));
    return scene;
}

} // namespace spatter
