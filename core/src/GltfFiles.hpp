#pragma once
// The files a glTF document names (buffers and images by uri), as tinygltf reads them: its own file
// callbacks open a path to see whether it exists and read whatever opens, so that a uri naming a FIFO
// waits forever for a writer and one naming a directory ("." ) asks for an absurd allocation. These
// read regular files only and say what a uri names otherwise. Internal to spatter::core.

#include <tiny_gltf.h>

#include <map>
#include <string>

namespace spatter::gltf {

// File callbacks for tinygltf::TinyGLTF::SetFsCallbacks.
tinygltf::FsCallbacks regularFileCallbacks();

// tinygltf only warns of an image file it could not read. For each image left empty whose uri names
// something beside the document (`baseDir`) that is not a regular file, adds what it is to `errors`
// (by image index), unless an error is there already.
void explainUnreadImageFiles(const tinygltf::Model& model, const std::string& baseDir,
                             std::map<int, std::string>& errors);

} // namespace spatter::gltf
