#include "time/rigid_body.hpp"

#include <cmath>

#include "core/error.hpp"

namespace dspdem {

Mat3 RigidBody::inertia_world() const {
  const Mat3 R = q.toRotationMatrix();
  return R * inertia_body * R.transpose();
}

RigidBody make_rigid_body(const std::string& name, std::vector<Index> nodes, const std::vector<Real>& x,
                          const std::vector<Real>& mass, const std::vector<Real>& v) {
  RigidBody b;
  b.name = name;
  b.nodes = std::move(nodes);
  auto pos = [&](Index n) { return Vec3(x[3 * n], x[3 * n + 1], x[3 * n + 2]); };
  auto vel = [&](Index n) { return Vec3(v[3 * n], v[3 * n + 1], v[3 * n + 2]); };
  Vec3 mc = Vec3::Zero(), p = Vec3::Zero();
  for (Index n : b.nodes) b.mass += mass[n], mc += mass[n] * pos(n), p += mass[n] * vel(n);
  if (!(b.mass > 0)) fail("rigid body '{}' has no mass (give its material a density)", name);
  b.centre = mc / b.mass, b.velocity = p / b.mass;
  for (Index n : b.nodes) {
    const Vec3 r = pos(n) - b.centre;
    b.offset.push_back(r);
    b.inertia_body += mass[n] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
    b.angular_momentum += mass[n] * r.cross(vel(n) - b.velocity);
  }
  // A body whose nodes lie on one line has no inertia about that line: it could spin
  // without limit there.
  const Eigen::SelfAdjointEigenSolver<Mat3> es(b.inertia_body);
  if (!(es.eigenvalues()(0) > 1e-12 * es.eigenvalues()(2)))
    fail("rigid body '{}' has no inertia about one axis (its nodes lie on a line)", name);
  b.update_omega();
  return b;
}

void rigid_set_velocities(const RigidBody& b, const Real* x, Real* v) {
  for (Index n : b.nodes) {
    const Vec3 r(x[3 * n] - b.centre(0), x[3 * n + 1] - b.centre(1), x[3 * n + 2] - b.centre(2));
    const Vec3 u = b.velocity + b.omega.cross(r);
    v[3 * n] = u(0), v[3 * n + 1] = u(1), v[3 * n + 2] = u(2);
  }
}

void rigid_kick(RigidBody& b, const Real* f, const Real* x, Real h, Real* v) {
  Vec3 F = Vec3::Zero(), T = Vec3::Zero();
  for (Index n : b.nodes) {
    const Vec3 fn(f[3 * n], f[3 * n + 1], f[3 * n + 2]);
    const Vec3 r(x[3 * n] - b.centre(0), x[3 * n + 1] - b.centre(1), x[3 * n + 2] - b.centre(2));
    F += fn, T += r.cross(fn);
  }
  b.velocity += h * F / b.mass;
  b.angular_momentum += h * T;
  b.update_omega();
  rigid_set_velocities(b, x, v);
}

Real rigid_drift(RigidBody& b, Real h, const Real* f_ext, Real* x, Real* v) {
  b.centre += h * b.velocity;
  const Real angle = h * b.omega.norm();
  if (angle > 0) b.q = Eigen::Quaternion<Real>(Eigen::AngleAxis<Real>(angle, b.omega.normalized())) * b.q;
  b.q.normalize();
  b.update_omega();
  const Mat3 R = b.q.toRotationMatrix();
  Real w = 0;
  for (std::size_t k = 0; k < b.nodes.size(); ++k) {
    const Index n = b.nodes[k];
    const Vec3 xn = b.centre + R * b.offset[k];
    for (int d = 0; d < 3; ++d) {
      w += f_ext[3 * n + d] * (xn(d) - x[3 * n + d]);
      x[3 * n + d] = xn(d);
    }
  }
  rigid_set_velocities(b, x, v);
  return w;
}

}  // namespace dspdem
