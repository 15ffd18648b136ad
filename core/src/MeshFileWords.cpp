#include "MeshFileWords.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace spatter::detail {

namespace {

bool isDigit(char c) {
    return c >= '0' && c <= '9';
}

char lowerAscii(char c) {
    return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c;
}

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (lowerAscii(a[i]) != lowerAscii(b[i])) return false;
    return true;
}

bool namesNonFinite(std::string_view word) {
    if (!word.empty() && (word[0] == '+' || word[0] == '-')) word.remove_prefix(1);
    if (word.size() > 3 && lowerAscii(word[0]) == 'n' && word[3] == '(') word = word.substr(0, 3); // nan(...)
    return equalsIgnoringCase(word, "nan") || equalsIgnoringCase(word, "inf") ||
           equalsIgnoringCase(word, "infinity");
}

// The parts of a decimal number; false when `word` is not one.
struct DecimalParts {
    std::string_view integer, fraction; // the digits before and after the point
    int64_t exponent = 0;               // saturated at +-10^12
};

bool splitDecimal(std::string_view word, DecimalParts& parts) {
    size_t i = 0;
    auto digits = [&] {
        const size_t start = i;
        while (i < word.size() && isDigit(word[i]))
            ++i;
        return word.substr(start, i - start);
    };
    if (i < word.size() && (word[i] == '+' || word[i] == '-')) ++i;
    parts.integer = digits();
    if (i < word.size() && word[i] == '.') {
        ++i;
        parts.fraction = digits();
    }
    if (parts.integer.empty() && parts.fraction.empty()) return false;
    if (i < word.size() && (word[i] == 'e' || word[i] == 'E')) {
        ++i;
        const bool negative = i < word.size() && word[i] == '-';
        if (i < word.size() && (word[i] == '+' || word[i] == '-')) ++i;
        const std::string_view e = digits();
        if (e.empty()) return false;
        for (char c : e)
            parts.exponent = std::min<int64_t>(parts.exponent * 10 + (c - '0'), 1000000000000);
        if (negative) parts.exponent = -parts.exponent;
    }
    return i == word.size();
}

// Whether a decimal number too large or too small for float is too large (its magnitude is >= 1).
bool atLeastOne(const DecimalParts& parts) {
    const size_t integerStart = parts.integer.find_first_not_of('0');
    if (integerStart != std::string_view::npos) // the first digit stands at 10^(digits - 1)
        return int64_t(parts.integer.size() - integerStart) - 1 + parts.exponent >= 0;
    const size_t fractionStart = parts.fraction.find_first_not_of('0');
    if (fractionStart == std::string_view::npos) return false; // zero
    return -int64_t(fractionStart) - 1 + parts.exponent >= 0;
}

} // namespace

bool isWordSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
}

std::string_view nextWord(std::string_view& rest) {
    size_t start = 0;
    while (start < rest.size() && isWordSpace(rest[start]))
        ++start;
    size_t end = start;
    while (end < rest.size() && !isWordSpace(rest[end]))
        ++end;
    const std::string_view word = rest.substr(start, end - start);
    rest.remove_prefix(end);
    return word;
}

std::string_view trimLine(std::string_view text) {
    const size_t first = text.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) return {};
    return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

NumberWord readFloatWord(std::string_view word, float& value) {
    DecimalParts parts;
    if (!splitDecimal(word, parts))
        return namesNonFinite(word) ? NumberWord::NotFinite : NumberWord::NotDecimal;
    const char* first = word.data() + (word[0] == '+' ? 1 : 0); // from_chars takes no '+'
    const std::from_chars_result r = std::from_chars(first, word.data() + word.size(), value);
    if (r.ec == std::errc::result_out_of_range) { // too large, or too small (which iostreams take as 0)
        if (atLeastOne(parts)) return NumberWord::BeyondFloat;
        value = word[0] == '-' ? -0.0f : 0.0f;
        return NumberWord::Finite;
    }
    return r.ec == std::errc() && std::isfinite(value) ? NumberWord::Finite : NumberWord::BeyondFloat;
}

const char* numberWordProblem(NumberWord kind) {
    switch (kind) {
    case NumberWord::Finite:
        break;
    case NumberWord::NotFinite:
        return "is not finite";
    case NumberWord::BeyondFloat:
        return "is not finite in single precision (beyond 3.4e38)";
    case NumberWord::NotDecimal:
        return "is not a decimal number";
    }
    return "is a number";
}

bool readIntegerWord(std::string_view word, int64_t& value) {
    size_t i = word.size() > 0 && (word[0] == '+' || word[0] == '-') ? 1 : 0;
    if (i == word.size()) return false;
    constexpr int64_t kLimit = int64_t(1) << 62;
    int64_t magnitude = 0;
    for (; i < word.size(); ++i) {
        if (!isDigit(word[i])) return false;
        magnitude = magnitude >= kLimit / 10 ? kLimit : magnitude * 10 + (word[i] - '0');
    }
    value = word[0] == '-' ? -magnitude : magnitude;
    return true;
}

std::string excerpt(std::string_view word, size_t limit) {
    std::string out;
    for (size_t i = 0; i < word.size() && i < limit; ++i) {
        const unsigned char c = static_cast<unsigned char>(word[i]);
        out += c >= 0x20 && c < 0x7f ? char(c) : '?';
    }
    if (word.size() > limit) out += "...";
    return out;
}

} // namespace spatter::detail
