// Rigid walls: analytic planes (half-spaces), boxes and curved jaws that contact the deformable
// elements with the same law. A wall either follows a prescribed velocity (with an optional
// ramp) or moves freely as a rigid body (mass, inertia tensor, quaternion orientation),
// integrated with the same kick-drift-kick scheme as the nodes.
#pragma once
#include <Eigen/Geometry>
#include <string>

#include "contact/polytope.hpp"

namespace dspdem::contact {

struct Wall {
  // Jaw: the concave cylindrical face of a loading jaw (ISRM Brazilian test: radius 1.5 R),
  // the solid being outside a cylinder of radius `radius` about the axis through `centre`
  // along the body z axis, within `half_angle` of the body normal0 direction seen from it.
  // Cylinder: a rigid roller or impactor, the segment of its axis (through `centre` along
  // axis0 rotated, of length 2 half_length) dilated by `radius`: a spherocylinder, equal to
  // the cylinder wherever the contact is on its side (its ends are hemispheres).
  enum class Type { Plane, Box, Jaw, Cylinder } type = Type::Plane;
  std::string name;
  // Pose: centre (plane: a point on it) and orientation; the plane's outward normal is
  // the body z axis rotated, the box's half sizes are along the body axes.
  Vec3 centre = Vec3::Zero();
  Eigen::Quaternion<Real> q = Eigen::Quaternion<Real>::Identity();
  Vec3 normal0 = Vec3::UnitZ();  ///< plane: outward normal in the reference pose
  Vec3 half = Vec3::Zero();      ///< box: half sizes
  Vec3 axis0 = Vec3::UnitZ();    ///< jaw: cylinder axis in the reference pose
  Real radius = 0;               ///< jaw: cylinder radius [m]
  Real cos_half_angle = 0;       ///< jaw: cos of the arc's half opening angle
  Real half_length = 0;          ///< cylinder: half the length of its axis segment [m]
  // Motion.
  bool free = false;
  Vec3 velocity = Vec3::Zero(), omega = Vec3::Zero();
  Real ramp = 0;  ///< prescribed walls: velocity ramp time [s]
  Vec3 velocity_target = Vec3::Zero();
  Real mass = 0;  ///< free walls
  Mat3 inertia_body = Mat3::Zero();
  Vec3 momentum_angular = Vec3::Zero();
  // Contact parameters (< 0: take the element's).
  Real kn = -1, mu = -1;
  // Results of the last force evaluation.
  Vec3 force = Vec3::Zero();   ///< total contact force on the wall [N]
  Vec3 torque = Vec3::Zero();  ///< about its centre [N m]

  /// What moves (core/archive.hpp); the shape and the settings come from the case.
  template <class Ar>
  void persist(Ar& ar) {
    ar(centre, q, velocity, omega, momentum_angular, force, torque);
  }
  Vec3 plane_normal() const { return q * normal0; }
  /// The wall's own rounding in the contact (r_b against an element's r_a): a cylinder is its
  /// axis dilated by its radius; the other walls are their surfaces.
  Real rounding() const { return type == Type::Cylinder ? radius : 0.0; }
  Vec3 jaw_axis() const { return q * axis0; }
  /// Box as a polytope (hexahedron topology, corners in gmsh order).
  Poly box_poly() const;
  /// Cylinder: its axis segment (segment topology), to be dilated by `radius`.
  Poly axis_poly() const;
  Vec3 velocity_at(const Vec3& x) const { return velocity + omega.cross(x - centre); }
  Real kinetic_energy() const;
  /// Updates omega from the angular momentum (free walls).
  void update_omega();
};

}  // namespace dspdem::contact
