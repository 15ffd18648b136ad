#include "cli/PathChecks.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace spatter::cli {

namespace fs = std::filesystem;

namespace {

// Empty when this process has `mode` (R_OK, W_OK, X_OK) on `path`; else why not.
std::string denied(const fs::path& path, int mode) {
    return access(path.c_str(), mode) == 0 ? std::string() : std::string(std::strerror(errno));
}

Error pathError(const NamedPath& p, const std::string& what) {
    return fail(p.option + ": " + p.path + " " + what);
}

// The nearest of `path`'s ancestors (or `path` itself) that exists; "." for a relative path none of
// whose ancestors exists.
fs::path nearestExisting(fs::path path) {
    std::error_code ec;
    while (!path.empty() && !fs::exists(path, ec) && path.parent_path() != path)
        path = path.parent_path();
    return path.empty() ? fs::path(".") : path;
}

} // namespace

Status readableFile(const NamedPath& p) {
    std::error_code ec;
    const fs::file_status st = fs::status(p.path, ec);
    if (!fs::exists(st)) return pathError(p, "does not exist");
    if (fs::is_directory(st)) return pathError(p, "is a directory, not a file");
    if (const std::string why = denied(p.path, R_OK); !why.empty())
        return pathError(p, "cannot be read: " + why);
    return {};
}

Status creatableFile(const NamedPath& p) {
    std::error_code ec;
    const fs::path path(p.path);
    const fs::file_status st = fs::status(path, ec);
    if (fs::is_directory(st) || !path.has_filename()) return pathError(p, "is a directory, not a file");
    if (fs::exists(st)) {
        if (const std::string why = denied(path, W_OK); !why.empty())
            return pathError(p, "cannot be written: " + why);
        return {};
    }
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!fs::exists(folder, ec))
        return pathError(p, "cannot be created: " + folder.string() + " does not exist");
    if (!fs::is_directory(folder, ec))
        return pathError(p, "cannot be created: " + folder.string() + " is not a directory");
    if (const std::string why = denied(folder, W_OK | X_OK); !why.empty())
        return pathError(p, "cannot be created: " + why);
    return {};
}

Status usableDirectory(const NamedPath& p) {
    std::error_code ec;
    const fs::path existing = nearestExisting(p.path);
    if (!fs::is_directory(existing, ec))
        return existing == fs::path(p.path)
                   ? pathError(p, "is not a directory")
                   : pathError(p, "cannot be created: " + existing.string() + " is not a directory");
    if (const std::string why = denied(existing, W_OK | X_OK); !why.empty())
        return pathError(p, "cannot be written into: " + why);
    return {};
}

Status executableFile(const NamedPath& p) {
    std::error_code ec;
    if (!fs::is_regular_file(p.path, ec) || !denied(p.path, X_OK).empty())
        return pathError(p, "is not an executable file");
    return {};
}

} // namespace spatter::cli
