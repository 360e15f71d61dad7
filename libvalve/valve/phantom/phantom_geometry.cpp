#include "valve/phantom/phantom_geometry.hpp"

#include "valve/analysis/annulus_targets.hpp"
#include "valve/core/error.hpp"
#include "valve/imaging/voxelize.hpp"

namespace valve {

namespace {
nlohmann::json json_vector(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
}  // namespace

PhantomGeometry mitral_phantom_geometry(const MitralPhantomOptions& options, bool with_chordae) {
  const MitralPhantom ph = make_mitral_phantom(options);
  PhantomGeometry g;
  g.leaflets = ph.leaflets;
  g.thickness = ph.options.thickness;
  g.chord_diameter = ph.chordae.diameter;
  if (with_chordae) {
    for (const auto& s : ph.chordae.segments)
      g.chord_segments.emplace_back(ph.chordae.points[s.from].position, ph.chordae.points[s.to].position);
    g.papillary = {ph.papillary[0], ph.papillary[1]};
    g.chordae = ph.chordae;
  }
  const auto& v = ph.options;
  const auto count = [&](auto what) { return with_chordae ? ph.chordae.count(what) : 0; };
  g.description = {
      {"atrial_direction", json_vector(ph.atrial_direction)},
      {"valve", {{"commissural_diameter_mm", v.commissural_diameter}, {"septal_lateral_diameter_mm", v.septal_lateral_diameter},
                 {"saddle_height_mm", v.saddle_height}, {"anterior_length_mm", v.anterior_length},
                 {"posterior_length_mm", v.posterior_length}, {"thickness_mm", v.thickness}}},
      {"chordae", {{"segments", with_chordae ? int(ph.chordae.segments.size()) : 0},
                   {"primary", count(ChordType::primary)},
                   {"secondary", count(ChordType::secondary)},
                   {"strut", count(ChordType::strut)},
                   {"insertions", count(ChordPointKind::insertion)}}}};
  return g;
}

PhantomGeometry model_phantom_geometry(AbaqusModel model, const ModelPhantomOptions& options,
                                       const std::optional<MatX3>& frame_points) {
  const std::string& inp = options.model_file;
  if (frame_points) {
    if (frame_points->rows() != model.points.rows())
      throw InputError(options.frame_file + ": expected " + std::to_string(model.points.rows()) + " points (one per node of " +
                       inp + "), found " + std::to_string(frame_points->rows()));
    model.points = *frame_points;
  }
  PhantomGeometry g;
  std::vector<int> model_rows;
  g.leaflets = shell_mesh(model, "Annular_Nodes", "Free_Edge_Nodes", &model_rows);
  g.thickness = options.thickness;
  g.chord_diameter = options.chord_diameter;
  const auto lines = line_elements(model);
  double tip_motion = 0;
  if (options.with_chordae && !lines.empty()) g.chordae = truss_chordae(model, model_rows, g.leaflets, inp, &tip_motion);
  g.leaflet_materials = leaflet_materials_json(model, inp);
  if (options.with_chordae)
    for (const auto& [a, b] : lines) g.chord_segments.emplace_back(model.points.row(a).transpose(), model.points.row(b).transpose());
  int annulus = 0, free_edge = 0;
  for (BoundaryType b : g.leaflets.boundary) annulus += b == BoundaryType::attached, free_edge += b == BoundaryType::free_edge;
  g.description = {{"model", inp},
                   {"atrial_direction", json_vector(annulus_atrial_direction(g.leaflets))},
                   {"frame", frame_points ? options.frame_file : std::string("(the .inp coordinates)")},
                   {"leaflet_nodes", g.leaflets.num_nodes()},
                   {"annulus_nodes", annulus},
                   {"free_edge_nodes", free_edge},
                   {"chordae", {{"segments", options.with_chordae ? int(lines.size()) : 0}}}};
  if (g.chordae) {
    const ChordaeNetwork& net = *g.chordae;
    nlohmann::json& c = g.description["chordae"];
    c["papillary_tips"] = net.count(ChordPointKind::papillary_tip);
    c["branch_points"] = net.count(ChordPointKind::branch);
    c["insertions"] = net.count(ChordPointKind::insertion);
    c["primary"] = net.count(ChordType::primary);
    c["secondary"] = net.count(ChordType::secondary);
    c["diameter_mm"] = net.diameter;
    c["papillary_tip_motion_not_applied_mm"] = tip_motion;
  }
  return g;
}

PhantomGeometry surface_phantom_geometry(TriMesh membrane, std::vector<std::pair<Vec3, Vec3>> chord_segments,
                                         double thickness, double chord_diameter, const std::string& mesh_file) {
  PhantomGeometry g;
  g.leaflets = std::move(membrane);
  g.thickness = thickness;
  g.chord_diameter = chord_diameter;
  g.chord_segments = std::move(chord_segments);
  g.description = {{"mesh", mesh_file},
                   {"atrial_direction", json_vector(annulus_atrial_direction(g.leaflets))},
                   {"leaflet_nodes", g.leaflets.num_nodes()},
                   {"chordae", {{"segments", int(g.chord_segments.size())}}}};
  return g;
}

ImageGeometry phantom_grid(const PhantomGeometry& phantom, double spacing, double margin) {
  Vec3 lo = phantom.leaflets.points.colwise().minCoeff().transpose();
  Vec3 hi = phantom.leaflets.points.colwise().maxCoeff().transpose();
  for (const auto& [a, b] : phantom.chord_segments) lo = lo.cwiseMin(a).cwiseMin(b), hi = hi.cwiseMax(a).cwiseMax(b);
  for (const auto& pm : phantom.papillary) {
    lo = lo.cwiseMin(pm.centre - pm.semi_axes);
    hi = hi.cwiseMax(pm.centre + pm.semi_axes);
  }
  const Vec3 pad = Vec3::Constant(margin + phantom.thickness);
  return grid_covering(lo - pad, hi + pad, spacing);
}

Volume voxelize_phantom(const PhantomGeometry& phantom, const ImageGeometry& grid, double background, double tissue,
                        Progress& progress) {
  Voxelizer vox(grid);
  vox.add_sheet(phantom.leaflets.points, phantom.leaflets.triangles, phantom.thickness);
  progress.update(0.5, "leaflets voxelized");
  if (!phantom.chord_segments.empty()) vox.add_tubes(phantom.chord_segments, phantom.chord_diameter);
  for (const auto& pm : phantom.papillary) vox.add_ellipsoid(pm.centre, pm.semi_axes);
  progress.update(0.8, "chordae voxelized");
  return vox.to_volume(static_cast<float>(background), static_cast<float>(tissue));
}

std::string phantom_image_file(const std::string& name, const std::string& format) {
  if (format == "mha") return name + ".mha";
  if (format == "nii") return name + ".nii.gz";
  if (format == "dicom") return name + ".dicom";
  return name + ".nrrd";
}

nlohmann::json phantom_metrics(const PhantomGeometry& phantom, const ImageGeometry& grid, const std::string& name,
                               const std::string& format) {
  nlohmann::json m = phantom.description;
  m["image"] = phantom_image_file(name, format);
  m["truth"] = name + ".truth.vtp";
  m["size"] = {grid.size[0], grid.size[1], grid.size[2]};
  m["spacing_mm"] = grid.spacing.x();
  m["origin_mm"] = json_vector(grid.origin);
  m["truth_triangles"] = phantom.leaflets.num_triangles();
  if (phantom.chordae) m["chordae_file"] = name + ".chordae.json";
  if (phantom.has_leaflet_materials()) m["leaflet_materials_file"] = name + ".leaflet_materials.json";
  return m;
}

}  // namespace valve
