#pragma once
/// \file
/// `Message`: the text of an error, built from strings and numbers.
///
/// Appends to a `std::string`, with `snprintf` for the numbers, rather than
/// streaming into an `std::ostringstream`: every constructor's failure path
/// formats a message, and a string stream is costly to compile into each.
/// Numbers print as a default `std::ostream` prints them: integers in full,
/// floating-point values with `%g` (six significant digits, "inf", "nan").

#include <cstdio>
#include <string>
#include <string_view>
#include <type_traits>

namespace adaptobs::detail {

class Message {
 public:
  Message& operator<<(std::string_view text) {
    text_.append(text);
    return *this;
  }

  Message& operator<<(const char* text) { return *this << std::string_view(text); }

  /// Integers in full, floating-point values with `%g`. `bool` and `char` are not
  /// numbers here (a stream prints a `char` as a character): streaming one does not compile.
  template <typename Number>
    requires std::is_arithmetic_v<Number> && (!std::is_same_v<Number, bool>) && (!std::is_same_v<Number, char>)
  Message& operator<<(Number value) {
    char digits[32];
    int length;
    if constexpr (std::is_floating_point_v<Number>) {
      length = std::snprintf(digits, sizeof digits, "%Lg", static_cast<long double>(value));
    } else if constexpr (std::is_signed_v<Number>) {
      length = std::snprintf(digits, sizeof digits, "%lld", static_cast<long long>(value));
    } else {
      length = std::snprintf(digits, sizeof digits, "%llu", static_cast<unsigned long long>(value));
    }
    text_.append(digits, static_cast<std::size_t>(length));
    return *this;
  }

  [[nodiscard]] const std::string& str() const noexcept { return text_; }

 private:
  std::string text_;
};

}  // namespace adaptobs::detail
