#include "cli/OutputCleanup.hpp"

#include <filesystem>

namespace spatter::cli {

OutputCleanup::~OutputCleanup() {
    std::error_code ec;
    for (const std::string& path : paths_) // the path itself, not what a symbolic link names
        if (std::filesystem::is_regular_file(std::filesystem::symlink_status(path, ec)))
            std::filesystem::remove(path, ec);
}

} // namespace spatter::cli
