// One frame of a run as a VTK XML unstructured grid (.vtu), zlib-compressed, appended
// binary; and the ParaView collection (.pvd) that lists frames with their real times.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace dspdem {

struct FrameData {
  const Mesh* mesh = nullptr;
  const Real* x = nullptr;   ///< current positions (the grid's points)
  const Real* x0 = nullptr;  ///< reference positions (for displacement)
  const Real* v = nullptr;
  const Real* stress = nullptr;  ///< 6 per element (xx yy zz xy yz xz), global element order
  const Index* body = nullptr;
  const Index* fragment = nullptr;  ///< per element, or null
  const Index* material = nullptr;
  std::vector<std::string> fields;
  bool compress = true;
  /// Rigid walls' poses, 7 per wall in the case's order (centre x y z, quaternion w x y z):
  /// written as the grid's field data `wall_pose`, so the renderer draws the walls where they
  /// were (their shapes come from the case).
  std::vector<double> wall_pose;
  /// A distributed run's piece: only the cells flagged here (the process's own elements) and
  /// their points, with the cell field `rank`; `path` is then the frame's .pvtu, which
  /// piece 0 writes, and each process writes its piece beside it (name_<piece>.vtu).
  const char* cell_owned = nullptr;
  int piece = 0, pieces = 1;
  /// Per element its gmsh tag, written as the cell field `element` when `fields` asks for it.
  const std::size_t* element_tag = nullptr;
};

/// Writes the frame to `path` (through a temporary name). Throws Error on failure.
void write_vtu(const std::string& path, const FrameData& f);

namespace joint {
struct JointSet;
}
/// Writes the joints as their own dataset: one polygon per joint on its mid-surface with
/// cell data state (0 intact, 1 softening, 2 broken), damage (0-1, the eq. 6 measure),
/// opening and slip (means over the points) [m]; with `x0` (the nodes' first positions) also
/// the point field displacement, the mid-surface's [m], so that a drawing that magnifies the
/// bodies' displacement can move the joints with them.
/// `owned` (one flag per joint) and pieces > 1: a distributed run's piece, as write_vtu's.
void write_joints_vtu(const std::string& path, const joint::JointSet& js, const Real* x, const Real* x0, bool compress,
                      const std::vector<char>& owned = {}, int piece = 0, int pieces = 1);

/// Writes a .pvd collection: (time, relative file) pairs.
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& frames);

/// Largest principal value of a symmetric stress given as xx yy zz xy yz xz.
Real max_principal(const Real* s);

}  // namespace dspdem
