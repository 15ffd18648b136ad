#include "ThreejsPeer.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace spatter::bench {

namespace {

namespace fs = std::filesystem;

// `text` in single quotes for the shell.
std::string quote(const std::string& text) {
    std::string out = "'";
    for (char c : text)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

bool onPath(const std::string& program) {
    return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

std::string lastLines(const std::string& path, size_t count) {
    std::ifstream in(path);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) lines.push_back(line);
    std::string out;
    for (size_t i = lines.size() > count ? lines.size() - count : 0; i < lines.size(); ++i)
        out += (out.empty() ? "" : " | ") + lines[i];
    return out;
}

} // namespace

PeerRun runThreejsPeer(const std::string& objPath, const std::string& raysPath, double decalSize,
                       double maxSeconds, uint64_t seed, const std::string& workDir,
                       const std::string& peerDir) {
    PeerRun run;
    const std::string dir = peerDir.empty() ? std::string(SPATTER_BENCH_PEER_DIR) : peerDir;
    std::error_code ec;
    if (!fs::is_regular_file(fs::path(dir) / "decals.mjs", ec)) {
        run.skipped = "no peer at " + dir;
        return run;
    }
    if (!onPath("node") || !onPath("npm")) {
        run.skipped = "node or npm is not installed";
        return run;
    }
    const std::string log = workDir + "/peer.log";
    if (!fs::is_directory(fs::path(dir) / "node_modules" / "three-mesh-bvh", ec)) {
        const std::string install =
            "cd " + quote(dir) + " && npm ci --no-audit --no-fund >" + quote(log) + " 2>&1";
        if (std::system(install.c_str()) != 0) {
            run.skipped = "npm ci failed in " + dir + ": " + lastLines(log, 2);
            return run;
        }
    }
    const std::string out = workDir + "/peer.json";
    std::ostringstream cmd;
    cmd.precision(17);
    cmd << "node " << quote(dir + "/decals.mjs") << " --mesh " << quote(objPath) << " --rays "
        << quote(raysPath) << " --size " << decalSize << " --max-seconds " << maxSeconds << " --seed " << seed
        << " --json " << quote(out) << " >" << quote(log) << " 2>&1";
    if (std::system(cmd.str().c_str()) != 0) {
        run.skipped = "the peer failed: " + lastLines(log, 2);
        return run;
    }
    std::ifstream in(out);
    run.result = Json::parse(in, nullptr, false);
    if (run.result.is_discarded() || !run.result.is_object()) {
        run.skipped = "the peer wrote no JSON object to " + out;
        return run;
    }
    run.ran = true;
    return run;
}

} // namespace spatter::bench
