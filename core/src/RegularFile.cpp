#include "RegularFile.hpp"

#include <filesystem>

namespace spatter::detail {

std::string regularFileProblem(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    switch (status.type()) {
    case fs::file_type::regular:
        return {};
    case fs::file_type::not_found:
        return "file not found";
    case fs::file_type::directory:
        return "is a directory";
    case fs::file_type::fifo:
        return "is a FIFO (named pipe), not a regular file";
    case fs::file_type::character:
        return "is a character device, not a regular file";
    case fs::file_type::block:
        return "is a block device, not a regular file";
    case fs::file_type::socket:
        return "is a socket, not a regular file";
    case fs::file_type::none:
        return "cannot be examined (" + ec.message() + ")";
    default:
        return "is not a regular file";
    }
}

} // namespace spatter::detail
