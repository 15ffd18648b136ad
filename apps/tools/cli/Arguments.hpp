#pragma once
// Walking a tool's command line: each option at most once, and an option's value present. Every tool
// reads its arguments through this, so that a repeated option or a missing value fails the same way
// everywhere.

#include "spatter/core/Result.hpp"

#include <optional>
#include <set>
#include <string>

namespace spatter::cli {

class Arguments {
public:
    // The arguments argv[first..argc). `repeatable` names the options that may be given more than
    // once (lists, such as spatter-render's --texture-space).
    Arguments(int argc, char** argv, int first = 1, std::set<std::string> repeatable = {});

    bool more() const { return next_ < argc_; }

    // The next argument. Fails on an option (a word that starts with '-', "-" alone aside) given
    // before: "--seed given twice".
    Result<std::string> next();

    // The value of the option next() returned: the argument after it, which it consumes; nothing when
    // there is none or it starts with "--" (a following option, left for next()).
    std::optional<std::string> value();

private:
    int argc_;
    char** argv_;
    int next_;
    std::set<std::string> repeatable_, seen_;
};

} // namespace spatter::cli
