#pragma once
// A named point or cell array of a mesh (Displacement, GreenStrain, Error_mm, ...): what the
// analyses compute and the mesh writers store beside the geometry.
#include <Eigen/Core>
#include <string>

namespace valve {

struct NamedArray {
  std::string name;
  Eigen::MatrixXd values;  // one row per point (or cell), one column per component
  bool per_cell = false;
};

}  // namespace valve
