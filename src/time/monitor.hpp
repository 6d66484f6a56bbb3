// What a monitor records into series.csv (a column per monitor); the case reader fills it
// from [[monitors]], the integrator evaluates it.
#pragma once
#include <string>

namespace dspdem {

struct MonitorConfig {
  enum class Type { Reaction, Displacement, DisplacementDifference, MaxDisplacement, Velocity, Momentum } type;
  std::string name, group, group2;
  int component = 3;  ///< 0,1,2 = x,y,z; 3 = magnitude
  std::string where;
};

}  // namespace dspdem
