// Error tiers (docs/ARCHITECTURE.md, "Errors"):
//  1. programmer errors: SKYLIGHT_CHECK(cond, msg) -> std::logic_error (a bug in skylight);
//  2. bad user input or bad files: skylight::InvalidArgument / skylight::IoError, whose message
//     names the offending field (or file) and value;
//  3. the CLI turns (2) into one line on stderr and a non-zero exit status.
#pragma once

#include <stdexcept>
#include <string>

namespace skylight {

// A parameter, flag or field value that is out of range, NaN or malformed. The CLI maps it to
// exit status 2. The message always names the field and the offending value.
class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A file that is missing, unreadable, corrupt or cannot be written (exit status 1 in the CLI).
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A fit or training whose result, measured on held-out data, is outside its stated bound: the
// result is not returned (the CLI exits with status 1 and writes nothing). The message says what
// was measured, against which bound, and how to change it.
class FitFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

[[noreturn]] void check_failed(const char* expr, const char* file, int line,
                               const std::string& msg);

}  // namespace skylight

// Internal invariant; failing it is a bug in skylight, never a user error.
#define SKYLIGHT_CHECK(cond, msg)                                            \
  do {                                                                       \
    if (!(cond)) ::skylight::check_failed(#cond, __FILE__, __LINE__, (msg)); \
  } while (false)
