#pragma once
// Runs the spatter-place binary of this build and collects what it wrote; where the other tools are.

#include <nlohmann/json.hpp>

#include <string>

namespace spatter::test {

// The spatter-place, spatter-info and spatter-proxy binaries, or nullptr when the tools are not built
// (SPATTER_BUILD_APPS=OFF).
extern const char* const kPlaceTool;
extern const char* const kInfoTool;
extern const char* const kProxyTool;

struct PlaceToolRun {
    int status = -1;        // as std::system returns it
    std::string records;    // stdout: JSON Lines
    nlohmann::json summary; // the last line of stderr parsed as JSON (discarded when it is not)
};

// Runs `spatter-place ARGS` (ARGS quoted as the shell needs) with stdout and stderr in files in `dir`.
PlaceToolRun runPlaceTool(const std::string& args, const std::string& dir);

std::string readFile(const std::string& path);

} // namespace spatter::test
