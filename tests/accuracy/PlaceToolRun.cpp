#include "PlaceToolRun.hpp"

#include <cstdlib>
#include <fstream>
#include <iterator>

namespace spatter::test {

#ifdef SPATTER_PLACE_TOOL
const char* const kPlaceTool = SPATTER_PLACE_TOOL;
#else
const char* const kPlaceTool = nullptr;
#endif
#ifdef SPATTER_INFO_TOOL
const char* const kInfoTool = SPATTER_INFO_TOOL;
#else
const char* const kInfoTool = nullptr;
#endif
#ifdef SPATTER_PROXY_TOOL
const char* const kProxyTool = SPATTER_PROXY_TOOL;
#else
const char* const kProxyTool = nullptr;
#endif

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

PlaceToolRun runPlaceTool(const std::string& args, const std::string& dir) {
    const std::string out = dir + "/records.jsonl", err = dir + "/stderr.txt";
    const std::string command =
        std::string("'") + kPlaceTool + "' " + args + " > '" + out + "' 2> '" + err + "'";
    PlaceToolRun r;
    r.status = std::system(command.c_str());
    r.records = readFile(out);
    std::string lastLine = readFile(err);
    while (!lastLine.empty() && lastLine.back() == '\n')
        lastLine.pop_back();
    lastLine = lastLine.substr(lastLine.rfind('\n') == std::string::npos ? 0 : lastLine.rfind('\n') + 1);
    r.summary = nlohmann::json::parse(lastLine, nullptr, false);
    return r;
}

} // namespace spatter::test
