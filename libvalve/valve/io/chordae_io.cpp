#include "valve/io/chordae_io.hpp"

#include "valve/io/mesh_io.hpp"

namespace valve {

void write_chordae_vtp(const std::filesystem::path& path, const ChordaeNetwork& net, const MatX3* positions,
                       const std::vector<double>* tension) {
  const int n = static_cast<int>(net.points.size()), m = static_cast<int>(net.segments.size());
  MatX3 x(n, 3);
  for (int i = 0; i < n; ++i) x.row(i) = positions ? Vec3(positions->row(i).transpose()) : net.points[i].position;
  std::vector<std::pair<int, int>> lines;
  Eigen::MatrixXd kind(n, 1), type(m, 1), rest(m, 1), length(m, 1), t(m, 1);
  for (int i = 0; i < n; ++i) kind(i, 0) = static_cast<int>(net.points[i].kind);
  for (int s = 0; s < m; ++s) {
    const ChordSegment& seg = net.segments[s];
    lines.emplace_back(seg.from, seg.to);
    type(s, 0) = static_cast<int>(seg.type);
    rest(s, 0) = net.rest_length(s);
    length(s, 0) = (x.row(seg.from) - x.row(seg.to)).norm();
    if (tension) t(s, 0) = (*tension)[s];
  }
  std::vector<NamedArray> arrays{{"PointKind", kind, false}, {"ChordType", type, true}, {"RestLength_mm", rest, true},
                                 {"Length_mm", length, true}};
  if (tension) arrays.push_back({"Tension_N", t, true});
  write_lines(path, x, lines, arrays);
}

}  // namespace valve
