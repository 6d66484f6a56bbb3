// The breakage probability of a particle against its impact energy, fitted to runs that each
// did or did not break: the form of Vogel & Peukert (L. Vogel, W. Peukert, "Breakage
// behaviour of different materials - construction of a mastercurve for the breakage
// probability", Powder Technology 129:101-110, 2003), which comminution uses to read single-
// particle impact tests and which DEM codes' breakage models build on:
//
//   P(W) = 1 - exp(-f_Mat x k (W - W_min))  for W > W_min, else 0,
//
// W the kinetic energy per mass at the impact (v^2 / 2, J/kg), x the particle's size, k the
// number of impacts (1 here), W_min the energy below which nothing breaks and f_Mat a
// material constant. A sweep of speeds run on several meshes (the sphere's realisations) is
// such a test: which mesh breaks near the threshold is a draw, and the fitted curve says over
// what range of speeds the draw lies, which single counts at one speed cannot.
//
// The fit is by maximum likelihood over the runs, each a Bernoulli trial; the interval of the
// energy at P = 1/2 is the profile-likelihood one at a deviance of 3.84 (chi-square with one
// degree of freedom at 95 %), which unlike a Wald interval does not assume the likelihood
// symmetric, as it is not near W_min. Its 95 % is nominal: Wilks's theorem behind it is
// asymptotic and strained here by W_min, a threshold with a bound at 0. The fit needs broken
// and held runs mixed at two energies or more; without, it names what the data say instead.
#pragma once
#include <cmath>
#include <vector>

namespace dspdem::report {

/// One run: its impact energy per mass [J/kg] and whether it broke.
struct BreakageTrial {
  double energy = 0;
  bool broken = false;
  /// The unit whose runs are not independent draws (a mesh run at several speeds): the
  /// bootstrap resamples groups whole.
  int group = 0;
};

struct BreakageFit {
  enum class Outcome {
    fitted,         ///< w_min and rate hold, and the interval unless it was not asked for
    none_broke,     ///< no run broke: only that P is small up to `below`
    all_broke,      ///< every run broke: only that P is large from `above` on
    separated,      ///< every run below `above` held and every one from it broke: the threshold lies
                    ///< between `below` and `above`, and the data cannot say how wide the draw is
    too_few_mixed,  ///< broken and held runs mix at fewer than two energies (at one: `mixed_energy`,
                    ///< where they fix P and nothing else), though not separated: the likelihood's
                    ///< top is a ridge or lies at an infinite rate, so the curve is not fixed
  };
  Outcome outcome = Outcome::none_broke;
  int trials = 0, broken = 0;
  /// The highest energy of a run that held, the lowest of one that broke (NaN: none such).
  double below = std::nan(""), above = std::nan("");
  /// too_few_mixed: the energy at which broken and held runs mix (NaN: at none).
  double mixed_energy = std::nan("");
  /// fitted: W_min [J/kg] and the rate f_Mat x k [kg/J].
  double w_min = std::nan(""), rate = std::nan("");
  double log_likelihood = std::nan("");
  /// fitted: the 95 % profile-likelihood interval of the energy at P = 1/2; w50_hi is
  /// +infinity when the data do not bound it above. NaN when fit_breakage was told to leave
  /// the interval out.
  double w50_lo = std::nan(""), w50_hi = std::nan("");

  /// The fitted probability of breaking at energy w (fitted only).
  double probability(double w) const;
  /// The energy at which the fitted probability is p, 0 < p < 1 (fitted only).
  double energy_at(double p) const;
};

/// The log-likelihood of the trials under P(W) = 1 - exp(-rate (W - w_min)); -infinity when a
/// run at or below w_min broke.
double breakage_log_likelihood(const std::vector<BreakageTrial>& trials, double w_min, double rate);

/// Fits W_min >= 0 and the rate by maximum likelihood when broken and held runs mix at two
/// energies or more (energies equal to the last bit count as one); `interval` false leaves the
/// interval out (it costs most of the fit). Throws Error for an energy that is negative or not
/// finite, or for no trials.
BreakageFit fit_breakage(const std::vector<BreakageTrial>& trials, bool interval = true);

/// The spread of the energy at P = 1/2 when the groups, not the runs, are the draws: the
/// groups resampled with replacement `resamples` times (a cluster bootstrap; B. Efron, R.
/// Tibshirani, An Introduction to the Bootstrap, 1993), each resample fitted, and the 2.5 % and
/// 97.5 % points of the fitted W50 (the percentile interval). Runs of one mesh at several speeds
/// are linked (a mesh hard to split at one speed tends to be at the next), which the profile
/// interval, counting every run as a draw, does not see. A resample in which nothing broke
/// counts as a W50 of +infinity, one in which all broke as 0; one whose W50 the data do not
/// place (a clean threshold, too few mixed energies) is left out and counted. Deterministic for
/// a seed. With twenty groups a percentile interval still runs a little narrow.
///
/// The same resamples give the spread of the draw, the energy at P = 0.9 over the energy at
/// P = 0.1 (how far apart the easy and the hard groups break; its square root is the ratio
/// of speeds), by the same percentile points over the resamples that fitted: one in which
/// nothing or everything broke, or whose curve the data do not place, has no spread, so all
/// of those are left out and counted, under the same limit.
struct BreakageBootstrap {
  /// NaN: fewer than two groups, or more than 2.5 % of the resamples left out (or fewer than
  /// 40 kept); w50_hi +infinity when more than 2.5 % broke nowhere.
  double w50_lo = std::nan(""), w50_hi = std::nan("");
  int groups = 0, resamples = 0, not_fitted = 0;  ///< not_fitted: resamples left out of W50's points
  /// E(P = 0.9) / E(P = 0.1), its 2.5 % and 97.5 % points; NaN as for W50, by their own count.
  double spread_lo = std::nan(""), spread_hi = std::nan("");
  int spread_left_out = 0;  ///< resamples without a fitted curve
};
BreakageBootstrap bootstrap_w50(const std::vector<BreakageTrial>& trials, int resamples = 1000,
                                unsigned long long seed = 2003);

}  // namespace dspdem::report
