// Joint forces (paper eq. 7): f = integral of N^T t over the joint, by Gauss quadrature on
// the mid-surface (triangles 3 points, quadrilaterals 2x2) or at the nodes (the material's
// joint_quadrature), weights from the reference area. The local frame (normal from side A to side B) is taken from the
// current mid-surface, so rigid rotations neither open nor shear a joint.
#pragma once
#include <vector>

#include "joint/joint_set.hpp"

namespace dspdem::joint {

struct JointTotals {
  Real elastic = 0;      ///< recoverable energy in the joints [J]
  Real fracture_I = 0;   ///< dissipated, mode I [J]
  Real fracture_II = 0;  ///< dissipated, mode II (and residual friction) [J]
  Index broken = 0;      ///< failed joints
  Real broken_area = 0;  ///< their reference area: the crack area [m^2]
};

/// Updates every joint at positions x and adds its nodal forces to f. Deterministic: joint
/// forces go to per-joint slots, then each node adds its slots in joint order (in parallel
/// over nodes); the result is bitwise that of add_joint_forces_reference on any thread count.
void add_joint_forces(JointSet& js, const Real* x, Real* f, std::vector<Real>& slots);

/// Takes back from f the forces that `joints` added in the evaluation whose slots these are
/// (add_joint_forces): for joints released after the sum (contact releases a broken joint
/// once its elements lie in different pieces, ContactSystem::add_forces), so that the kicks
/// never apply them. Returns the half of those forces' trapezoid work over the step that
/// ended here, 1/2 h f . v (v the nodes' mid-step velocity, h the step) that the kicks will
/// therefore not apply either, summed over the joints flagged in `owned` (all when empty):
/// the released energy's correction (see Integrator::compute_forces). Serial, in the list's
/// order: the same bits on any thread count.
Real remove_joint_forces(const JointSet& js, const std::vector<Index>& joints, const std::vector<Real>& slots,
                         const Real* v, Real h, const std::vector<char>& owned, Real* f);

/// The plain serial kernel, joint after joint: the test oracle of add_joint_forces.
void add_joint_forces_reference(JointSet& js, const Real* x, Real* f);

/// Totals over the joints; with `owned` (one flag per joint), over the flagged ones only (a
/// distributed run's share; released joints' energy only without a mask).
JointTotals joint_totals(const JointSet& js, const std::vector<char>& owned = {});

/// Energy stored in joint j now [J].
Real joint_elastic_energy(const JointSet& js, Index j);

/// Quadrature of a face: shape values N (per point, per node) and weights (fractions of the
/// face area). Gauss: triangles 3 points at (2/3, 1/6, 1/6) and permutations, quads 2x2.
/// Nodal: one point at each node, equal weights. Either way npf points, point g stored in
/// state slot g.
int face_quadrature(int npf, Quadrature rule, double N[4][4], double w[4]);

}  // namespace dspdem::joint
