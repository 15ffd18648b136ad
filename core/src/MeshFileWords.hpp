#pragma once
// MeshFileWords: the words and numbers of text mesh files as MeshFileGuard takes them, strictly: a
// number is a whole word, so that "0x10", "1,5" or "3abc" are not read as the 0, 1 or 3 that
// OpenMesh's readers (iostreams) take from their start.

#include <cstdint>
#include <string>
#include <string_view>

namespace spatter::detail {

// Words are separated by the characters isspace takes in the "C" locale.
bool isWordSpace(char c);
// The next word of `rest`, which is advanced past it; empty when none is left.
std::string_view nextWord(std::string_view& rest);
// `text` without the spaces, tabs, CRs and LFs at its ends.
std::string_view trimLine(std::string_view text);

enum class NumberWord {
    Finite,      // a decimal number in the range of float
    NotFinite,   // nan, inf, infinity (any case, signed)
    BeyondFloat, // a decimal number whose magnitude float cannot hold (it would become infinite)
    NotDecimal,  // anything else: hexadecimal, commas, trailing letters, an empty word
};

// Reads a whole word as a float: [+-](digits[.digits]|.digits)[(e|E)[+-]digits]. Magnitudes too
// small for float read as 0 or a denormal, as iostreams read them.
NumberWord readFloatWord(std::string_view word, float& value);
// What is wrong with a word of that kind, for a message: "is not finite" and so on.
const char* numberWordProblem(NumberWord kind);

// Reads a whole word as a decimal integer [+-]digits, saturating at +-2^62 (an index that large is
// past any vertex anyway); false when it is no such word.
bool readIntegerWord(std::string_view word, int64_t& value);

// At most `limit` characters of `word` for a message, with anything unprintable as '?' and "..."
// where it was cut.
std::string excerpt(std::string_view word, size_t limit = 32);

} // namespace spatter::detail
