#pragma once
// TextLineReader: the lines of a stream, read in large blocks and handed out as views into one
// buffer, so that a check of a large text file neither allocates per line nor parses through
// iostreams. A line ends at '\n' (not included); the last line need not end with one.

#include <cstddef>
#include <istream>
#include <string_view>
#include <vector>

namespace spatter::detail {

class TextLineReader {
public:
    explicit TextLineReader(std::istream& in);

    // The next line, valid until the following call; false after the last line.
    bool next(std::string_view& line);
    // The number (from 1) of the line `next` gave last.
    size_t lineNumber() const { return lineNumber_; }

private:
    bool fill(); // reads more of the stream behind the unread bytes; false at its end

    std::istream& in_;
    std::vector<char> buffer_;
    size_t begin_ = 0, end_ = 0; // the unread bytes of buffer_
    size_t lineNumber_ = 0;
    bool atEnd_ = false;
};

} // namespace spatter::detail
