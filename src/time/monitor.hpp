// What a monitor records into series.csv (a column per monitor); the case reader fills it
// from [[monitors]], the integrator evaluates it.
#pragma once
#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "core/types.hpp"

namespace dspdem {

struct MonitorConfig {
  enum class Type {
    Reaction,
    Displacement,
    DisplacementDifference,
    MaxDisplacement,
    Velocity,
    Momentum,
    BrokenJoints,  ///< failed joints whose face centroid (at the start) lies in `box`
    CrackArea      ///< their reference area [m^2]
  } type;
  std::string name, group, group2;
  int component = 3;  ///< 0,1,2 = x,y,z; 3 = magnitude
  /// BrokenJoints, CrackArea: the region counted (faces included); none: every joint.
  std::optional<Eigen::AlignedBox<Real, 3>> box;
  std::string where;
  bool counts_joints() const { return type == Type::BrokenJoints || type == Type::CrackArea; }
};

}  // namespace dspdem
