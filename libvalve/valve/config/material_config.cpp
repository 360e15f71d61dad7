#include "valve/config/material_config.hpp"

#include <cstdlib>

#include "valve/core/error.hpp"

#ifndef VALVE_SOURCE_CONFIG_DIR
#define VALVE_SOURCE_CONFIG_DIR "configs"
#endif

namespace valve {
namespace fs = std::filesystem;

namespace {
BilinearCurve parse_curve(JsonReader r) {
  BilinearCurve c;
  c.m1 = r.quantity("m1", Dimension::pressure, std::nullopt, 1e-12, 1e6);
  c.m2 = r.quantity("m2", Dimension::pressure, std::nullopt, 1e-12, 1e6);
  c.lambda_star = r.number("lambda_star", std::nullopt, 1.0, 10.0);
  r.finish();
  return c;
}
}  // namespace

MaterialConfig parse_material(JsonReader& r) {
  MaterialConfig m;
  m.name = r.string("name", std::string("custom"));
  m.source = r.string("source", std::string(""));
  const std::string law = r.choice("law", {"fung", "hgo", "bilinear"}, std::string("fung"));
  if (law == "fung") {
    FungParameters p;
    p.c = r.quantity("c", Dimension::pressure, std::nullopt, 1e-15, 1e3);
    p.A1 = r.number("A1", std::nullopt);
    p.A2 = r.number("A2", std::nullopt);
    p.A3 = r.number("A3", 0.0);
    p.A4 = r.number("A4", 0.0);
    p.A5 = r.number("A5", 0.0);
    p.A6 = r.number("A6", 0.0);
    // The law must be convex at zero strain: the Hessian of Q must be positive definite.
    if (p.A1 <= 0 || p.A2 <= 0 || p.A1 * p.A2 - p.A3 * p.A3 <= 0 || p.A4 < 0)
      r.fail("A1", "A1 > 0, A2 > 0, A1 A2 > A3², A4 >= 0 (a stable Fung law)",
             "A1=" + std::to_string(p.A1) + " A2=" + std::to_string(p.A2) + " A3=" + std::to_string(p.A3) +
                 " A4=" + std::to_string(p.A4));
    m.fung = p;
  }
  if (law == "hgo") {
    HgoParameters p;
    p.C10 = r.quantity("C10", Dimension::pressure, std::nullopt, 1e-15, 1e3);
    p.C01 = r.number("C01", std::nullopt, 1e-9, 1e4);
    p.k1 = r.quantity("k1", Dimension::pressure, std::string("0 MPa"), 0, 1e3);
    p.k2 = r.number("k2", 0.0, 0, 1e4);
    p.kappa = r.number("kappa", 0.0, 0, 1.0 / 3);
    m.hgo = p;
  }
  if (r.has("bilinear") || law == "bilinear") {
    JsonReader b = r.object("bilinear");
    BilinearParameters bp;
    bp.fiber = parse_curve(b.object("fiber"));
    bp.cross = parse_curve(b.object("cross"));
    b.record("fiber", "given");
    r.record("bilinear", b.used());
    m.bilinear_given = bp;
  }
  {
    JsonReader f = r.object("fit");
    m.fit.max_stress = f.quantity("max_stress", Dimension::pressure, std::string("60 kPa"), 1e-9, 1e3);
    m.fit.samples = f.integer("samples", 400, 10, 100000);
    m.fit.measure = f.choice("measure", {"pk2_vs_green", "nominal_vs_stretch"}, std::string("pk2_vs_green")) ==
                            "pk2_vs_green"
                        ? FitMeasure::pk2_vs_green
                        : FitMeasure::nominal_vs_stretch;
    r.record("fit", f.finish());
  }
  if (r.has("thickness")) m.thickness = r.quantity("thickness", Dimension::length, std::nullopt, 1e-6, 100);
  if (r.has("density")) m.density = r.quantity("density", Dimension::density, std::nullopt, 1e-12, 1);
  return m;
}

BilinearParameters MaterialConfig::bilinear() const {
  if (bilinear_given) return *bilinear_given;
  if (!fung && !hgo) throw InputError("material " + name + ": expected a Fung or HGO law or bilinear curves, found neither");
  return fit_bilinear_equibiaxial(*law(), fit);
}

std::shared_ptr<const MaterialLaw> MaterialConfig::law() const {
  if (fung) return std::make_shared<FungLaw>(*fung);
  if (hgo) return std::make_shared<HgoLaw>(*hgo);
  throw InputError("material " + name +
                   ": the membrane FE model needs a constitutive law (law: fung or hgo), found bilinear curves only");
}

fs::path config_directory() {
  if (const char* env = std::getenv("VALVE_CONFIG_DIR"); env && *env) return env;
  return VALVE_SOURCE_CONFIG_DIR;
}

namespace {

// The preset file a string names: "<name>.json" under configs/materials, or a .json path.
fs::path material_file(const std::string& s, const std::string& file, const std::string& where, const fs::path& base_dir) {
  if (s.size() > 5 && s.substr(s.size() - 5) == ".json") return fs::path(s).is_absolute() ? fs::path(s) : base_dir / s;
  const fs::path path = config_directory() / "materials" / (s + ".json");
  if (!fs::exists(path))
    throw_input_error(file, where, "a known material preset (see " + (config_directory() / "materials").string() + ")",
                      "\"" + s + "\"");
  return path;
}

}  // namespace

MaterialConfig load_material(const json& value, const std::string& file, const std::string& where,
                             const fs::path& base_dir, json* used) {
  if (value.is_object() && value.contains("base")) {
    if (!value["base"].is_string())
      throw_input_error(file, where + ".base", "a material preset name or a .json path", describe_json(value["base"]));
    const fs::path path = material_file(value["base"].get<std::string>(), file, where + ".base", base_dir);
    json merged = load_json_file(path);
    json patch = value;
    patch.erase("base");
    merged.merge_patch(patch);
    JsonReader r(merged, file, where);
    MaterialConfig m = parse_material(r);
    json u = r.finish();
    u["base"] = path.string();
    if (used) *used = u;
    return m;
  }
  if (value.is_object()) {
    JsonReader r(value, file, where);
    MaterialConfig m = parse_material(r);
    if (used) *used = r.finish();
    return m;
  }
  if (!value.is_string())
    throw_input_error(file, where, "a material object, a preset name or a .json path", describe_json(value));
  const fs::path path = material_file(value.get<std::string>(), file, where, base_dir);
  const json j = load_json_file(path);
  JsonReader r(j, path.string());
  MaterialConfig m = parse_material(r);
  json u = r.finish();
  u["file"] = path.string();
  if (used) *used = u;
  return m;
}

}  // namespace valve
