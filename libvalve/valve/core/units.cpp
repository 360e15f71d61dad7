#include "valve/core/units.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "valve/core/error.hpp"

namespace valve {
namespace {

struct UnitFactor {
  const char* name;
  double factor;  // internal units per one of this unit
};

const std::vector<UnitFactor>& table(Dimension d) {
  static const std::vector<UnitFactor> length{{"mm", 1.0}, {"m", 1e3}, {"cm", 10.0}, {"um", 1e-3}};
  static const std::vector<UnitFactor> pressure{{"MPa", 1.0},       {"kPa", 1e-3},   {"Pa", 1e-6},
                                                {"GPa", 1e3},       {"mmHg", units::mmHg},
                                                {"N/mm^2", 1.0},    {"N/m^2", 1e-6}};
  static const std::vector<UnitFactor> density{
      {"kg/m^3", 1e-6}, {"g/cm^3", 1e-3}, {"g/mm^3", 1.0}};
  static const std::vector<UnitFactor> stiffness{{"N/mm", 1.0}, {"N/m", 1e-3}};
  static const std::vector<UnitFactor> time{{"ms", 1.0}, {"s", 1e3}, {"us", 1e-3}};
  static const std::vector<UnitFactor> force{{"N", 1.0}, {"mN", 1e-3}};
  static const std::vector<UnitFactor> mass{{"g", 1.0}, {"kg", 1e3}, {"mg", 1e-3}};
  static const std::vector<UnitFactor> rate{{"1/ms", 1.0}, {"1/s", 1e-3}};
  static const std::vector<UnitFactor> damping{{"N*ms/mm", 1.0}, {"N*s/m", 1.0}, {"kg/s", 1.0}};
  static const std::vector<UnitFactor> compliance{{"1/MPa", 1.0}, {"1/kPa", 1e3}, {"1/Pa", 1e6}};
  switch (d) {
    case Dimension::length: return length;
    case Dimension::pressure: return pressure;
    case Dimension::density: return density;
    case Dimension::stiffness: return stiffness;
    case Dimension::time: return time;
    case Dimension::force: return force;
    case Dimension::mass: return mass;
    case Dimension::rate: return rate;
    case Dimension::damping: return damping;
    case Dimension::compliance: return compliance;
  }
  return length;
}

std::string trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

}  // namespace

std::string to_string(Dimension d) {
  switch (d) {
    case Dimension::length: return "length";
    case Dimension::pressure: return "pressure";
    case Dimension::density: return "density";
    case Dimension::stiffness: return "stiffness";
    case Dimension::time: return "time";
    case Dimension::force: return "force";
    case Dimension::mass: return "mass";
    case Dimension::rate: return "rate";
    case Dimension::damping: return "damping";
    case Dimension::compliance: return "compliance";
  }
  return "?";
}

std::vector<std::string> accepted_units(Dimension dim) {
  std::vector<std::string> out;
  for (const auto& u : table(dim)) out.emplace_back(u.name);
  return out;
}

std::string internal_unit(Dimension dim) {
  for (const auto& u : table(dim))
    if (u.factor == 1.0) return u.name;
  return "";  // unreachable: every table holds its internal unit
}

std::string format_quantity(double internal_value, Dimension dim) {
  return format_number(internal_value) + " " + internal_unit(dim);
}

double parse_quantity(const std::string& text, Dimension dim, const std::string& where) {
  std::string units_list;
  for (const auto& u : accepted_units(dim)) units_list += (units_list.empty() ? "" : "|") + u;
  const std::string expected = "a " + to_string(dim) + " like \"<number> <" + units_list + ">\"";
  const std::string s = trim(text);
  const char* begin = s.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin || !std::isfinite(value)) throw_input_error(where, "", expected, "\"" + text + "\"");
  const std::string unit = trim(std::string(end));
  if (unit.empty()) throw_input_error(where, "", expected, "a bare number \"" + text + "\"");
  for (const auto& u : table(dim))
    if (unit == u.name) return value * u.factor;
  throw_input_error(where, "", expected, "unit \"" + unit + "\"");
}

}  // namespace valve
