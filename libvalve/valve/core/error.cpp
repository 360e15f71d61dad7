#include "valve/core/error.hpp"

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

void throw_input_error(const std::string& where, const std::string& key,
                       const std::string& expected, const std::string& found) {
  throw InputError(describe_problem(where, key, expected, found));
}

}  // namespace valve
