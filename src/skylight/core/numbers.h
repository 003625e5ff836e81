// The one strict number parser of the project, used for command-line flags, environment variables,
// CSV fields and file headers, and the bounded excerpts that error messages quote.
//
// A number is the whole text: an optional sign, decimal digits with an optional point and an
// optional exponent ("-1.5e-3", "+2", ".5", "5."). Rejected: empty text, surrounding spaces,
// trailing characters ("1e", "5x"), hexadecimal ("0x10"), "inf"/"nan" words and values that
// overflow to infinity (|x| > DBL_MAX) or underflow to zero from a non-zero literal ("1e-400").
// Subnormal values are accepted ("1e-310", "4.9e-324").
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace skylight {

// The finite value of `text`, or nullopt if it is not a number under the rules above.
std::optional<double> parse_number(std::string_view text);
// A whole decimal integer (optional sign, digits only), or nullopt (also when out of range).
std::optional<long long> parse_integer(std::string_view text);

// Why `text` is not a number under the rules above, as a message's predicate: "is not a number",
// "overflows (the largest number is 1.8e+308)" or "underflows to 0 (the smallest non-zero number is
// 4.94e-324)"; every reader of numbers in user files words its error with it, so that "1e-400" is
// never called "not a finite number".
std::string number_problem(std::string_view text);

// The same, throwing InvalidArgument "<what>: '<excerpt>' <number_problem>" (or "is not an
// integer"); `what` names the flag, field or file position.
double parse_number(std::string_view text, std::string_view what);
long long parse_integer(std::string_view text, std::string_view what);
// Comma-separated numbers ("1,2.5,3"); every element must be a number (an empty element, as in
// "1,,2" or "1,2,", is an error naming its position).
std::vector<double> parse_number_list(std::string_view text, std::string_view what);

// `text` without leading and trailing spaces, tabs and carriage returns (CSV fields).
std::string_view trim(std::string_view text);

// A bounded excerpt of untrusted text for error messages: at most `max_chars` characters (then
// "..." and the total length), control characters, quotes, backslashes and bytes >= 0x7f escaped
// as \n, \t, \r, \\, \' or \xHH, so a message is always one printable line.
std::string excerpt(std::string_view text, std::size_t max_chars = 64);

}  // namespace skylight
