// Builds a CaseConfig in code for tests: one material, one body "all".
#pragma once
#include "io/case_config.hpp"
#include "io/model_builder.hpp"
#include "time/model.hpp"

namespace dspdem::testsupport {

inline CaseConfig simple_case(Real E, Real nu, Real rho, Kinematics kin = Kinematics::Corotational) {
  CaseConfig c;
  c.path = "test";
  c.name = "test";
  Material m;
  m.name = "mat";
  m.E = E, m.nu = nu, m.density = rho;
  c.materials.push_back(m);
  c.joint_materials.resize(1);
  BodyConfig b;
  b.name = "body";
  b.groups = {"all"};
  b.material = "mat";
  b.kinematics = kin;
  c.bodies.push_back(b);
  return c;
}

/// Makes body 0 fracturable with the given joint parameters.
inline void make_fracturable(CaseConfig& c, Real ft, Real GfI, Real coh, Real phi_deg, Real GfII, Real penalty = 100) {
  JointMaterial jm;
  jm.given = true;
  jm.ft = ft, jm.GfI = GfI, jm.c = coh, jm.phi_deg = phi_deg, jm.GfII = GfII, jm.penalty = penalty;
  c.joint_materials.assign(c.materials.size(), jm);
  c.bodies[0].fracture = BodyConfig::Fracture::All;
}

inline BoundaryConfig fixed(const std::string& group, const char* dofs = "xyz") {
  BoundaryConfig b;
  b.type = BoundaryConfig::Type::Fixed;
  b.group = group;
  for (int d = 0; d < 3; ++d) b.dof[d] = std::string(dofs).find("xyz"[d]) != std::string::npos;
  return b;
}

}  // namespace dspdem::testsupport
