#include "cli/DistinctFiles.hpp"

#include <filesystem>

namespace spatter::cli {

namespace fs = std::filesystem;

namespace {

bool named(const NamedPath& p) {
    return !p.path.empty() && p.path != "-";
}

Status differ(const NamedPath& a, const NamedPath& b) {
    if (named(a) && named(b) && sameFile(a.path, b.path))
        return fail(a.option + " and " + b.option + " name the same file (" + b.path + ")");
    return {};
}

} // namespace

bool sameFile(const std::string& a, const std::string& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) {
        const bool same = fs::equivalent(a, b, ec);
        return same && !ec;
    }
    const fs::path canonicalA = fs::weakly_canonical(fs::absolute(a, ec), ec);
    if (ec) return false;
    const fs::path canonicalB = fs::weakly_canonical(fs::absolute(b, ec), ec);
    return !ec && canonicalA == canonicalB;
}

Status distinctFiles(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
    for (size_t i = 0; i < outputs.size(); ++i) {
        for (const NamedPath& input : inputs)
            if (Status s = differ(input, outputs[i]); !s) return s;
        for (size_t j = i + 1; j < outputs.size(); ++j)
            if (Status s = differ(outputs[i], outputs[j]); !s) return s;
    }
    return {};
}

} // namespace spatter::cli
