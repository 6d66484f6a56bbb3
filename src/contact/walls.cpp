#include "contact/walls.hpp"

#include "fem/hex8.hpp"

namespace dspdem::contact {

Poly Wall::box_poly() const {
  Poly p;
  p.topo = &topology(Shape::Hex);
  const auto& nc = hex8::natural_coords();
  const Mat3 R = q.toRotationMatrix();
  for (int k = 0; k < 8; ++k) p.v[k] = centre + R * Vec3(nc.col(k).cwiseProduct(half));
  return p;
}

Poly Wall::axis_poly() const {
  Poly p;
  p.topo = &topology(Shape::Segment);
  const Vec3 a = half_length * (q * axis0);
  p.v[0] = centre - a, p.v[1] = centre + a;
  return p;
}

Real Wall::kinetic_energy() const {
  if (!free) return 0;
  return 0.5 * mass * velocity.squaredNorm() + 0.5 * omega.dot(momentum_angular);
}

void Wall::update_omega() {
  const Mat3 R = q.toRotationMatrix();
  omega = R * inertia_body.ldlt().solve(R.transpose() * momentum_angular);
}

}  // namespace dspdem::contact
