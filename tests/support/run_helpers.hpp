// Helpers for verification tests that drive the Integrator directly.
#pragma once
#include "fem/stable_dt.hpp"
#include "io/model_builder.hpp"
#include "support/box_mesh.hpp"
#include "support/model_builder.hpp"
#include "time/integrator.hpp"

namespace dspdem::testsupport {

/// Node index of grid point (i, j, k) in a box_mesh with nx x ny cells per layer.
inline Index grid_node(int nx, int ny, int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); }

inline Real critical_dt(const Model& m) { return stable_step(m).dt; }

}  // namespace dspdem::testsupport

#include <fmt/format.h>
namespace dspdem::testsupport {
/// Scientific notation for RecordProperty values.
inline std::string sci(double v) { return fmt::format("{:.4e}", v); }
}  // namespace dspdem::testsupport
