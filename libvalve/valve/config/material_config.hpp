#pragma once
// Leaflet material description: a Fung law (seed Eq. 3.1-3.3), or one of the two laws of the
// Texas TriValve deck's subroutine (invariant_membrane_law.hpp: "iso_exponential" for its
// VUANISO_ISO branch, "hgo" for VUANISO_HGO; incompressible unless "compressible": true),
// and the bilinear curves the mass-spring model uses, either fitted from that law or given
// directly (Table 5.1). Chordae laws (rod_law.hpp) are read by parse_rod_law.
// Presets live in configs/materials/<name>.json with their literature source.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "valve/config/json_reader.hpp"
#include "valve/material/bilinear_fit.hpp"
#include "valve/material/invariant_membrane_law.hpp"
#include "valve/material/material_law.hpp"
#include "valve/material/rod_law.hpp"

namespace valve {

struct MaterialConfig {
  std::string name;
  std::string source;              // literature source of the values
  std::optional<FungParameters> fung;
  std::optional<ModifiedHgoParameters> hgo;
  std::optional<IsotropicExponentialParameters> iso_exponential;
  bool compressible = false;       // the invariant laws' (J − 1)²/D term, plane stress S33 = 0
  std::optional<BilinearParameters> bilinear_given;  // used as is by the mass-spring model
  BilinearFitOptions fit;          // used when the bilinear curves are fitted from the law
  std::optional<double> thickness; // mm
  std::optional<double> density;   // g/mm³

  /// The bilinear curves for the mass-spring model (given, or fitted from the law).
  BilinearParameters bilinear() const;
  std::shared_ptr<const MaterialLaw> law() const;  // throws if only bilinear curves are given
};

/// Parses a material object (inline in a scene or a preset file).
MaterialConfig parse_material(JsonReader& r);

/// Parses a chord law: {"law": "linear", "youngs_modulus": "40 MPa"} or
/// {"law": "ogden", "mu": ["18.9 MPa", ...], "alpha": [98.3, ...], "D": ["3.3e-5 1/MPa", ...]}
/// (Abaqus's *Hyperelastic, OGDEN: N = 1..3 terms; D may be shorter, missing terms are 0).
std::shared_ptr<const RodLaw> parse_rod_law(JsonReader& r);

/// Loads a material from a value that is an object, a preset name or a .json path
/// (relative paths are taken from `base_dir`). `where` names the key for messages.
/// An object with "base" (a preset name or .json path) starts from that material and
/// overrides it key by key (JSON merge patch), so a study can vary one parameter of a
/// preset: {"base": "mitral_leaflet_table51", "bilinear": {"fiber": {"m1": "0.0116 MPa"}}}.
MaterialConfig load_material(const json& value, const std::string& file, const std::string& where,
                             const std::filesystem::path& base_dir, json* used);

}  // namespace valve
