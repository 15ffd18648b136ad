#pragma once
// Helpers shared by the file-loader fuzz targets: the loaders read files, so each input is written
// to a file in a private work directory first.

#include "spatter/core/Image.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <unistd.h>

namespace spatter::fuzz {

// A fresh directory for this process's files: $TMPDIR (or /tmp)/spatter-fuzz-NAME-PID.
inline std::string workDir(const std::string& name) {
    const char* tmp = std::getenv("TMPDIR");
    std::filesystem::path dir = std::filesystem::path(tmp && *tmp ? tmp : "/tmp") /
                                ("spatter-fuzz-" + name + "-" + std::to_string(::getpid()));
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    std::filesystem::create_directories(dir, ec);
    if (ec) {
        std::fprintf(stderr, "fuzz: cannot create %s: %s\n", dir.c_str(), ec.message().c_str());
        std::abort();
    }
    return dir.string();
}

// Writes `size` bytes to `path`, replacing it; aborts when that fails (the harness is broken then).
inline void writeFile(const std::string& path, const uint8_t* data, size_t size) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || (size && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
        std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
        std::abort();
    }
}

// A 2 x 2 RGBA PNG at `path`, for glTF files that name an external image.
inline void writeTinyPng(const std::string& path) {
    Image image;
    image.width = 2;
    image.height = 2;
    image.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
    if (Status s = writePng(path, image); !s) {
        std::fprintf(stderr, "fuzz: %s\n", s.error().c_str());
        std::abort();
    }
}

} // namespace spatter::fuzz
