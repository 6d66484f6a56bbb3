#include "contact/skeleton.hpp"

#include <fmt/format.h>

#include <cmath>

#include "fem/hex8.hpp"
#include "joint/joint_set.hpp"

namespace dspdem::contact {

namespace {
struct Plane {
  Vec3 n, p;  ///< outward unit normal, point on the plane
};

// Face planes of a hexahedron: normal from the two diagonals, through the face centroid.
std::array<Plane, 6> hex_planes(const Vec3* x) {
  std::array<Plane, 6> out;
  const auto& faces = joint::cell_faces(CellType::Hex8);
  for (int f = 0; f < 6; ++f) {
    const auto& q = faces[f];
    out[f].n = (x[q[2]] - x[q[0]]).cross(x[q[3]] - x[q[1]]).normalized();
    out[f].p = 0.25 * (x[q[0]] + x[q[1]] + x[q[2]] + x[q[3]]);
  }
  return out;
}

Vec3 centroid(const Vec3* x, int n) {
  Vec3 c = Vec3::Zero();
  for (int i = 0; i < n; ++i) c += x[i];
  return c / n;
}
}  // namespace

void hex_shape(const Vec3& xi, Real* N) {
  const auto& nc = hex8::natural_coords();
  for (int j = 0; j < 8; ++j) N[j] = 0.125 * (1 + nc(0, j) * xi(0)) * (1 + nc(1, j) * xi(1)) * (1 + nc(2, j) * xi(2));
}

Vec3 hex_natural(const Vec3* x, const Vec3& p, const Vec3& start, int max_iter) {
  Vec3 xi = start;
  for (int it = 0; it < max_iter; ++it) {
    Real N[8];
    hex_shape(xi, N);
    const hex8::Grad dN = hex8::shape_derivatives(xi);
    Vec3 r = -p;
    Mat3 J = Mat3::Zero();
    for (int j = 0; j < 8; ++j) r += N[j] * x[j], J += x[j] * dN.col(j).transpose();
    const Vec3 dxi = J.partialPivLu().solve(r);
    xi -= dxi;
    if (dxi.squaredNorm() < 1e-24) break;
  }
  return xi;
}

Real inradius(CellType t, const Vec3* x) {
  if (t == CellType::Tet4) {
    const Real v = std::abs(tet4_volume(x[0], x[1], x[2], x[3]));
    Real area = 0;
    for (const auto& f : joint::cell_faces(t)) area += 0.5 * (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]).norm();
    return 3 * v / area;
  }
  const Vec3 c = centroid(x, 8);
  Real rho = INFINITY;
  for (const Plane& pl : hex_planes(x)) rho = std::min(rho, (pl.p - c).dot(pl.n));
  return rho;
}

std::string make_skeleton(CellType t, const Vec3* x, Real r, Skeleton& out) {
  out.inradius = inradius(t, x);
  if (!(r >= 0) || r >= out.inradius)
    return fmt::format(
        "contact radius {:.4g} m is not below the element's inradius {:.4g} m (the skeleton would be "
        "empty)",
        r, out.inradius);
  out.w.fill(0);
  if (t == CellType::Tet4) {
    // Incentre: barycentric weights proportional to the areas of the opposite faces.
    Real area[4];
    for (int j = 0; j < 4; ++j) {
      const Vec3& a = x[(j + 1) % 4];
      area[j] = 0.5 * (x[(j + 2) % 4] - a).cross(x[(j + 3) % 4] - a).norm();
    }
    const Real total = area[0] + area[1] + area[2] + area[3];
    const Real s = (out.inradius - r) / out.inradius;
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j) out.w[4 * k + j] = (k == j ? s : 0.0) + (1 - s) * area[j] / total;
    return "";
  }
  const auto planes = hex_planes(x);
  const auto& faces = joint::cell_faces(CellType::Hex8);
  for (int k = 0; k < 8; ++k) {
    Mat3 A;
    Vec3 b;
    int row = 0;
    for (int f = 0; f < 6; ++f)
      for (int q : faces[f])
        if (q == k) {
          A.row(row) = planes[f].n.transpose();
          b(row++) = planes[f].n.dot(planes[f].p) - r;
        }
    const Vec3 y = A.partialPivLu().solve(b);
    const Vec3 xi = hex_natural(x, y);
    if (!(xi.cwiseAbs().maxCoeff() < 1))
      return fmt::format("contact radius {:.4g} m folds the skeleton of this hexahedron (inradius {:.4g} m)", r,
                         out.inradius);
    hex_shape(xi, &out.w[8 * k]);
  }
  // The skeleton must keep the element's orientation (no corner passed another).
  Vec3 s[8];
  for (int k = 0; k < 8; ++k) {
    s[k].setZero();
    for (int j = 0; j < 8; ++j) s[k] += out.w[8 * k + j] * x[j];
  }
  hex8::Coords S;
  for (int k = 0; k < 8; ++k) S.col(k) = s[k];
  if (!(hex8::min_corner_jacobian(S) > 0))
    return fmt::format("contact radius {:.4g} m inverts the skeleton of this hexahedron", r);
  return "";
}

void shape_at(CellType t, const Vec3* x, const Vec3& p, Real* N, const Real* near) {
  if (t == CellType::Hex8) {
    Vec3 start = Vec3::Zero();
    if (near)
      for (int j = 0; j < 8; ++j) start += near[j] * hex8::natural_coords().col(j);
    // From a nearby start two Newton steps leave an error far below what matters here: the
    // weights sum to one at any xi (force exact), only the moment arm moves by |x(xi) - p|.
    hex_shape(hex_natural(x, p, start, near ? 2 : 20), N);
    return;
  }
  Mat3 J;
  J.col(0) = x[1] - x[0], J.col(1) = x[2] - x[0], J.col(2) = x[3] - x[0];
  const Vec3 l = J.partialPivLu().solve(Vec3(p - x[0]));
  N[0] = 1 - l.sum(), N[1] = l(0), N[2] = l(1), N[3] = l(2);
}

}  // namespace dspdem::contact
