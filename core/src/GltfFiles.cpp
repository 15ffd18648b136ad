#include "GltfFiles.hpp"

#include "GltfImages.hpp"
#include "RegularFile.hpp"

#include <filesystem>
#include <fstream>

namespace spatter::gltf {

namespace {

// Whether `path` exists, without opening it.
bool pathExists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}

std::string expandNothing(const std::string& path, void*) {
    return path;
}

bool readRegularFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    if (std::string problem = detail::regularFileProblem(path); !problem.empty()) {
        if (err) *err += problem;
        return false;
    }
    std::error_code ec;
    const uintmax_t size = std::filesystem::file_size(path, ec);
    std::ifstream in(path, std::ios::binary);
    if (ec || !in) {
        if (err) *err += "cannot be opened";
        return false;
    }
    out->resize(size_t(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(out->data()), std::streamsize(size))) {
        if (err)
            *err += "cannot be read whole (" + std::to_string(in.gcount()) + " of " + std::to_string(size) +
                    " bytes)";
        return false;
    }
    return true;
}

bool writeNothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "the loader writes no files";
    return false;
}

} // namespace

tinygltf::FsCallbacks regularFileCallbacks() {
    tinygltf::FsCallbacks callbacks{};
    callbacks.FileExists = &pathExists;
    callbacks.ExpandFilePath = &expandNothing;
    callbacks.ReadWholeFile = &readRegularFile;
    callbacks.WriteWholeFile = &writeNothing;
    callbacks.user_data = nullptr;
    return callbacks;
}

void explainUnreadImageFiles(const tinygltf::Model& model, const std::string& baseDir,
                             std::map<int, std::string>& errors) {
    for (size_t i = 0; i < model.images.size(); ++i) {
        const tinygltf::Image& image = model.images[i];
        if (!image.image.empty() || image.uri.empty() || image.uri.rfind("data:", 0) == 0) continue;
        const std::string path = baseDir.empty() ? image.uri : baseDir + "/" + image.uri;
        const std::string problem = detail::regularFileProblem(path);
        if (problem.empty() || problem == "file not found") continue;
        errors.emplace(int(i), imageName(image, int(i)) + ": '" + path + "' " + problem);
    }
}

} // namespace spatter::gltf
