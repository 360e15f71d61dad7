#include "valve/scene/scene_config.hpp"

#include <algorithm>
#include <map>
#include <tuple>

#include "valve/core/error.hpp"
#include "valve/core/install_layout.hpp"

namespace valve {
namespace fs = std::filesystem;

std::string to_string(ModelKind m) { return m == ModelKind::mass_spring ? "mass_spring" : "membrane_fe"; }

namespace {

// A path from the scene: relative ones are taken from the scene file's folder.
fs::path resolve(const fs::path& base_dir, const std::string& path) {
  return fs::path(path).is_absolute() ? fs::path(path) : base_dir / path;
}

void parse_bdf2(JsonReader& r, Bdf2Options& o) {
  o.truncation_tolerance = r.quantity("truncation_tolerance", Dimension::length, o.truncation_tolerance, 1e-12, 100);
  o.displacement_tolerance = r.quantity("displacement_tolerance", Dimension::length, o.displacement_tolerance, 1e-15, 10);
  o.relative_residual_tolerance = r.number("relative_residual_tolerance", o.relative_residual_tolerance, 0.0, 1.0);
  o.quiet_steps = r.integer("quiet_steps", o.quiet_steps, 1, 1000000);
  o.settle_window = r.quantity("settle_window", Dimension::time, o.settle_window, 0.0, 1e9);
  o.settle_tolerance = r.quantity("settle_tolerance", Dimension::length, o.settle_tolerance, 1e-12, 100);
  o.initial_step = r.quantity("initial_step", Dimension::time, o.initial_step, 1e-12, 1e6);
  o.min_step = r.quantity("min_step", Dimension::time, o.min_step, 1e-20, 1e6);
  o.max_step = r.quantity("max_step", Dimension::time, o.max_step, 1e-12, 1e9);
  o.min_steps = r.integer("min_steps", o.min_steps, 0, 1000000);
  o.max_steps = r.integer("max_steps", o.max_steps, 1, 2000000000);
  o.max_time = r.quantity("max_time", Dimension::time, o.max_time, 1e-9, 1e15);
  o.max_wall_seconds = r.number("max_wall_seconds", o.max_wall_seconds, 0.001, 1e7);
  o.adaptive = r.boolean("adaptive", o.adaptive);
  o.error_estimate = r.choice("error_estimate", {"step_doubling", "predictor"},
                              std::string(o.error_estimate == ErrorEstimate::predictor ? "predictor" : "step_doubling")) ==
                             "predictor"
                         ? ErrorEstimate::predictor
                         : ErrorEstimate::step_doubling;
  o.linear_solver = parse_linear_solver(
      r.choice("linear_solver", linear_solver_names(), std::string("auto")));
  o.iterative_tolerance = r.number("iterative_tolerance", o.iterative_tolerance, 1e-16, 1e-1);
  o.iterative_max_iterations = r.integer("iterative_max_iterations", o.iterative_max_iterations, 1, 10000000);
}

// trust_radius: a length, or absent for the solver's default, which `default_description` names.
void parse_trust_radius(JsonReader& r, double& trust_radius, const std::string& default_description) {
  if (r.has("trust_radius")) trust_radius = r.quantity("trust_radius", Dimension::length, std::nullopt, 1e-12, 1e12);
  else r.record("trust_radius", default_description);
  r.document("trust_radius", to_string(Dimension::length), default_description);
}

void parse_static(JsonReader& r, StaticOptions& o) {
  o.relative_residual_tolerance = r.number("relative_residual_tolerance", o.relative_residual_tolerance, 1e-16, 1.0);
  o.max_newton_iterations = r.integer("max_newton_iterations", o.max_newton_iterations, 1, 10000000);
  o.initial_increment = r.number("initial_increment", o.initial_increment, 1e-9, 1.0);
  o.initial_pseudo_step = r.number("initial_pseudo_step_ms2", o.initial_pseudo_step, 1e-20, 1e20);
  o.max_strain_increment = r.number("max_strain_increment", o.max_strain_increment, 0.0, 10.0);
  parse_trust_radius(r, o.trust_radius, "2.5% of the bounding-box diagonal");
  o.min_increment = r.number("min_increment", o.min_increment, 1e-15, 1.0);
  o.max_increments = r.integer("max_increments", o.max_increments, 1, 100000000);
  o.max_wall_seconds = r.number("max_wall_seconds", o.max_wall_seconds, 0.001, 1e7);
  o.linear_solver = parse_linear_solver(
      r.choice("linear_solver", linear_solver_names(), std::string("auto")));
  o.iterative_tolerance = r.number("iterative_tolerance", o.iterative_tolerance, 1e-16, 1e-1);
  o.iterative_max_iterations = r.integer("iterative_max_iterations", o.iterative_max_iterations, 1, 10000000);
}

void parse_quasistatic(JsonReader& r, QuasistaticOptions& o, QuasistaticApproach& a) {
  a.dynamic = r.choice("approach", {"newton", "dynamic"}, std::string(a.dynamic ? "dynamic" : "newton")) == "dynamic";
  a.settle_tolerance = r.quantity("approach_settle_tolerance", Dimension::length, a.settle_tolerance, 1e-12, 100.0);
  o.relative_residual_tolerance = r.number("relative_residual_tolerance", o.relative_residual_tolerance, 1e-16, 1.0);
  o.max_iterations = r.integer("max_iterations", o.max_iterations, 1, 10000000);
  o.initial_increment = r.number("initial_increment", o.initial_increment, 1e-9, 1.0);
  o.min_increment = r.number("min_increment", o.min_increment, 1e-15, 1.0);
  o.initial_proximal_step = r.number("initial_proximal_step_ms2", o.initial_proximal_step, 1e-20, 1e20);
  o.proximal_rule = r.choice("proximal_rule", {"step", "gain"},
                             std::string(o.proximal_rule == ProximalStepRule::gain ? "gain" : "step")) == "gain"
                        ? ProximalStepRule::gain
                        : ProximalStepRule::step;
  parse_trust_radius(r, o.trust_radius, "5% of the bounding-box diagonal");
  o.max_wall_seconds = r.number("max_wall_seconds", o.max_wall_seconds, 0.001, 1e7);
  o.linear_solver = parse_linear_solver(r.choice("linear_solver", linear_solver_names(), std::string("auto")));
  o.iterative_tolerance = r.number("iterative_tolerance", o.iterative_tolerance, 1e-16, 1e-1);
  o.forcing = r.choice("forcing", {"adaptive", "fixed"},
                       std::string(o.forcing == NewtonForcing::fixed ? "fixed" : "adaptive")) == "fixed"
                  ? NewtonForcing::fixed
                  : NewtonForcing::adaptive;
}

}  // namespace

json scene_json_with_overrides(const fs::path& scene_file, const CommandLine& cl) {
  json j = load_json_file(scene_file);
  if (!j.is_object()) throw InputError(scene_file.string() + ": expected a JSON object at the top level");
  if (auto v = cl.get("mesh")) j["mesh"] = fs::absolute(*v).string();
  if (auto v = cl.get("model")) j["model"] = *v;
  if (auto v = cl.get("pressure")) {
    if (!j.contains("pressure") || !j["pressure"].is_object()) j["pressure"] = json::object();
    j["pressure"]["value"] = *v;
  }
  if (auto v = cl.get("solver")) {
    if (!j.contains("solver") || !j["solver"].is_object()) j["solver"] = json::object();
    j["solver"]["type"] = *v;
  }
  for (const auto& assignment : cl.get_all("set")) apply_override(j, assignment, scene_file.string());
  return j;
}

SceneConfig parse_scene(const json& j, const std::string& file, const fs::path& base_dir) {
  JsonReader r(j, file);
  SceneConfig sc;
  sc.file = file;
  sc.mesh_path = resolve(base_dir, r.string("mesh"));
  sc.model = r.choice("model", {"mass_spring", "membrane_fe"}) == "mass_spring" ? ModelKind::mass_spring
                                                                                : ModelKind::membrane_fe;
  {
    r.document("mesh", "path", "required");
    r.document("material", "a preset name, a .json path or a material object", "required");
    r.document("material.base", "a preset name or a .json path the object's keys patch (JSON merge patch)", "none");
    json used;
    sc.material = load_material(r.raw("material"), file, "material", base_dir, &used);
    r.record("material", used);
  }
  sc.thickness = r.quantity("thickness", Dimension::length, sc.material.thickness.value_or(sc.thickness), 1e-6, 100);
  r.document("thickness", "", "the material's thickness, else " + format_quantity(SceneConfig().thickness, Dimension::length));
  sc.density = r.quantity("density", Dimension::density, sc.material.density.value_or(sc.density), 1e-15, 1);
  r.document("density", "", "the material's density, else " + format_quantity(SceneConfig().density, Dimension::density));
  if (r.has("pressure")) {
    JsonReader p = r.object("pressure");
    PressureConfig pc;
    pc.value = p.quantity("value", Dimension::pressure, std::nullopt, 0.0, 1e3);
    pc.along_normal = p.choice("direction", {"along_normal", "against_normal"}, std::string("along_normal")) == "along_normal";
    r.record("pressure", p.finish());
    sc.pressure = pc;
  }
  if (r.has("edge_loads")) {
    JsonReader e = r.object("edge_loads");
    EdgeLoadConfig ec;
    ec.stress_x = e.quantity("stress_x", Dimension::pressure, ec.stress_x, 0.0, 1e3);
    ec.stress_y = e.quantity("stress_y", Dimension::pressure, ec.stress_y, 0.0, 1e3);
    r.record("edge_loads", e.finish());
    sc.edge_loads = ec;
  }
  if (r.has("damping")) {
    JsonReader d = r.object("damping");
    DampingConfig dc;
    const std::string type = d.choice("type", {"critical", "mass_proportional"}, std::string("critical"));
    if (type == "critical") {
      dc.mode = DampingTerm::Mode::critical;
      dc.factor = d.number("ratio", dc.factor, 0.0, 1e6);
    } else {
      dc.mode = DampingTerm::Mode::mass_proportional;
      dc.factor = d.quantity("rate", Dimension::rate, std::nullopt, 0.0, 1e12);
    }
    r.record("damping", d.finish());
    sc.damping = dc;
  }
  {
    JsonReader f = r.object("fixed");
    sc.fixed.use_node_roles = f.boolean("node_roles", sc.fixed.use_node_roles);
    sc.fixed.nodes = f.integer_list("nodes", std::vector<int>{});
    sc.fixed.planar = f.boolean("planar", sc.fixed.planar);
    sc.fixed.pin_centre = f.boolean("pin_centre", sc.fixed.pin_centre);
    r.record("fixed", f.finish());
  }
  if (r.has("contact")) {
    JsonReader c = r.object("contact");
    const auto broad_phase = [&c] {
      return parse_broad_phase(c.choice("broad_phase", {"spatial_hash", "sweep_and_prune", "bvh"}, std::string("spatial_hash")));
    };
    // Both distances beyond the contact's reach; the cap on the automatic distance only (a
    // scene that gives the distance needs none).
    const auto detection_fits = [&c](double detection, double cap, double reach, const std::string& reach_name) {
      if (detection != 0 && detection <= reach)
        c.fail("detection", "0 (automatic) or more than " + reach_name, format_quantity(detection, Dimension::length));
      if (cap == 0) return;
      if (detection != 0) c.fail("max_detection", "0 mm when detection is given", format_quantity(cap, Dimension::length));
      if (cap <= reach) c.fail("max_detection", "0 mm or more than " + reach_name, format_quantity(cap, Dimension::length));
    };
    const bool between = c.boolean("between_leaflets", true), self = c.boolean("self", true);
    if (!between && !self) c.fail("self", "true when between_leaflets is false", "false");
    const std::string contact_model = c.choice("model", {"penalty", "barrier", "seed"}, std::string("penalty"));
    if (contact_model == "seed") {
      ContactOptions co;
      co.stiffness = c.quantity("stiffness", Dimension::stiffness, co.stiffness, 1e-12, 1e12);
      co.penetration_stiffness = c.quantity("penetration_stiffness", Dimension::stiffness, co.penetration_stiffness, 1e-12, 1e12);
      co.zone = c.quantity("zone", Dimension::length, co.zone, 1e-9, 1e3);
      co.between_leaflets = between;
      co.self_contact = self;
      co.normal_side_between_leaflets = c.choice("side_between_leaflets", {"normal", "memory"}, std::string("normal")) == "normal";
      co.detection = c.quantity("detection", Dimension::length, co.detection, 0.0, 1e3);
      co.max_detection = c.quantity("max_detection", Dimension::length, co.max_detection, 0.0, 1e3);
      co.broad_phase = broad_phase();
      detection_fits(co.detection, co.max_detection, co.zone, "zone");
      sc.contact = co;
    } else {
      PenaltyContactOptions po;
      po.potential = contact_model == "barrier" ? ContactPotential::barrier : ContactPotential::penalty;
      po.separation = c.quantity("separation", Dimension::length, po.separation, 1e-6, 1e3);
      po.stiffness = c.quantity("stiffness", Dimension::stiffness,
                                po.potential == ContactPotential::barrier ? kDefaultBarrierStiffness : po.stiffness, 1e-12, 1e12);
      if (po.potential == ContactPotential::barrier) po.offset = c.quantity("offset", Dimension::length, po.offset, 0.0, 1e3);
      po.detection = c.quantity("detection", Dimension::length, po.detection, 0.0, 1e3);
      po.max_detection = c.quantity("max_detection", Dimension::length, po.max_detection, 0.0, 1e3);
      po.edge_contact = c.boolean("edges", true);
      po.interior_edges = c.boolean("interior_edges", false);
      if (po.interior_edges && !po.edge_contact) c.fail("interior_edges", "false when edges is false", "true");
      po.between_leaflets = between;
      po.self_contact = self;
      po.broad_phase = broad_phase();
      detection_fits(po.detection, po.max_detection, po.separation + po.offset, "separation plus offset");
      sc.penalty_contact = po;
    }
    r.record("contact", c.finish());
  }
  if (r.has("aortic_root")) {
    JsonReader a = r.object("aortic_root");
    AorticRootConfig ac;
    // Wall properties come from a preset (with its literature source) unless given inline.
    ac.preset = a.string("preset", std::string("aortic_root"));
    const fs::path preset_file = config_directory() / "materials" / (ac.preset + ".json");
    const json preset = load_json_file(preset_file);
    JsonReader pr(preset, preset_file.string(), "");
    const double t_default = pr.quantity("wall_thickness", Dimension::length, std::nullopt, 1e-6, 100);
    const double e_default = pr.quantity("youngs_modulus", Dimension::pressure, std::nullopt, 1e-9, 1e6);
    const std::optional<double> stiffening_default =
        pr.has("stiffening_pressure")
            ? std::optional<double>(pr.quantity("stiffening_pressure", Dimension::pressure, std::nullopt, 1e-9, 1e3))
            : std::nullopt;
    const std::optional<double> stiffness_index_default =
        pr.has("stiffness_index") ? std::optional<double>(pr.number("stiffness_index", 1.0, 1e-3, 1e3)) : std::nullopt;
    ac.source = pr.string("source", std::string(""));
    pr.string("name", std::string(""));
    pr.string("note", std::string(""));
    pr.string("stiffening_source", std::string(""));
    pr.finish();
    ac.wall_thickness = a.quantity("wall_thickness", Dimension::length, t_default, 1e-6, 100);
    a.document("wall_thickness", "", "the preset's");
    ac.youngs_modulus = a.quantity("youngs_modulus", Dimension::pressure, e_default, 1e-9, 1e6);
    a.document("youngs_modulus", "", "the preset's");
    ac.unloaded_diameter_ratio = a.number("unloaded_diameter_ratio", ac.unloaded_diameter_ratio, 0.5, 2.0);
    // "none" turns the preset's stiffening off: the seed's linear tube at every pressure.
    if (a.has("stiffening_pressure") && a.raw("stiffening_pressure") == json("none")) {
      a.record("stiffening_pressure", "none");
    } else if (a.has("stiffening_pressure")) {
      ac.stiffening_pressure = a.quantity("stiffening_pressure", Dimension::pressure, std::nullopt, 1e-9, 1e3);
    } else if (stiffening_default) {
      ac.stiffening_pressure = a.quantity("stiffening_pressure", Dimension::pressure, *stiffening_default, 1e-9, 1e3);
    }
    a.document("stiffening_pressure", "pressure or \"none\"", "the preset's, else none");
    // "continuous": the linear tube's own index at the stiffening pressure (tension and slope
    // continuous there), also over a preset that gives one.
    if (a.has("stiffness_index") && a.raw("stiffness_index") == json("continuous"))
      a.record("stiffness_index", "continuous");
    else if (a.has("stiffness_index") || stiffness_index_default)
      ac.stiffness_index = a.number("stiffness_index", stiffness_index_default.value_or(1.0), 1e-3, 1e3);
    a.document("stiffness_index", "number (β) or \"continuous\"", "the preset's, else continuous");
    ac.pressure = sc.pressure ? a.quantity("pressure", Dimension::pressure, sc.pressure->value, 0.0, 1e3)
                              : a.quantity("pressure", Dimension::pressure, std::nullopt, 0.0, 1e3);
    a.document("pressure", "", "the scene's pressure");
    const auto point = a.number_list("axis_point", std::vector<double>{0, 0, 0});
    const auto dir = a.number_list("axis_direction", std::vector<double>{0, 0, 1});
    if (point.size() != 3) a.fail("axis_point", "[x, y, z] in mm", std::to_string(point.size()) + " numbers");
    if (dir.size() != 3 || Vec3(dir[0], dir[1], dir[2]).norm() == 0)
      a.fail("axis_direction", "a non-zero [x, y, z]", describe_json(a.used().at("axis_direction")));
    ac.axis_point = Vec3(point[0], point[1], point[2]);
    ac.axis_direction = Vec3(dir[0], dir[1], dir[2]).normalized();
    r.record("aortic_root", a.finish());
    sc.aortic_root = ac;
  }
  if (r.has("bending")) {
    JsonReader b = r.object("bending");
    BendingConfig bc;
    bc.modulus = b.quantity("modulus", Dimension::pressure, std::nullopt, 0.0, 1e6);
    bc.thickness = b.quantity("thickness", Dimension::length, sc.thickness, 1e-6, 100);
    b.document("thickness", "", "the scene's thickness");
    r.record("bending", b.finish());
    sc.bending = bc;
  }
  if (r.has("coaptation")) {
    JsonReader c = r.object("coaptation");
    CoaptationOptions& co = sc.coaptation;
    co.gap = c.choice("gap", {"ray", "nearest"}, std::string(to_string(co.gap))) == "nearest" ? GapMeasure::nearest
                                                                                             : GapMeasure::ray;
    co.threshold_mm = c.quantity("threshold", Dimension::length, co.threshold_mm, 1e-6, 100);
    co.free_edge_offset_mm = c.quantity("free_edge_offset", Dimension::length, co.free_edge_offset_mm, 0.0, 1e3);
    co.commissure_margin = c.number("commissure_margin", co.commissure_margin, 0.0, 0.499);
    co.closed_min_height_mm = c.quantity("closed_min_height", Dimension::length, co.closed_min_height_mm, 1e-6, 1e3);
    r.record("coaptation", c.finish());
  }
  if (r.has("chordae")) {
    JsonReader c = r.object("chordae");
    ChordaeConfig cc;
    c.document("file", "path", "required");
    cc.file = resolve(base_dir, c.string("file"));
    cc.law = c.choice("law", {"file", "linear"}, std::string("file")) == "file" ? ChordaeConfig::Law::file
                                                                                : ChordaeConfig::Law::linear;
    cc.youngs_modulus = c.quantity("youngs_modulus", Dimension::pressure, cc.youngs_modulus, 1e-6, 1e6);
    if (c.has("diameter")) cc.diameter = c.quantity("diameter", Dimension::length, std::nullopt, 0.0, 10);
    else c.record("diameter", "each chord's area_mm2, else the chordae file's diameter_mm");
    c.document("diameter", to_string(Dimension::length), "each chord's area_mm2, else the chordae file's diameter_mm");
    cc.snap_tolerance = c.quantity("snap_tolerance", Dimension::length, cc.snap_tolerance, 0.0, 100);
    cc.rest_length_scale = c.number("rest_length_scale", cc.rest_length_scale, 0.2, 5.0);
    cc.types = c.string_list("types", cc.types);
    for (const auto& t : cc.types)
      if (t != "primary" && t != "secondary" && t != "strut") c.fail("types", "a list of primary, secondary, strut", t);
    const std::string chains = c.choice("chains", {"automatic", "nodes", "condensed"}, std::string("automatic"));
    cc.chains = chains == "nodes" ? ChordaeConfig::Chains::nodes
                : chains == "condensed" ? ChordaeConfig::Chains::condensed : ChordaeConfig::Chains::automatic;
    c.document("papillary_tips", "list of [x, y, z] in mm", "as in the chordae file");
    if (c.has("papillary_tips")) {
      const json& tips = c.raw("papillary_tips");
      bool ok = tips.is_array();
      if (ok)
        for (const auto& t : tips) ok = ok && t.is_array() && t.size() == 3 && t[0].is_number() && t[1].is_number() && t[2].is_number();
      if (!ok) c.fail("papillary_tips", "a list of [x, y, z] in mm", describe_json(tips));
      for (const auto& t : tips) cc.papillary_tips.emplace_back(t[0].get<double>(), t[1].get<double>(), t[2].get<double>());
      c.record("papillary_tips", tips);
    }
    r.record("chordae", c.finish());
    sc.chordae = cc;
  }
  if (r.has("annulus_motion")) {
    JsonReader a = r.object("annulus_motion");
    AnnulusMotionConfig ac;
    a.document("closed_mesh", "path", "required");
    ac.closed_mesh = resolve(base_dir, a.string("closed_mesh"));
    ac.register_rigidly = a.boolean("register", ac.register_rigidly);
    ac.correspondence = a.choice("correspondence", {"arc_length", "nodes"}, std::string("arc_length")) == "nodes"
                            ? AnnulusMotionConfig::Correspondence::nodes
                            : AnnulusMotionConfig::Correspondence::arc_length;
    r.record("annulus_motion", a.finish());
    sc.annulus_motion = ac;
  }
  if (r.has("perturbation")) {
    JsonReader p = r.object("perturbation");
    PerturbationConfig pc;
    pc.amplitude = p.quantity("amplitude", Dimension::length, std::nullopt, 0.0, 1.0);
    pc.seed = static_cast<std::uint64_t>(p.integer("seed", static_cast<int>(pc.seed), 0, 2147483647));
    r.record("perturbation", p.finish());
    sc.perturbation = pc;
  }
  if (r.has("leaflet_materials")) {
    // The list inline, or the path of a JSON file holding it (valve-phantom ttv writes the
    // deck's leaflet laws so); paths inside a file are taken from its folder.
    json from_file;
    std::string list_file = file;
    fs::path list_dir = base_dir;
    r.document("leaflet_materials", "list of {leaflets, material, thickness}, or a .json path holding one", "none");
    const json* list_ptr = &r.raw("leaflet_materials");
    if (list_ptr->is_string()) {
      const fs::path path = resolve(base_dir, list_ptr->get<std::string>());
      from_file = load_json_file(path);
      list_file = path.string();
      list_dir = path.parent_path();
      list_ptr = &from_file;
    }
    const json& list = *list_ptr;
    const std::string prefix = list_file == file ? "leaflet_materials" : "";
    if (!list.is_array())
      throw_input_error(list_file, prefix.empty() ? "(top level)" : prefix, "a list of {leaflets, material, thickness}",
                        describe_json(list));
    json used_list = json::array();
    for (size_t k = 0; k < list.size(); ++k) {
      const std::string key = prefix + "[" + std::to_string(k) + "]";
      if (!list[k].is_object()) throw_input_error(list_file, key, "an object {leaflets, material, thickness}", describe_json(list[k]));
      JsonReader e(list[k], list_file, key);
      LeafletMaterialConfig lm;
      lm.leaflets = e.integer_list("leaflets", std::nullopt);
      if (lm.leaflets.empty()) e.fail("leaflets", "a non-empty list of leaflet indices", "[]");
      json used_material;
      if (!e.has("material")) e.fail("material", "a preset name or a material object", "nothing");
      lm.material = load_material(e.raw("material"), list_file, key + ".material", list_dir, &used_material);
      e.record("material", used_material);
      lm.thickness = e.quantity("thickness", Dimension::length, lm.material.thickness.value_or(sc.thickness), 1e-6, 100);
      e.document("thickness", "", "the material's thickness, else the scene's");
      used_list.push_back(e.finish());
      sc.leaflet_materials.push_back(std::move(lm));
    }
    if (list_file != file) used_list = json{{"file", list_file}, {"list", used_list}};
    r.record("leaflet_materials", used_list);
  }
  {
    JsonReader l = r.object("load");
    sc.load_increments = l.number_list("increments", std::vector<double>{1.0});
    if (sc.load_increments.empty()) l.fail("increments", "a non-empty list", "[]");
    for (size_t k = 0; k < sc.load_increments.size(); ++k)
      if (sc.load_increments[k] <= 0 || (k > 0 && sc.load_increments[k] <= sc.load_increments[k - 1]))
        l.fail("increments", "increasing positive load factors", describe_json(l.used().at("increments")));
    r.record("load", l.finish());
  }
  {
    JsonReader s = r.object("solver");
    const std::string type = s.choice("type", {"auto", "bdf2", "static", "quasistatic"}, std::string("auto"));
    sc.solver = type == "auto"          ? SolverKind::automatic
                : type == "bdf2"        ? SolverKind::bdf2
                : type == "quasistatic" ? SolverKind::quasistatic
                                        : SolverKind::static_newton;
    // Contact needs steps that cannot carry surfaces through each other: BDF2's small,
    // time-resolved steps, or the quasi-static solver's collision-bounded line search. The
    // static solver's steps let surfaces cross (penalty_contact.hpp), so "auto" means BDF2
    // and "static" is refused; the seed's contact law has no energy for the quasi-static merit.
    if (sc.contact || sc.penalty_contact) {
      if (sc.solver == SolverKind::static_newton)
        s.fail("type", "bdf2, quasistatic or auto when the scene has contact (static steps let surfaces cross)", "static");
      if (sc.solver == SolverKind::quasistatic && sc.contact)
        s.fail("type", "bdf2 or auto with the seed's contact model (it has no energy)", "quasistatic");
      if (sc.solver == SolverKind::automatic) sc.solver = SolverKind::bdf2;
      // The penalty sees unsigned distances: a pair pushed through within one Newton step
      // stays crossed (46 intersecting pairs on the sample mitral closure, none with the barrier).
      if (sc.solver == SolverKind::quasistatic && sc.penalty_contact &&
          sc.penalty_contact->potential == ContactPotential::penalty)
        sc.warnings.push_back(file + ": solver.type quasistatic with contact.model penalty: sheets may end crossed; "
                              "contact.model barrier keeps them apart");
    }
    // Both option blocks are read (and validated) whichever solver runs, so that a scene
    // can carry both and be switched with --solver.
    JsonReader b = s.object("bdf2");
    parse_bdf2(b, sc.bdf2);
    s.record("bdf2", b.finish());
    JsonReader st = s.object("static");
    parse_static(st, sc.statics);
    s.record("static", st.finish());
    JsonReader q = s.object("quasistatic");
    parse_quasistatic(q, sc.quasistatic, sc.quasistatic_approach);
    s.record("quasistatic", q.finish());
    r.record("solver", s.finish());
  }
  r.document("monitor", "\"all\", \"free_edge_middle\", a node index or a point [x, y, z] in mm", "\"all\"");
  if (r.has("monitor")) {
    const json& m = r.raw("monitor");
    if (m.is_string() && m == "all") {
      sc.monitor.kind = MonitorConfig::Kind::all;
    } else if (m.is_string() && m == "free_edge_middle") {
      sc.monitor.kind = MonitorConfig::Kind::free_edge_middle;
    } else if (m.is_number_integer() && m.get<int>() >= 0) {
      sc.monitor.kind = MonitorConfig::Kind::node;
      sc.monitor.node = m.get<int>();
    } else if (m.is_array() && m.size() == 3 && m[0].is_number() && m[1].is_number() && m[2].is_number()) {
      sc.monitor.kind = MonitorConfig::Kind::nearest_point;
      sc.monitor.point = Vec3(m[0].get<double>(), m[1].get<double>(), m[2].get<double>());
    } else {
      r.fail("monitor", "\"all\", \"free_edge_middle\", a node index or a point [x, y, z] in mm", describe_json(m));
    }
  } else {
    r.record("monitor", "all");
  }
  if (r.has("strain_markers")) {
    JsonReader m = r.object("strain_markers");
    StrainMarkerConfig mc;
    mc.side = m.quantity("side", Dimension::length, mc.side, 1e-6, 1e3);
    mc.seed_rule = m.choice("convergence", {"seed", "solver"}, std::string("seed")) == "seed";
    mc.rule_fraction = m.number("fraction", mc.rule_fraction, 1e-12, 1.0);
    r.record("strain_markers", m.finish());
    sc.strain_markers = mc;
  }
  {
    JsonReader o = r.object("output");
    sc.time_series = o.boolean("time_series", sc.time_series);
    sc.time_series_every = o.integer("every", sc.time_series_every, 1, 1000000);
    r.record("output", o.finish());
  }
  sc.used = r.finish();
  return sc;
}

namespace {

// A scene declaring every block, with the required keys given, for the key table.
json every_block_scene() {
  const json fung = {{"law", "fung"}, {"c", "1 kPa"}, {"A1", 1.0}, {"A2", 1.0}};
  return {{"mesh", "leaflets.vtp"},
          {"model", "membrane_fe"},
          {"material", fung},
          {"pressure", {{"value", "80 mmHg"}}},
          {"edge_loads", json::object()},
          {"damping", json::object()},
          {"fixed", json::object()},
          {"contact", json::object()},
          {"aortic_root", json::object()},
          {"bending", {{"modulus", "1 MPa"}}},
          {"coaptation", json::object()},
          {"chordae", {{"file", "chordae.json"}}},
          {"annulus_motion", {{"closed_mesh", "closed.vtp"}}},
          {"perturbation", {{"amplitude", "1e-6 mm"}}},
          {"leaflet_materials", json::array({{{"leaflets", {0}}, {"material", fung}}})},
          {"load", json::object()},
          {"solver", json::object()},
          {"monitor", "all"},
          {"strain_markers", json::object()},
          {"output", json::object()}};
}

std::vector<KeySpec> keys_read(const json& scene) {
  const std::string file = "(key table)";
  KeySpecRecorder recorder(file);
  parse_scene(scene, file, fs::path("."));
  std::vector<KeySpec> keys;
  for (KeySpec k : recorder.keys()) {
    // A leaflet's material has the keys of `material`; its list's entries are keyed "[]".
    if (k.path.rfind("leaflet_materials[0].material.", 0) == 0) continue;
    const auto index = k.path.find("[0]");
    if (index != std::string::npos) k.path.replace(index, 3, "[]");
    keys.push_back(k);
  }
  return keys;
}

bool same_key(const KeySpec& a, const KeySpec& b) {
  return a.path == b.path && a.type == b.type && a.default_value == b.default_value && a.range == b.range;
}

}  // namespace

std::vector<SceneKeyRow> scene_key_table() {
  const json base = every_block_scene();
  std::vector<SceneKeyRow> rows;
  for (const KeySpec& k : keys_read(base)) rows.push_back({k, ""});
  // Each choice that brings keys or defaults of its own, as the block it replaces.
  const std::vector<std::tuple<std::string, std::string, json>> variants{
      {"material", "law=hgo", {{"law", "hgo"}, {"C10", "1 kPa"}, {"C01", 1.0}}},
      {"material", "law=iso_exponential", {{"law", "iso_exponential"}, {"C0", "1 kPa"}}},
      {"material", "law=bilinear",
       {{"law", "bilinear"},
        {"bilinear",
         {{"fiber", {{"m1", "1 kPa"}, {"m2", "10 kPa"}, {"lambda_star", 1.1}}},
          {"cross", {{"m1", "1 kPa"}, {"m2", "10 kPa"}, {"lambda_star", 1.1}}}}}}},
      {"contact", "model=barrier", {{"model", "barrier"}}},
      {"contact", "model=seed", {{"model", "seed"}}},
      {"damping", "type=mass_proportional", {{"type", "mass_proportional"}, {"rate", "1 1/ms"}}},
  };
  for (const auto& [block, choice, replacement] : variants) {
    json scene = base;
    scene[block] = replacement;
    for (const KeySpec& k : keys_read(scene)) {
      if (k.path != block && k.path.rfind(block + ".", 0) != 0) continue;
      const bool in_base = std::any_of(rows.begin(), rows.end(), [&](const SceneKeyRow& r) {
        return r.applies_when.empty() && same_key(r.key, k);
      });
      if (!in_base) rows.push_back({k, block + "." + choice});
    }
  }
  // Keys of one block together, in the order the parser reads them; a block's variants after it.
  const auto block_of = [](const SceneKeyRow& r) { return r.key.path.substr(0, r.key.path.find_first_of(".[")); };
  std::map<std::string, std::size_t> block_rank;
  for (std::size_t i = 0; i < rows.size(); ++i) block_rank.emplace(block_of(rows[i]), i);
  std::stable_sort(rows.begin(), rows.end(), [&](const SceneKeyRow& a, const SceneKeyRow& b) {
    return block_rank.at(block_of(a)) < block_rank.at(block_of(b));
  });
  return rows;
}

std::string scene_key_table_markdown() {
  auto cell = [](std::string text) {
    for (std::size_t at = 0; (at = text.find('|', at)) != std::string::npos; at += 2) text.replace(at, 1, "\\|");
    return text;
  };
  std::string md = "| key | type | default | range | applies when |\n| --- | --- | --- | --- | --- |\n";
  for (const SceneKeyRow& row : scene_key_table())
    md += "| `" + row.key.path + "` | " + cell(row.key.type) + " | " + cell(row.key.default_value) + " | " +
          cell(row.key.range) + " | " + (row.applies_when.empty() ? "" : "`" + row.applies_when + "`") + " |\n";
  return md;
}

SceneConfig load_scene(const fs::path& file) {
  const json j = load_json_file(file);
  return parse_scene(j, file.string(), file.parent_path());
}

}  // namespace valve
