// Skeletons of elements (README M3): every face plane moved inward by the
// dilation radius r. Tet: the homothety about the incentre with factor (rho - r)/rho.
// Hex: each corner is the meeting point of its three offset face planes (the half-space
// intersection, exact while the offset keeps the hexahedron's topology, which is checked).
//
// The skeleton is stored as weights on the element's nodes, skeleton vertex k =
// sum_j W(k, j) x_j, computed in the reference configuration; the weights are convex (the
// skeleton vertices lie inside the element), so the skeleton follows the element's
// deformation and a node moving by u moves no skeleton vertex by more than |u|.
#pragma once
#include <array>
#include <string>

#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace dspdem::contact {

struct Skeleton {
  std::array<Real, 64> w{};  ///< npe x npe, row k = skeleton vertex k
  Real inradius = 0;         ///< of the element
};

/// Inradius of a tet4 or hex8 (hex: smallest distance from the centroid to a face plane).
Real inradius(CellType t, const Vec3* x);

/// Skeleton for radius r. Returns an empty string, or why r cannot be used (r >= inradius,
/// or a hexahedron whose offset corners fold over).
std::string make_skeleton(CellType t, const Vec3* x, Real r, Skeleton& out);

/// Natural coordinates (hex8, in [-1, 1]^3) of a point p in the element with corners x, by
/// Newton iteration on the trilinear map; and the 8 shape functions there.
Vec3 hex_natural(const Vec3* x, const Vec3& p, const Vec3& start = Vec3::Zero(), int max_iter = 20);
void hex_shape(const Vec3& xi, Real* N);

/// Shape functions N_j of the element at point p (which may lie slightly outside it:
/// extrapolated, still summing to one and reproducing p). Used to spread a contact force.
/// `near` (optional, hex8): node weights of a point close to p, whose natural coordinates
/// start the Newton iteration (one or two steps then suffice).
void shape_at(CellType t, const Vec3* x, const Vec3& p, Real* N, const Real* near = nullptr);

}  // namespace dspdem::contact
