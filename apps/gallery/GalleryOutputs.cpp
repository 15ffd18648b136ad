#include "GalleryOutputs.hpp"

#include "cli/DistinctFiles.hpp"
#include "cli/PathChecks.hpp"

#include <filesystem>
#include <vector>

namespace spatter::gallery {

Status prepareHeadlessOutputs(const GalleryOptions& options) {
    std::error_code ec;
    std::filesystem::create_directories(options.outDir, ec);
    if (ec) return fail("--out: cannot create the folder " + options.outDir + ": " + ec.message());
    std::vector<cli::NamedPath> outputs = {{"--out", options.outDir + "/gallery.png"},
                                           {"--out", options.outDir + "/gallery.json"}};
    if (!options.savePath.empty()) outputs.push_back({"--save", options.savePath});
    if (Status s = cli::distinctFiles(outputs, {{"--scene", options.scene}}); !s) return s;
    for (const cli::NamedPath& output : outputs)
        if (Status s = cli::creatableFile(output); !s) return s;
    if (!options.cacheDir.empty()) return cli::usableDirectory({"--cache", options.cacheDir});
    return {};
}

} // namespace spatter::gallery
