#include "valve/config/material_config.hpp"

#include <cstdlib>

#include "valve/core/error.hpp"
#include "valve/core/install_layout.hpp"

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
  const std::string law = r.choice("law", {"fung", "hgo", "iso_exponential", "bilinear"}, std::string("fung"));
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
             "A1=" + format_number(p.A1) + " A2=" + format_number(p.A2) + " A3=" + format_number(p.A3) +
                 " A4=" + format_number(p.A4));
    m.fung = p;
  }
  // The invariant laws keep the subroutine's property names; D is Abaqus's bulk compliance.
  auto compressibility = [&](double& D) {
    D = r.quantity("D", Dimension::compliance, std::string("0 1/MPa"), 0, 1e12);
    m.compressible = r.boolean("compressible", false);
    if (m.compressible && D <= 0) r.fail("D", "D > 0 when compressible is true", "0 1/MPa");
  };
  if (law == "hgo") {
    ModifiedHgoParameters p;
    p.C10 = r.quantity("C10", Dimension::pressure, std::nullopt, 1e-15, 1e3);
    compressibility(p.D);
    p.k1 = r.quantity("k1", Dimension::pressure, std::string("0 MPa"), 0, 1e3);
    p.k2 = r.number("k2", 0.0, 0, 1e4);
    p.kappa = r.number("kappa", 0.0, 0, 1.0 / 3);
    p.C01 = r.number("C01", std::nullopt, 1e-9, 1e4);
    m.hgo = p;
  }
  if (law == "iso_exponential") {
    IsotropicExponentialParameters p;
    p.C0 = r.quantity("C0", Dimension::pressure, std::nullopt, 1e-15, 1e3);
    compressibility(p.D);
    p.C1 = r.quantity("C1", Dimension::pressure, std::string("0 MPa"), 0, 1e3);
    p.C2 = r.number("C2", 0.0, 0, 1e4);
    m.iso_exponential = p;
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
  r.document("thickness", to_string(Dimension::length), "none (the scene's default applies)");
  if (r.has("density")) m.density = r.quantity("density", Dimension::density, std::nullopt, 1e-12, 1);
  r.document("density", to_string(Dimension::density), "none (the scene's default applies)");
  return m;
}

BilinearParameters MaterialConfig::bilinear() const {
  if (bilinear_given) return *bilinear_given;
  if (!fung && !hgo && !iso_exponential)
    throw InputError("material " + name + ": expected a constitutive law or bilinear curves, found neither");
  return fit_bilinear_equibiaxial(*law(), fit);
}

std::shared_ptr<const MaterialLaw> MaterialConfig::law() const {
  if (fung) return std::make_shared<FungLaw>(*fung);
  if (hgo) return make_modified_hgo_law(*hgo, compressible);
  if (iso_exponential) return make_isotropic_exponential_law(*iso_exponential, compressible);
  throw InputError("material " + name +
                   ": the membrane FE model needs a constitutive law (law: fung, hgo or iso_exponential), found bilinear "
                   "curves only");
}

std::shared_ptr<const RodLaw> parse_rod_law(JsonReader& r) {
  const std::string law = r.choice("law", {"linear", "ogden"});
  if (law == "linear")
    return std::make_shared<LinearRodLaw>(r.quantity("youngs_modulus", Dimension::pressure, std::nullopt, 1e-9, 1e6));
  OgdenParameters p;
  const json& mu = r.raw("mu");
  const json& alpha = r.raw("alpha");
  auto quantities = [&](const std::string& key, const json& list, Dimension dim, std::size_t max_size) {
    if (!list.is_array() || list.empty() || list.size() > max_size)
      r.fail(key, "a list of 1 to " + std::to_string(max_size) + " quantities like \"1.5 " + accepted_units(dim).front() + "\"",
             describe_json(list));
    std::vector<double> out;
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (!list[k].is_string()) r.fail(key + "[" + std::to_string(k) + "]", "a quantity with its unit", describe_json(list[k]));
      out.push_back(parse_quantity(list[k].get<std::string>(), dim, r.file() + ": " + r.key_path(key + "[" + std::to_string(k) + "]")));
    }
    return out;
  };
  const std::vector<double> mus = quantities("mu", mu, Dimension::pressure, 3);
  if (!alpha.is_array() || alpha.size() != mus.size())
    r.fail("alpha", std::to_string(mus.size()) + " numbers (one per mu)", describe_json(alpha));
  p.terms = static_cast<int>(mus.size());
  double mu0 = 0;
  for (int k = 0; k < p.terms; ++k) {
    if (!alpha[k].is_number() || alpha[k].get<double>() == 0)
      r.fail("alpha[" + std::to_string(k) + "]", "a non-zero number", describe_json(alpha[k]));
    p.mu[k] = mus[k];
    p.alpha[k] = alpha[k].get<double>();
    mu0 += p.mu[k];
    if (p.mu[k] * p.alpha[k] < 0)
      r.fail("mu[" + std::to_string(k) + "]", "mu and alpha of one sign in each term (a stable Ogden law)",
             format_number(p.mu[k]) + " MPa with alpha " + format_number(p.alpha[k]));
  }
  if (mu0 <= 0) r.fail("mu", "a positive initial shear modulus (sum of mu)", format_number(mu0) + " MPa");
  r.record("mu", mu);
  r.record("alpha", alpha);
  if (r.has("D")) {
    r.record("D", r.raw("D"));
    const std::vector<double> D = quantities("D", r.raw("D"), Dimension::compliance, p.terms);
    for (std::size_t k = 0; k < D.size(); ++k) {
      if (D[k] < 0) r.fail("D[" + std::to_string(k) + "]", "D >= 0", format_number(D[k]) + " 1/MPa");
      p.D[k] = D[k];
    }
  }
  return std::make_shared<OgdenRodLaw>(p);
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
