// When a closed face opens (extrinsic insertion, issue 20): the traction the two elements
// put on their common face, and how far it is along to the onset of the joint law that face
// will follow once open. A face opens when the ratio reaches 1; the law then starts where its
// own elastic branch ends, so that the criterion and the law agree on the strength.
#pragma once
#include <algorithm>
#include <cmath>

#include "core/types.hpp"
#include "joint/joint_law.hpp"

namespace dspdem::joint {

/// Normal (tension positive) and shear (magnitude) traction on a face [Pa].
struct FaceTraction {
  Real tn = 0, ts = 0;
};

/// The traction vector on a face of unit normal n from the mean of its two elements' Cauchy
/// stresses (6 each, xx yy zz xy yz xz, as fem's internal_forces writes them). The mean is
/// the face's traction for a stress field linear across the face and the usual estimate
/// otherwise.
inline Vec3 face_traction_vector(const Real* sa, const Real* sb, const Vec3& n) {
  Mat3 s;
  s << sa[0] + sb[0], sa[3] + sb[3], sa[5] + sb[5],  //
      sa[3] + sb[3], sa[1] + sb[1], sa[4] + sb[4],   //
      sa[5] + sb[5], sa[4] + sb[4], sa[2] + sb[2];
  return 0.5 * (s * n);
}

/// Its normal part (tension positive) and the magnitude of its shear part.
inline FaceTraction face_traction(const Real* sa, const Real* sb, const Vec3& n) {
  const Vec3 t = face_traction_vector(sa, sb, n);
  const Real tn = t.dot(n);
  return {tn, (t - tn * n).norm()};
}

/// Where the traction t stands against the onset of law p's damage: 1 on its elastic limit,
/// below 1 inside. Mode I: tension over f_t. Paper (tension cut-off and Mohr-Coulomb, each
/// softening alone): the larger of t_n / f_t and t_s / f_s(t_n), f_s = c - min(t_n, f_t) tan phi.
/// Coupled: the onset ellipse, sqrt((<t_n> / f_t)^2 + (t_s / f_s)^2), f_s = c + <-t_n> tan phi.
inline Real onset_ratio(const CohesiveParams& p, const FaceTraction& t) {
  switch (p.law) {
    case JointLaw::ModeI:
      return t.tn / p.ft;
    case JointLaw::Paper:
    case JointLaw::PaperResidual:  // the same elastic limit; only the softening differs
      return std::max(t.tn / p.ft, t.ts / shear_strength(p, t.tn));
    case JointLaw::Coupled: {
      const Real un = std::max<Real>(0.0, t.tn) / p.ft;
      const Real us = t.ts / (p.c + std::max<Real>(0.0, -t.tn) * p.tan_phi);
      return std::sqrt(un * un + us * us);
    }
  }
  return 0;
}

/// Which stress gives a closed face its traction for the insertion test. Mean: the mean of
/// its two elements' stresses. Larger: each element's own stress on the face, and the one
/// nearer the onset (the larger ratio). Linear elements have one stress each, and at a stress
/// concentration (a notch tip, the disc's loaded diameter) the mean of the two smooths the peak
/// over two elements; an intrinsic joint's nodal point feels it. Measured (issue 20): on the
/// Brazilian disc the mean gave a splitting strength 21.6 % above the input f_t, the larger
/// +1.7 % (intrinsic joints: -3.5 %); on the Galvez beam the peak load was 16-18 % above the
/// intrinsic run's with the mean, 9-13 % with the larger.
enum class FaceStress : char { Mean = 0, Larger = 1 };

/// The traction vector a closed face of unit normal n carries for the insertion test, and its
/// onset ratio under law p (onset_ratio), by rule r.
struct FaceOnset {
  Vec3 t = Vec3::Zero();
  Real ratio = 0;
};
inline FaceOnset face_onset(const CohesiveParams& p, const Real* sa, const Real* sb, const Vec3& n, FaceStress r) {
  auto of = [&](const Vec3& t) {
    const Real tn = t.dot(n);
    return FaceOnset{t, onset_ratio(p, {tn, (t - tn * n).norm()})};
  };
  if (r == FaceStress::Mean) return of(face_traction_vector(sa, sb, n));
  const FaceOnset a = of(face_traction_vector(sa, sa, n)), b = of(face_traction_vector(sb, sb, n));
  return b.ratio > a.ratio ? b : a;
}

/// A traction smaller than this in magnitude cannot reach law p's onset (a screen that
/// spares the full test on faces far from it): mode I needs t_n >= f_t; for the coupled
/// ellipse (<t_n> / f_t)^2 + (t_s / f_s)^2 <= |t|^2 / min(f_t, f_s)^2 and f_s >= c, so it needs
/// |t| >= min(f_t, c); the paper's law needs
/// t_n >= f_t or t_s >= c - t_n tan(phi) >= c - |t| tan(phi), so |t| >= c / (1 + tan(phi)).
inline Real onset_floor(const CohesiveParams& p) {
  switch (p.law) {
    case JointLaw::ModeI:
      return p.ft;
    case JointLaw::Coupled:
      return std::min(p.ft, p.c);
    case JointLaw::Paper:
    case JointLaw::PaperResidual:
      return std::min(p.ft, std::max<Real>(0.0, p.c) / (1 + std::max<Real>(0.0, p.tan_phi)));
  }
  return 0;
}

/// An upper bound of |sigma n| over unit n: the Frobenius norm of a stress (6 components).
inline Real stress_bound(const Real* s) {
  return std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

}  // namespace dspdem::joint
