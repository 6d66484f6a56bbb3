// The finite-element part of a model: per-type element blocks with their reference data,
// lumped nodal masses, and the internal-force evaluation.
//
// Determinism: element kernels write into per-element force slots; nodes then gather their
// slots in a fixed order (CSR). Sums therefore do not depend on the number of threads.
#pragma once
#include <string>
#include <vector>

#include "core/types.hpp"
#include "fem/linear_elastic.hpp"
#include "mesh/mesh.hpp"

namespace dspdem {

/// How an element measures strain. Corotational: strain in the frame of the polar rotation
/// R of F (objective, exact for rigid rotation). SmallStrain: sym(grad u), cheaper, only
/// valid while rotations stay small. Rigid: no strain at all; the element only carries mass
/// and a contact skeleton, and its body moves as one rigid motion (time/rigid_body.hpp).
enum class Kinematics { Corotational, SmallStrain, Rigid };

/// Bulk material of a set of elements.
struct Material {
  std::string name;
  Real density = 0;  ///< [kg/m^3]
  Real E = 0;        ///< Young's modulus [Pa]
  Real nu = 0;       ///< Poisson's ratio
  Real alpha = 0;    ///< mass-proportional Rayleigh damping [1/s]
  Real beta = 0;     ///< stiffness-proportional Rayleigh damping [s]
};

/// One homogeneous kernel block: one cell type, one kinematics.
struct FemBlock {
  CellType type = CellType::Tet4;
  Kinematics kin = Kinematics::Corotational;
  std::vector<Index> conn;  ///< n x npe
  std::vector<Index> elem;  ///< global element id
  std::vector<Real> grad;   ///< n x (3 x npe), column-major per element: reference b_I
  std::vector<Real> vol;    ///< reference volume
  std::vector<Real> lambda, mu, beta;
  std::vector<Real> gamma;  ///< hex8: n x (4 x 8)
  std::vector<Real> khg;    ///< hex8: n x 144
  std::size_t slot0 = 0;    ///< first force slot of this block
  bool damped = false;      ///< any element with beta > 0
  Index size() const { return static_cast<Index>(elem.size()); }
  int npe() const { return nodes_per_cell(type); }
};

struct FemModel {
  Index n_nodes = 0;
  Index n_elements = 0;
  std::vector<Real> x0;          ///< reference coordinates
  std::vector<Real> mass;        ///< lumped nodal mass
  std::vector<Real> node_alpha;  ///< mass-proportional damping per node
  std::vector<FemBlock> blocks;
  std::vector<std::size_t> elem_tag;  ///< global element -> gmsh tag
  std::vector<Index> elem_material;
  std::vector<Index> elem_body;
  std::vector<Index> node_ptr, node_slot;  ///< CSR node -> force slots
  // Per-step work arrays
  std::vector<Real> slots;        ///< 3 per element node
  std::vector<Real> elem_energy;  ///< strain energy per element [J]
  std::vector<Real> elem_dpower;  ///< stiffness-damping dissipation rate per element [W]
  bool any_stiffness_damping = false;
};

/// Builds the model. `material` and `body` give each global element (blocks in mesh order)
/// its material and body; `body_kin` the kinematics per body.
FemModel build_fem_model(const Mesh& mesh, const std::vector<Material>& materials, const std::vector<Index>& material,
                         const std::vector<Index>& body, const std::vector<Kinematics>& body_kin);

/// Result of a force evaluation: the first element found inverted (det F <= 0), or -1.
struct ForceStatus {
  Index inverted_element = -1;
  Real min_detF = 1.0;
};

/// Which elements an evaluation computes: all (no mask), or those whose mask entry (per
/// element) is `value`. A distributed run computes the elements that need no ghost while the
/// ghosts' values travel, then the others (time/integrator.cpp).
struct ElementPass {
  const char* mask = nullptr;
  char value = 0;
  bool takes(Index e) const { return !mask || mask[e] == value; }
};

/// Internal nodal forces f (acting on the nodes, i.e. minus the gradient of the strain
/// energy, plus stiffness-proportional damping forces) at positions x and velocities v.
/// Overwrites f (3 x n_nodes). If `stress` is given, also writes each element's Cauchy
/// stress (6 per element: xx yy zz xy yz xz).
ForceStatus internal_forces(FemModel& m, const Real* x, const Real* v, Real* f, Real* stress = nullptr);

/// The two halves of internal_forces: the elements' nodal forces into their slots (the
/// elements of `pass`), then every node's sum of its slots in a fixed order, into f. So the
/// elements may be computed in any order or in several passes: f is the same to the bit.
ForceStatus element_forces(FemModel& m, const Real* x, const Real* v, Real* stress, ElementPass pass);
void gather_forces(const FemModel& m, Real* f);

/// Per-block kernels (one file each).
ForceStatus tet4_forces(FemModel& m, const FemBlock& b, const Real* x, const Real* v, Real* stress, ElementPass pass);
ForceStatus hex8_forces(FemModel& m, const FemBlock& b, const Real* x, const Real* v, Real* stress, ElementPass pass);

/// Sum of a per-element array in fixed chunks: the same result for any thread count.
Real deterministic_sum(const std::vector<Real>& a);

}  // namespace dspdem
