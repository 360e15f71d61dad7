#pragma once
// Coaptation of a closed valve (seed 4.2.5): where adjacent leaflets touch, how much area
// they share and how far the contact strip reaches down from each free edge.
//
// Gap, measured one of two ways (CoaptationOptions::gap):
// - ray (the seed's 4.2.5): from every node a ray is cast along +n and −n, n being the
//   area-weighted normal of the deformed mesh over the node's own leaflet (other leaflets'
//   triangles would tilt n at a commissure); the gap is the distance to the nearest hit on a
//   triangle of ANOTHER leaflet. Both directions are cast because leaflet windings need not
//   agree on which side faces the neighbour.
// - nearest: the distance from the node to the nearest point of another leaflet's surface.
//   Why: a ray is a line of zero width and skims past a neighbour whose border lies a
//   fraction of a millimetre beside it. Two free edges pressed side by side at slightly
//   different heights are the common case: in the closed three-leaflet valve (FE, fibers at
//   25°, mesh seed 1) 17 of the 33 free-edge nodes lie 0.23-0.40 mm from another leaflet
//   (penalty contact holds them 0.25 mm apart) while their rays hit nothing (13) or land
//   more than 0.5 mm away (4), and the ray measure finds 8-50 % of each free edge coapting
//   where the nearest measure finds 83-100 %. The leaflets are sheets of the threshold's
//   thickness (0.5 mm) drawn as their mid-surfaces, so mid-surfaces nearer than that touch,
//   at whatever angle they meet. The price: the coapting
//   region extends past a neighbour's border by sqrt(threshold² − gap²) (0.43 mm at the
//   contact's 0.25 mm), which adds a rim to the area.
// A node shared by two leaflets (commissure corner) is in contact by construction: gap 0,
// but it takes no part in the heights (its normal is undefined and it would connect the
// contact regions of two leaflets).
//
// Coapting node: gap <= threshold (seed: 0.5 mm; contact keeps the leaflets a zone width
// apart, so touching leaflets show a small positive gap, not 0).
//
// Area. A_L = Σ_{t in L} area_deformed(t) · (number of coapting nodes of t) / 3, i.e. the
// integral over the deformed leaflet of the piecewise-linear interpolant of the coapting
// indicator. Counting only fully coapting triangles would bias the area low by about one
// row of triangles along the whole contact border; the interpolant places the border, on
// average, half way between a coapting and a non-coapting node.
//
// Heights, along the leaflet's columns (leaflet_columns.hpp: material lines from each point
// of the free edge straight down the rest leaflet). Down a column, c = the coapting
// indicator of the unshared nodes, interpolated linearly over the triangles (the same
// interpolant as the area, so a band's border lies, on average, half way between a coapting
// and a non-coapting node); ℓ = deformed length along the column from the free edge:
//   top(s) = the first ℓ where c reaches 0.5   (band only if top(s) ≤ free_edge_offset_mm)
//   h(s)   = the next ℓ where c drops below 0.5 (or the column's end) − top(s)
// (0 without a band). Where the free edge itself coapts, top(s) = 0 and h(s) is the depth
// of the strip that hangs from it. The offset admits a strip whose top lies a little below a
// free edge that flares apart (the closed three-leaflet valve: free edges stretched from 20.9
// to 26-28 mm fold up at the centre, and the contact band begins one row of triangles,
// 1.6-2 mm, below them), while contact patches further down (a belly touching a neighbour)
// stay out of the height. Columns are sampled every 1/200 of the free edge's rest length,
// and at both margins and the middle.
// Why lines rather than sets of nodes (each node in the column of its nearest free-edge
// node): on the aortic valve's unstructured mesh some free-edge nodes are the nearest of no
// other node, so such columns read 0 whatever coapted below them; see leaflet_columns.hpp.
//
// Reach of the free edges (given the valve axis). In a sealed three-leaflet valve the free
// edges meet on the axis; a free edge that stops short of it leaves a hole at the centre,
// whatever the bands beside it do (the projected orifice, orifice.hpp, measures that hole's
// area). free_edge_axis_distance_mm is the closest approach of a leaflet's deformed free
// edge (the polyline of its nodes) to the axis; the nodes alone would read up to half a
// free-edge segment (about 1 mm on the 666-triangle valve) too far. Why a separate measure: the
// heights say where a band is broken, not how far the leaflet is from closing the hole, which
// is what changes between repairs and between solver settings.
//
// Minimum height: the minimum of h over the columns whose rest arc length from either end
// of the free edge is at least commissure_margin × the free edge's rest length:
// at the commissures the strip shrinks to nothing by anatomy, not because of a bad
// closure, so the ends are excluded. A leaflet is closed when that minimum is at least
// closed_min_height_mm (0.5 mm, the leaflet's thickness): its coaptation strip runs along the
// whole free edge between the margins and is nowhere pinched thinner than the leaflet.
// Why not > 0: heights along interpolated columns are continuous, so a band pinched to a
// point reads from rounding (1e-15 mm) to a few hundredths of a millimetre where it breaks:
// of the 29 valves of the graft and ten-mesh studies that > 0 calls closed,
// 9 have minima of 1e-15 to 0.08 mm and one 0.33 mm; the next smallest is 0.81 mm.
#include <nlohmann/json.hpp>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

/// A line through `point` along `direction` (any non-zero length).
struct ValveAxis {
  Vec3 point = Vec3::Zero();
  Vec3 direction = Vec3::UnitZ();
  /// A finite point and a finite, non-zero direction of any size (1e-170 or 1e200).
  bool valid() const {
    const double length = direction.stableNorm();
    return point.allFinite() && length > 0 && std::isfinite(length);
  }
  Vec3 unit_direction() const { return direction / direction.stableNorm(); }
};

/// How a node's gap to the other leaflets is measured (see above).
enum class GapMeasure { ray, nearest };
inline const char* to_string(GapMeasure g) { return g == GapMeasure::nearest ? "nearest" : "ray"; }

struct CoaptationOptions {
  GapMeasure gap = GapMeasure::ray;  // the seed's; a scene may choose nearest (coaptation.gap)
  double threshold_mm = 0.5;  // seed 4.2.5: a node coapts when its gap is at most this
  /// Fraction of each free edge's rest length, at both ends, excluded from min_height_mm.
  double commissure_margin = 0.1;
  /// How far below the free edge (mm, along the leaflet) a contact band may begin and still
  /// count as coaptation from the free edge: the seed's normal valve coapts to about 3 mm
  /// below the free edge (Fig. 4.4C), so a band that begins deeper is not that coaptation.
  double free_edge_offset_mm = 3.0;
  /// A leaflet is closed when its minimum height is at least this (mm; see above).
  double closed_min_height_mm = 0.5;
  /// The valve's axis (aortic valve: the root's); without it the free-edge reach is not computed.
  std::optional<ValveAxis> axis;
  void validate() const;  // throws InputError: threshold not > 0, margin outside [0, 0.5),
                          // closed_min_height not finite and > 0,
                          // an axis that is not finite or has no direction
};

/// Value of gap_mm for a node whose rays hit no other leaflet, or (nearest) for a mesh with
/// no other leaflet, and for nodes without triangles. A negative sentinel, never inf or NaN,
/// so that it can be written to files and told apart from every real distance.
constexpr double kCoaptationNoHit = -1.0;

/// Point-array names under which a stage writes CoaptationResult::gap_mm and ::coapting.
constexpr const char* kCoaptationGapArray = "CoaptationGap_mm";
constexpr const char* kCoaptingArray = "Coapting";

struct LeafletCoaptation {
  int leaflet = 0;
  double area_mm2 = 0;            // deformed, interpolated indicator (see above)
  std::vector<int> free_edge;     // free_edge_polyline(mesh, leaflet), corners included
  /// The sampled columns, ascending: rest arc length of each along the free edge, h and top
  /// (-1 without a band). Empty without a free edge.
  std::vector<double> column_arc_mm, column_height_mm, column_band_top_mm;
  int middle_node = -1;             // free_edge_middle_node(mesh, leaflet)
  double midline_height_mm = 0;     // h of the column at half the free edge's rest length
  double midline_band_top_mm = -1;  // its top (-1 without a band)
  /// Minimum of h over the columns between the commissure margins; 0 without free edge.
  double min_height_mm = 0;
  /// Rest length of the free-edge segments whose two end nodes coapt, over the rest length
  /// of the free edge (0 without free edge).
  double coapting_fraction_of_free_edge = 0;
  /// Closest approach of the deformed free-edge polyline to the valve axis; -1 without an
  /// axis or a free edge.
  double free_edge_axis_distance_mm = -1;
  bool closed = false;  // min_height_mm >= closed_min_height_mm
};

struct CoaptationResult {
  std::vector<double> gap_mm;  // per node, mm; kCoaptationNoHit where no other leaflet is found
  std::vector<int> coapting;   // per node, 1 if 0 <= gap_mm <= threshold, else 0
  std::vector<LeafletCoaptation> leaflets;  // one per leaflet id present, ascending
  bool closed = false;       // every leaflet closed (false for a mesh with one leaflet)
  bool central_gap = false;  // some leaflet's free-edge middle node does not coapt
  double min_height_mm = 0;  // smallest min_height_mm of the leaflets (0 without leaflets)
  /// Largest free_edge_axis_distance_mm of the leaflets that have a free edge: how far from
  /// the axis the farthest free edge stops (-1 without an axis or without free edges).
  double max_free_edge_axis_distance_mm = -1;
  /// Given the axis: the projected orifice (orifice.hpp), the part of the valve's
  /// cross-section no leaflet of thickness threshold_mm covers, seen along the axis (mm²;
  /// -1 without an axis, without attached nodes, or when the axis does not pass inside
  /// their ring, e.g. sheets measured against an axis beside them).
  double orifice_area_mm2 = -1;
  /// One line: closed / central gap and per leaflet area, midline and minimum height, and the
  /// free edge's distance from the axis when there is one.
  std::string report() const;
};

/// The summary block valve-simulate and valve-coaptation write (metrics.coaptation): the
/// verdicts, per leaflet area, heights, free-edge reach, and the options used.
nlohmann::json coaptation_metrics(const CoaptationResult& result, const CoaptationOptions& options);

/// The sampled columns of every leaflet as CSV, one row per column:
/// leaflet,arc_mm,height_mm,band_top_mm (rest arc length along the free edge, h, top or -1).
std::string coaptation_columns_csv(const CoaptationResult& result);

/// Coaptation of the deformed valve `x` (3N, node-major, mm). Throws InputError when x does
/// not have 3N finite entries, per-node or per-triangle arrays have the wrong size, a leaflet
/// index is negative, or the options are invalid.
CoaptationResult analyze_coaptation(const TriMesh& mesh, const VecX& x, const CoaptationOptions& options = {});

}  // namespace valve
