#pragma once
// Result<T>: a value or an error message. The public API reports failures through this type and
// never throws across module boundaries.

#include <optional>
#include <string>
#include <utility>

namespace spatter {

struct Error {
    std::string message;
};

// Makes an Error; `return fail("...")` converts into any Result<T>.
inline Error fail(std::string message) {
    return Error{std::move(message)};
}

template <class T> class Result {
public:
    Result(T value) : value_(std::move(value)) {}
    Result(Error error) : error_(std::move(error.message)) {}

    bool ok() const { return value_.has_value(); }
    explicit operator bool() const { return ok(); }

    // Precondition: ok(). The caller owns the moved-out value. *r is r.value(), as for std::optional.
    T& value() & { return *value_; }
    const T& value() const& { return *value_; }
    T&& value() && { return std::move(*value_); }
    T& operator*() & { return *value_; }
    const T& operator*() const& { return *value_; }
    T&& operator*() && { return std::move(*value_); }
    T* operator->() { return &*value_; }
    const T* operator->() const { return &*value_; }

    // Empty when ok().
    const std::string& error() const { return error_; }

private:
    std::optional<T> value_;
    std::string error_;
};

// Result of an operation with no value: success, or an error message.
class Status {
public:
    Status() = default;
    Status(Error error) : error_(std::move(error.message)), failed_(true) {}
    bool ok() const { return !failed_; }
    explicit operator bool() const { return ok(); }
    const std::string& error() const { return error_; }

private:
    std::string error_;
    bool failed_ = false;
};

} // namespace spatter
