#pragma once
// Physical quantities given as strings ("120 mmHg", "2.3 MPa", "0.5 mm").
//
// Internal unit system (consistent, used everywhere inside libvalve):
//   length mm, mass g, time ms  =>  force N, stress/pressure MPa (N/mm^2),
//   energy mJ (N mm), density g/mm^3, stiffness N/mm, damping N ms/mm.
// Example: 1060 kg/m^3 = 1.06e-3 g/mm^3; 80 mmHg = 0.0106658 MPa; 10 N/m = 0.01 N/mm.
#include <string>
#include <vector>

namespace valve {

enum class Dimension {
  length,
  pressure,   // also stress and elastic moduli
  density,
  stiffness,  // force per length (springs, contact)
  time,
  force,
  mass,
  rate,       // 1/time
  damping,    // force per velocity
  compliance, // 1/pressure (Abaqus's bulk compliance D)
};

std::string to_string(Dimension d);

/// Parses "<number> <unit>" into internal units. Throws InputError naming `where`
/// when the unit is missing, unknown, or of another dimension.
double parse_quantity(const std::string& text, Dimension dim, const std::string& where);

/// Units accepted for a dimension, for error messages and docs.
std::vector<std::string> accepted_units(Dimension dim);

/// The internal unit of a dimension, as parse_quantity accepts it: "mm", "MPa", "g/mm^3".
std::string internal_unit(Dimension dim);

/// A value in internal units as text that parse_quantity reads back exactly: "0.65 mm".
std::string format_quantity(double internal_value, Dimension dim);

namespace units {
constexpr double mmHg = 133.322387415e-6;  // MPa
constexpr double kPa = 1e-3;               // MPa
constexpr double Pa = 1e-6;                // MPa
constexpr double kg_per_m3 = 1e-6;         // g/mm^3
}  // namespace units

}  // namespace valve
