#include "joint/joint_compliance.hpp"

namespace dspdem::joint {

Real added_compliance(const JointSet& js, const std::vector<Real>& elem_E, const std::vector<Real>& elem_volume) {
  std::vector<char> jointed(elem_volume.size(), 0);
  Real sum = 0;
  for (Index j = 0; j < js.size(); ++j) {
    if (!js.closed.empty() && js.closed[j]) continue;  // a closed face is continuous material
    const CohesiveParams& p = js.params[js.param[j]];
    const Real E = 0.5 * (elem_E[js.ea[j]] + elem_E[js.eb[j]]);
    sum += E * added_compliance_term(js.area0[j], p.kn, p.ks);
    jointed[js.ea[j]] = jointed[js.eb[j]] = 1;
  }
  Real vol = 0;
  for (std::size_t e = 0; e < elem_volume.size(); ++e)
    if (jointed[e]) vol += elem_volume[e];
  return vol > 0 ? sum / vol : 0.0;
}

}  // namespace dspdem::joint
