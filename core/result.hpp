// Result<T>: a value, or a message saying why there is none. The one way new code returns
// value-or-error (CONTRIBUTING.md): no exceptions, no out-parameters, no bool beside an error().
//
//   Result<Config> parse_config(std::string_view text) {
//       if (text.empty()) return Error{"empty configuration"};
//       return Config{...};
//   }
//   Result<Config> config = parse_config(text);
//   if (!config) return fail(config.error());
//   use(*config);
//
// The message is for a person: it names what failed (the file, the token) and why.
//
// An action that gives nothing but can fail returns Result<void>: `return {};` on success.
#pragma once

#include <cassert>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

namespace dpscope {

// The failure side of a Result; a Result<T> is made from an Error or from a T.
struct Error {
    std::string message;
};

template <typename T>
class [[nodiscard]] Result {
    // What a value is made of: anything T can be constructed from, except an Error or a Result.
    template <typename U>
    static constexpr bool kMakesValue =
        std::is_constructible_v<T, U&&> && !std::is_same_v<std::remove_cvref_t<U>, Error> &&
        !std::is_same_v<std::remove_cvref_t<U>, Result>;

  public:
    // From anything a T can be made of (a T, a std::unique_ptr to a derived class, ...).
    template <typename U = T, std::enable_if_t<kMakesValue<U>, int> = 0>
    Result(U&& value) : value_(std::in_place, std::forward<U>(value)) {}
    Result(Error error) : error_(std::move(error.message)) {}

    bool has_value() const noexcept { return value_.has_value(); }
    explicit operator bool() const noexcept { return has_value(); }

    // The value; only when has_value().
    T& value() & {
        assert(has_value());
        return *value_;
    }
    const T& value() const& {
        assert(has_value());
        return *value_;
    }
    T&& value() && {
        assert(has_value());
        return std::move(*value_);
    }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }
    T&& operator*() && { return std::move(*this).value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }

    // Why there is no value; "" when there is one.
    const std::string& error() const noexcept { return error_; }

  private:
    std::optional<T> value_;
    std::string error_;
};

// Success, or an Error: for an action that gives nothing back (commit a file, configure a port).
template <>
class [[nodiscard]] Result<void> {
  public:
    Result() = default;  // success
    Result(Error error) : error_(std::move(error.message)), failed_(true) {}

    bool has_value() const noexcept { return !failed_; }
    explicit operator bool() const noexcept { return has_value(); }

    // Why it failed; "" when it did not.
    const std::string& error() const noexcept { return error_; }

  private:
    std::string error_;
    bool failed_ = false;
};

}  // namespace dpscope
