#pragma once
// The small exception hierarchy thrown at file, config and API boundaries.
// Stages map InputError to exit code 2 and NumericalError to exit code 3.
#include <stdexcept>
#include <string>

namespace valve {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input: an unreadable file, a malformed config, a value out of range.
class InputError : public Error {
 public:
  using Error::Error;
};

/// A numerical failure that leaves no usable result (not a mere non-convergence,
/// which is reported as a status).
class NumericalError : public Error {
 public:
  using Error::Error;
};

/// One-line message "<where>: <key>: expected <expected>, found <found>".
/// Empty parts are left out.
std::string describe_problem(const std::string& where, const std::string& key,
                             const std::string& expected, const std::string& found);

/// Shortest decimal text that reads back as exactly `x` ("45", "0.1", "1e-05"; "nan", "inf"),
/// for the values messages and tables show.
std::string format_number(double x);
/// The shortest "%g" text that reads back as exactly x ("1e+12", "2.5e-07"); format_number
/// uses it for numbers that are not whole.
std::string format_shortest_general(double x);

[[noreturn]] void throw_input_error(const std::string& where, const std::string& key,
                                    const std::string& expected, const std::string& found);

}  // namespace valve
