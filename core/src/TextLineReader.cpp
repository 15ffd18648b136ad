#include "TextLineReader.hpp"

#include <cstring>

namespace spatter::detail {

namespace {
constexpr size_t kTextBlockBytes = size_t(1) << 20;
} // namespace

TextLineReader::TextLineReader(std::istream& in) : in_(in), buffer_(kTextBlockBytes) {}

bool TextLineReader::fill() {
    if (atEnd_) return false;
    if (begin_ > 0) { // keep the start of a line cut by the last block
        std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
        end_ -= begin_;
        begin_ = 0;
    }
    if (end_ == buffer_.size()) buffer_.resize(buffer_.size() * 2); // a line longer than the buffer
    in_.read(buffer_.data() + end_, std::streamsize(buffer_.size() - end_));
    const size_t got = size_t(in_.gcount());
    end_ += got;
    if (!in_) atEnd_ = true;
    return got > 0 || !atEnd_;
}

bool TextLineReader::next(std::string_view& line) {
    size_t searched = 0; // bytes of the unread part already known to hold no '\n'
    for (;;) {
        const char* start = buffer_.data() + begin_;
        const size_t unread = end_ - begin_;
        if (const void* nl = std::memchr(start + searched, '\n', unread - searched)) {
            const size_t length = size_t(static_cast<const char*>(nl) - start);
            line = std::string_view(start, length);
            begin_ += length + 1;
            ++lineNumber_;
            return true;
        }
        searched = unread;
        if (!fill()) break;
    }
    if (begin_ == end_) return false;
    line = std::string_view(buffer_.data() + begin_, end_ - begin_);
    begin_ = end_;
    ++lineNumber_;
    return true;
}

} // namespace spatter::detail
