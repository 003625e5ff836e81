#include "skylight/core/numbers.h"

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <system_error>

#include "skylight/core/error.h"

namespace skylight {
namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// The grammar above, checked before from_chars (which would accept "inf", "nan" and a leading
// "0x" as "0" followed by garbage): [+-]? (d+ .? d* | . d+) ([eE] [+-]? d+)?
bool is_decimal_literal(std::string_view s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  std::size_t digits = 0;
  while (i < s.size() && is_digit(s[i])) ++i, ++digits;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && is_digit(s[i])) ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    std::size_t exponent_digits = 0;
    while (i < s.size() && is_digit(s[i])) ++i, ++exponent_digits;
    if (exponent_digits == 0) return false;
  }
  return i == s.size();
}

}  // namespace

std::optional<double> parse_number(std::string_view text) {
  if (!is_decimal_literal(text)) return std::nullopt;
  std::string_view s = text;
  if (s.front() == '+') s.remove_prefix(1);  // from_chars takes no '+'
  double v = 0.0;
#if defined(__EMSCRIPTEN__)
  // The viewer's WebAssembly build (web/): Emscripten's libc++ has no floating-point from_chars;
  // strtod on the literal checked above, ERANGE for overflow and underflow as result_out_of_range.
  const std::string literal(s);
  char* end = nullptr;
  errno = 0;
  v = std::strtod(literal.c_str(), &end);
  if (errno == ERANGE || end != literal.c_str() + literal.size() || !std::isfinite(v)) {
    return std::nullopt;
  }
#else
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  // result_out_of_range: overflow, or a non-zero literal that underflows to 0.
  if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
#endif
  return v;
}

std::optional<long long> parse_integer(std::string_view text) {
  std::string_view s = text;
  const bool plus = !s.empty() && s.front() == '+';
  if (plus) s.remove_prefix(1);
  const bool minus = !plus && !s.empty() && s.front() == '-';
  if (s.size() <= (minus ? 1u : 0u) || !is_digit(s[minus ? 1 : 0])) return std::nullopt;
  long long v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

std::string number_problem(std::string_view text) {
  if (!is_decimal_literal(text)) return "is not a number";
  // A number, but not one a double holds: too large, or non-zero and too small.
  const double magnitude = std::strtod(std::string(text).c_str(), nullptr);
  return std::isinf(magnitude) || std::abs(magnitude) > 1.0
             ? fmt::format("overflows (the largest number is {:.3g})",
                           std::numeric_limits<double>::max())
             : fmt::format("underflows to 0 (the smallest non-zero number is {:.3g})",
                           std::numeric_limits<double>::denorm_min());
}

double parse_number(std::string_view text, std::string_view what) {
  const auto v = parse_number(text);
  if (v) return *v;
  throw InvalidArgument(fmt::format("{}: '{}' {}", what, excerpt(text), number_problem(text)));
}

long long parse_integer(std::string_view text, std::string_view what) {
  const auto v = parse_integer(text);
  if (!v) throw InvalidArgument(fmt::format("{}: '{}' is not an integer", what, excerpt(text)));
  return *v;
}

std::vector<double> parse_number_list(std::string_view text, std::string_view what) {
  std::vector<double> out;
  std::size_t start = 0;
  for (int index = 1;; ++index) {
    const std::size_t comma = text.find(',', start);
    const std::string_view item = text.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    if (item.empty())
      throw InvalidArgument(
          fmt::format("{}: element {} of '{}' is empty", what, index, excerpt(text)));
    out.push_back(parse_number(item, fmt::format("{} (element {})", what, index)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

std::string_view trim(std::string_view s) {
  auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

std::string excerpt(std::string_view text, std::size_t max_chars) {
  std::string out;
  const std::size_t n = std::min(text.size(), max_chars);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    switch (c) {
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\'':
        out += "\\'";
        break;
      default:
        if (c < 0x20 || c >= 0x7f)
          out += fmt::format("\\x{:02x}", c);
        else
          out += static_cast<char>(c);
    }
  }
  if (text.size() > max_chars) out += fmt::format("... ({} characters)", text.size());
  return out;
}

}  // namespace skylight
