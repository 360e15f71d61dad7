#pragma once
// Finite-difference check shared by the material law tests: the stress is the gradient of the
// energy and the tangent the (symmetric) Jacobian of the stress, to 1e-6 relative.
#include <catch2/catch.hpp>

#include "valve/material/material_law.hpp"

inline void check_law_derivatives(const valve::MaterialLaw& law, const valve::Voigt& E, double symmetry_tolerance) {
  using valve::Mat3;
  using valve::Voigt;
  const double h = 1e-7;
  Voigt S_fd;
  Mat3 D_fd;
  for (int k = 0; k < 3; ++k) {
    Voigt ep = E, em = E;
    ep[k] += h;
    em[k] -= h;
    S_fd[k] = (law.energy(ep) - law.energy(em)) / (2 * h);
    D_fd.col(k) = (law.stress(ep) - law.stress(em)) / (2 * h);
  }
  CHECK((S_fd - law.stress(E)).norm() <= 1e-6 * law.stress(E).norm());
  CHECK((D_fd - law.tangent(E)).norm() <= 1e-6 * law.tangent(E).norm());
  CHECK((law.tangent(E) - law.tangent(E).transpose()).norm() < symmetry_tolerance * law.tangent(E).norm());
}
