#include "valve/analysis/sections.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "valve/core/error.hpp"

namespace valve {

SectionFrame section_frame(const MatX3& ring, int count, const Vec3& up) {
  if (ring.rows() < 3) throw Error("section_frame: the annulus ring has fewer than 3 points");
  SectionFrame f;
  f.origin = ring.colwise().mean().transpose();
  const MatX3 centred = ring.rowwise() - f.origin.transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(centred.transpose() * centred);
  // Eigenvalues ascend: column 2 is the longest axis, column 0 the ring's normal.
  f.axis = eig.eigenvectors().col(2);
  f.u = eig.eigenvectors().col(1);
  f.v = eig.eigenvectors().col(0);
  if (up.squaredNorm() > 0 && f.v.dot(up) < 0) f.v = -f.v;
  if (f.axis.cross(f.u).dot(f.v) < 0) f.u = -f.u;  // right-handed (axis, u, v)
  double lo = 0, hi = 0;
  for (int i = 0; i < centred.rows(); ++i) {
    const double s = centred.row(i).dot(f.axis);
    lo = std::min(lo, s), hi = std::max(hi, s);
  }
  for (int k = 0; k < count; ++k) f.offsets.push_back(lo + (hi - lo) * (k + 1) / (count + 1));
  return f;
}

std::vector<SectionSegment> cut_sections(const TriMesh& mesh, const MatX3& points, const SectionFrame& frame) {
  std::vector<SectionSegment> out;
  for (std::size_t p = 0; p < frame.offsets.size(); ++p) {
    const double c = frame.offsets[p];
    for (const Tri& t : mesh.triangles) {
      Vec3 x[3];
      double s[3];
      for (int k = 0; k < 3; ++k) {
        x[k] = points.row(t[k]).transpose() - frame.origin;
        s[k] = x[k].dot(frame.axis) - c;
      }
      // The crossing points on the edges whose ends lie on opposite sides (a vertex exactly
      // on the plane counts as the positive side, so each crossing is found once).
      Vec3 hit[2];
      int n = 0;
      for (int k = 0; k < 3 && n < 2; ++k) {
        const int l = (k + 1) % 3;
        if ((s[k] >= 0) == (s[l] >= 0)) continue;
        const double w = s[k] / (s[k] - s[l]);
        hit[n++] = x[k] + w * (x[l] - x[k]);
      }
      // Two crossings at one vertex that lies on the plane: nothing to draw.
      if (n == 2 && (hit[0] - hit[1]).squaredNorm() > 1e-24)
        out.push_back({static_cast<int>(p), hit[0].dot(frame.u), hit[0].dot(frame.v), hit[1].dot(frame.u), hit[1].dot(frame.v)});
    }
  }
  return out;
}

nlohmann::json to_json(const SectionFrame& frame) {
  auto vec = [](const Vec3& a) { return nlohmann::json::array({a.x(), a.y(), a.z()}); };
  return {{"origin", vec(frame.origin)}, {"axis", vec(frame.axis)}, {"u", vec(frame.u)}, {"v", vec(frame.v)},
          {"offsets_mm", frame.offsets}};
}

}  // namespace valve
