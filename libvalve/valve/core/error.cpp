#include "valve/core/error.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace valve {

std::string describe_problem(const std::string& where, const std::string& key,
                             const std::string& expected, const std::string& found) {
  std::string msg = where;
  auto append = [&msg](const std::string& part) {
    if (part.empty()) return;
    if (!msg.empty()) msg += ": ";
    msg += part;
  };
  append(key);
  std::string detail;
  if (!expected.empty()) detail = "expected " + expected;
  if (!found.empty()) detail += (detail.empty() ? "found " : ", found ") + found;
  append(detail);
  // One line only: a multi-line message would break log parsing and the exit-2 contract.
  for (char& c : msg)
    if (c == '\n' || c == '\r') c = ' ';
  return msg;
}

std::string format_number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (x == std::floor(x) && std::fabs(x) < 1e15) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", x == 0 ? 0.0 : x);  // no "-0"
    return buf;
  }
  return format_shortest_general(x);
}

std::string format_shortest_general(double x) {
  char buf[40];
  for (int p = 1; p <= 17; ++p) {
    std::snprintf(buf, sizeof buf, "%.*g", p, x);
    if (std::strtod(buf, nullptr) == x) break;
  }
  return buf;
}

void throw_input_error(const std::string& where, const std::string& key,
                       const std::string& expected, const std::string& found) {
  throw InputError(describe_problem(where, key, expected, found));
}

}  // namespace valve
