#include "cli/Arguments.hpp"

#include <utility>

namespace spatter::cli {

Arguments::Arguments(int argc, char** argv, int first, std::set<std::string> repeatable)
    : argc_(argc), argv_(argv), next_(first), repeatable_(std::move(repeatable)) {}

Result<std::string> Arguments::next() {
    std::string a = argv_[next_++];
    const bool option = a.size() > 1 && a[0] == '-';
    if (option && !repeatable_.count(a) && !seen_.insert(a).second) return fail(a + " given twice");
    return a;
}

std::optional<std::string> Arguments::value() {
    if (!more() || std::string(argv_[next_]).rfind("--", 0) == 0) return std::nullopt;
    return std::string(argv_[next_++]);
}

} // namespace spatter::cli
