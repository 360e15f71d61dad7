#pragma once
// What a phantom image is made of, whichever valve it comes from: a leaflet mid-surface
// voxelized as a sheet, chordae as tubes, papillary muscles as ellipsoids. Three sources:
// the parametric open mitral valve (mitral_phantom.hpp), a finite element model from an
// Abaqus deck (shell leaflets, truss chordae) and any membrane mesh with optional line
// segments (a simulated closed valve). The description of each is the phantom summary's
// metrics, so that a test of the image can be traced to the geometry it was made from.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "valve/chordae/chordae_network.hpp"
#include "valve/core/progress.hpp"
#include "valve/imaging/volume.hpp"
#include "valve/io/abaqus_inp.hpp"
#include "valve/mesh/tri_mesh.hpp"
#include "valve/phantom/mitral_phantom.hpp"

namespace valve {

struct PhantomGeometry {
  TriMesh leaflets;  ///< mid-surface: the ground truth
  double thickness = 1;  ///< mm, of the voxelized sheet
  std::vector<std::pair<Vec3, Vec3>> chord_segments;
  double chord_diameter = 0.5;  ///< mm, of the voxelized tubes
  std::vector<PapillaryMuscle> papillary;
  std::optional<ChordaeNetwork> chordae;  ///< the network a simulation can take, when the source has one
  nlohmann::json description;  ///< what was built, for the summary's metrics
  nlohmann::json leaflet_materials;  ///< a deck's leaflet laws in a scene's leaflet_materials form; null otherwise

  bool has_leaflet_materials() const { return leaflet_materials.is_array() && !leaflet_materials.empty(); }
};

/// The parametric mitral valve; without chordae, neither tubes, papillary muscles nor a
/// network (the counts in the description are then 0). Thickness and chord diameter are the
/// phantom's own, after its random variation.
PhantomGeometry mitral_phantom_geometry(const MitralPhantomOptions& options, bool with_chordae);

struct ModelPhantomOptions {
  std::string model_file;  ///< the deck, named in messages and the description
  std::string frame_file;  ///< where frame positions come from, if any
  double thickness = 0.65;       ///< mm; the Texas TriValve deck's shell section
  double chord_diameter = 0.65;  ///< mm; its truss sections, 0.27-0.36 mm²
  bool with_chordae = true;
};

/// A finite element valve: the shells (sets Annular_Nodes and Free_Edge_Nodes mark the
/// annulus and free edge) and, with chordae, the trusses as tubes and as a network whose
/// papillary tips are the held truss nodes. A frame with another number of points than the
/// deck's nodes is an InputError naming the frame file. `frame_points` replace the deck's
/// node positions (a frame of the model's motion, one row per node).
PhantomGeometry model_phantom_geometry(AbaqusModel model, const ModelPhantomOptions& options,
                                       const std::optional<MatX3>& frame_points = std::nullopt);

/// Any membrane mesh as a sheet of `thickness`, with `chord_segments` as tubes of
/// `chord_diameter`; `mesh_file` names it in the description.
PhantomGeometry surface_phantom_geometry(TriMesh membrane, std::vector<std::pair<Vec3, Vec3>> chord_segments,
                                         double thickness, double chord_diameter, const std::string& mesh_file);

/// The grid of `spacing` mm covering every part of the phantom with `margin` mm to spare
/// beyond the sheet's half thickness and more: the box is widened by margin + thickness on
/// every side.
ImageGeometry phantom_grid(const PhantomGeometry& phantom, double spacing, double margin);

/// The phantom's partial-volume image on `grid`: `background` outside, `tissue` inside,
/// mixed at the surfaces. Reports to `progress` after the leaflets and after the chordae.
Volume voxelize_phantom(const PhantomGeometry& phantom, const ImageGeometry& grid, double background, double tissue,
                        Progress& progress);

/// The image's file name in its format: NAME.nrrd, NAME.mha, NAME.nii.gz, or the folder
/// NAME.dicom of a DICOM series.
std::string phantom_image_file(const std::string& name, const std::string& format);

/// The summary's metrics: the geometry's description, then the files written into the
/// output folder and the image grid.
nlohmann::json phantom_metrics(const PhantomGeometry& phantom, const ImageGeometry& grid, const std::string& name,
                               const std::string& format);

}  // namespace valve
