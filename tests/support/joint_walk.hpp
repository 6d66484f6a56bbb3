// Random walks of a joint point in (opening dn, slip ds), for the laws' energy tests: small
// steps as in a run, with the normal traction swinging between tension and compression. The
// generator runs on from one walk to the next; reset() starts a walk at the origin.
#pragma once
#include <algorithm>
#include <cstdint>

#include "core/types.hpp"
#include "joint/cohesive_law.hpp"

namespace dspdem::testsupport {

struct JointWalk {
  std::uint64_t r;           ///< the generator's state (a 64-bit LCG): the seed
  Real dn_step, ds_step;     ///< largest step of each [m]
  Real dn_lo, dn_hi, ds_hi;  ///< bounds [m]
  Real dn = 0, ds = 0;

  Real uni() {
    r = r * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<Real>(r >> 11) * 0x1.0p-53;
  }
  void reset() { dn = ds = 0; }
  /// One step: dn uniform in +-dn_step / 2, ds drifting up (mean 0.05 ds_step).
  void step() {
    dn = std::clamp(dn + (uni() - 0.5) * dn_step, dn_lo, dn_hi);
    ds = std::clamp(ds + (uni() - 0.45) * ds_step, 0.0, ds_hi);
  }
};

/// What walking a law showed: the first step at which a mode's dissipation fell by more than
/// the tolerance or the stored energy went below minus it (path < 0: none), and how many walks
/// ended broken.
struct WalkVerdict {
  int path = -1, step = -1;
  int broken = 0;
};

/// Walks `paths` walks of `steps` steps through update(p, dn, ds, state), each from a fresh
/// state; tol bounds the trapezoid rule's error at kinks.
template <class Update>
WalkVerdict walk_energy(const joint::CohesiveParams& p, JointWalk& walk, int paths, int steps, Real tol,
                        Update update) {
  WalkVerdict v;
  for (int path = 0; path < paths; ++path) {
    joint::CohesiveState s;
    Real dI = 0, dII = 0;
    walk.reset();
    for (int i = 0; i < steps; ++i) {
      walk.step();
      update(p, walk.dn, walk.ds, s);
      const Real nI = s.dissipated_I(p), nII = s.dissipated_II(p);
      if ((nI < dI - tol || nII < dII - tol || s.elastic_energy(p) < -tol) && v.path < 0) v.path = path, v.step = i;
      dI = std::max(dI, nI), dII = std::max(dII, nII);
    }
    v.broken += s.status == joint::JointStatus::Broken;
  }
  return v;
}

}  // namespace dspdem::testsupport
