// Stable time step of the explicit central-difference / Velocity Verlet scheme.
//
// For each element we solve the element eigenproblem K_e phi = w^2 M_e phi with the
// element's own share of the lumped mass; by the element eigenvalue inequality (Irons &
// Ahmad; Belytschko, Liu & Moran, Nonlinear FE, sec. 6.3.4) the largest element frequency
// bounds the largest frequency of the assembled mesh, so dt_e = 2/w_e is a guaranteed
// bound, not a wave-speed heuristic. With stiffness-proportional damping beta the critical
// step shrinks to (2/w)(sqrt(1+xi^2) - xi), xi = beta w / 2.
#pragma once
#include <string>
#include <vector>

#include "fem/fem_model.hpp"

namespace dspdem {

struct StableStep {
  Real dt = 0;         ///< critical step (before any safety factor)
  Index element = -1;  ///< global element that limits it
  std::string limiter = "element";
};

/// Critical step of every element (global element order) and the minimum.
StableStep element_stable_step(const FemModel& m, const std::vector<Material>& materials,
                               std::vector<Real>* per_element = nullptr);

}  // namespace dspdem
