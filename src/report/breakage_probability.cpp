#include "report/breakage_probability.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <random>
#include <utility>

#include "core/error.hpp"

namespace dspdem::report {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kLn2 = 0.69314718055994530942;
// The chi-square quantile of one degree of freedom at 95 %: the deviance that bounds the
// profile-likelihood interval.
constexpr double kDeviance95 = 3.841458820694124;

// The argument in [a, b] that maximises f, by golden-section search: the profile likelihoods
// below are smooth and single-peaked inside the bracket the grid search hands over.
template <class F>
double golden_max(const F& f, double a, double b, int iterations = 60) {
  const double g = 0.61803398874989484820;
  double c = b - g * (b - a), d = a + g * (b - a), fc = f(c), fd = f(d);
  for (int i = 0; i < iterations && b - a > 1e-14 * std::max(1.0, std::abs(b)); ++i) {
    if (fc >= fd)
      b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
    else
      a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
  }
  return fc >= fd ? c : d;
}

// The maximum of f over [a, b): a grid of n points first (a profile likelihood may have
// more than one bump near the threshold), then golden section round the best of them.
template <class F>
double grid_then_golden(const F& f, double a, double b, int n, double& best) {
  int jbest = 0;
  best = -kInf;
  for (int j = 0; j < n; ++j) {
    const double v = f(a + (b - a) * j / n);
    if (v > best) best = v, jbest = j;
  }
  const double lo = a + (b - a) * std::max(0, jbest - 1) / n, hi = a + (b - a) * (jbest + 1) / n;
  const double x = golden_max(f, lo, std::min(hi, b - 1e-12 * (b - a)));
  const double v = f(x);
  if (v > best) {
    best = v;
    return x;
  }
  return a + (b - a) * jbest / n;
}

// The rate that maximises the likelihood at a given w_min: the root of the score in the
// rate, sum over broken runs of e / (exp(rate e) - 1) = sum over held runs of e, with e = W -
// w_min > 0. The left side falls from +infinity to 0, so with a held run above w_min there is
// exactly one root; it is found by bisection on log(rate).
double best_rate(const std::vector<BreakageTrial>& t, double w_min) {
  double held = 0, e_max = 0;
  for (const auto& x : t) {
    const double e = x.energy - w_min;
    if (e <= 0) continue;
    e_max = std::max(e_max, e);
    if (!x.broken) held += e;
  }
  DSPDEM_ASSERT(held > 0 && e_max > 0);
  auto score = [&](double log_rate) {
    const double r = std::exp(log_rate);
    double s = -held;
    for (const auto& x : t)
      if (x.broken) s += (x.energy - w_min) / std::expm1(r * (x.energy - w_min));
    return s;
  };
  double lo = -std::log(e_max), hi = lo;
  for (int i = 0; i < 400 && score(lo) < 0; ++i) lo -= 1;
  for (int i = 0; i < 400 && score(hi) > 0; ++i) hi += 1;
  for (int i = 0; i < 60 && hi - lo > 1e-13; ++i) {
    const double m = 0.5 * (lo + hi);
    (score(m) > 0 ? lo : hi) = m;
  }
  return std::exp(0.5 * (lo + hi));
}

}  // namespace

double BreakageFit::probability(double w) const {
  DSPDEM_CHECK(outcome == Outcome::fitted, "internal: the breakage probability of a curve that was not fitted");
  return w <= w_min ? 0.0 : -std::expm1(-rate * (w - w_min));
}

double BreakageFit::energy_at(double p) const {
  DSPDEM_CHECK(outcome == Outcome::fitted, "internal: the breakage energy of a curve that was not fitted");
  DSPDEM_CHECK(p > 0 && p < 1, "internal: a breakage probability of {} (0 < p < 1)", p);
  return w_min - std::log1p(-p) / rate;
}

double breakage_log_likelihood(const std::vector<BreakageTrial>& trials, double w_min, double rate) {
  double ll = 0;
  for (const auto& t : trials) {
    const double e = t.energy - w_min;
    if (t.broken) {
      if (e <= 0) return -kInf;
      ll += std::log(-std::expm1(-rate * e));
    } else if (e > 0) {
      ll -= rate * e;
    }
  }
  return ll;
}

BreakageFit fit_breakage(const std::vector<BreakageTrial>& trials, bool interval) {
  DSPDEM_CHECK(!trials.empty(), "breakage probability: no runs to fit");
  // Per energy, how many runs held and how many broke: the outcomes, the lowest energy of a
  // broken run and the highest of a held one all come from it.
  std::map<double, std::pair<int, int>> at;  // energy: held, broken
  for (const auto& t : trials) {
    DSPDEM_CHECK(std::isfinite(t.energy) && t.energy >= 0, "breakage probability: an impact energy of {} J/kg",
                 t.energy);
    ++(t.broken ? at[t.energy].second : at[t.energy].first);
  }
  BreakageFit f;
  int mixed = 0;
  double mixed_at = std::nan("");
  for (const auto& [w, hb] : at) {
    f.trials += hb.first + hb.second, f.broken += hb.second;
    if (hb.second > 0 && std::isnan(f.above)) f.above = w;
    if (hb.first > 0) f.below = w;
    if (hb.first > 0 && hb.second > 0) ++mixed, mixed_at = w;
  }
  using O = BreakageFit::Outcome;
  if (f.broken == 0) return f.outcome = O::none_broke, f;
  if (f.broken == f.trials) return f.outcome = O::all_broke, f;
  if (f.below < f.above) return f.outcome = O::separated, f;
  // With broken and held runs mixed at one energy L only, the likelihood's top is a ridge or is
  // reached only as the rate grows without bound and W_min tends to L: P(L) is fixed and
  // nothing else, and a search would hand back whichever point of the ridge it met first. With
  // none (a run held above one that broke, each energy all one way) the data cross without a
  // draw to fit either.
  if (mixed < 2) return f.mixed_energy = mixed_at, f.outcome = O::too_few_mixed, f;
  f.outcome = O::fitted;

  // W_min lies in [0, the lowest energy of a broken run): at or above it that run could not
  // have broken. The likelihood is maximised over the rate for each W_min in closed form up
  // to a root (best_rate), and over W_min by search.
  auto profile = [&](double w_min) { return breakage_log_likelihood(trials, w_min, best_rate(trials, w_min)); };
  double best = -kInf;
  f.w_min = grid_then_golden(profile, 0.0, f.above, 128, best);
  f.rate = best_rate(trials, f.w_min);
  f.log_likelihood = breakage_log_likelihood(trials, f.w_min, f.rate);
  if (!interval) return f;

  // The profile likelihood of W50, the energy at P = 1/2: over W_min below both W50 and the
  // lowest broken run, with the rate that puts P = 1/2 at W50.
  auto profile50 = [&](double w50) {
    double best = -kInf;
    grid_then_golden([&](double w_min) { return breakage_log_likelihood(trials, w_min, kLn2 / (w50 - w_min)); }, 0.0,
                     std::min(w50, f.above), 64, best);
    return best;
  };
  const double w50 = f.energy_at(0.5);
  const double top = std::max(f.log_likelihood, profile50(w50));
  auto outside = [&](double w) { return 2 * (top - profile50(w)) > kDeviance95; };
  auto bisect = [&](double in, double out) {
    for (int i = 0; i < 80 && std::abs(out - in) > 1e-9 * std::abs(in); ++i) {
      const double m = 0.5 * (in + out);
      (outside(m) ? out : in) = m;
    }
    return 0.5 * (in + out);
  };
  const double tiny = 1e-9 * w50;
  f.w50_lo = outside(tiny) ? bisect(w50, tiny) : 0.0;
  double out = 2 * w50;
  for (int i = 0; i < 60 && !outside(out); ++i) out *= 2;
  f.w50_hi = outside(out) ? bisect(out / 2, out) : kInf;  // out / 2 is w50 or a point found inside
  return f;
}

BreakageBootstrap bootstrap_w50(const std::vector<BreakageTrial>& trials, int resamples, unsigned long long seed) {
  DSPDEM_CHECK(resamples > 0, "breakage probability: {} bootstrap resamples", resamples);
  std::map<int, std::vector<BreakageTrial>> by_group;
  for (const auto& t : trials) by_group[t.group].push_back(t);
  std::vector<const std::vector<BreakageTrial>*> groups;
  for (const auto& [g, runs] : by_group) groups.push_back(&runs);
  BreakageBootstrap b;
  b.groups = static_cast<int>(groups.size()), b.resamples = resamples;
  if (groups.size() < 2) return b;
  // The generator's own output, reduced by a modulus: its bias, under n / 2^64, is nothing
  // beside the bootstrap's, and unlike std::uniform_int_distribution it gives the same draws
  // with every standard library.
  std::mt19937_64 rng(seed);
  std::vector<double> w50, spread;
  std::vector<BreakageTrial> sample;
  for (int r = 0; r < resamples; ++r) {
    sample.clear();
    for (std::size_t k = 0; k < groups.size(); ++k) {
      const auto* g = groups[rng() % groups.size()];
      sample.insert(sample.end(), g->begin(), g->end());
    }
    // A resample in which nothing broke has its W50 above every run, one in which all broke
    // below every run: they are the tails, kept as +infinity and 0 (dropping them would narrow
    // the interval). One with a clean threshold or too few mixed energies has a W50 the data do
    // not place: dropped, and counted.
    const BreakageFit f = fit_breakage(sample, false);
    using O = BreakageFit::Outcome;
    if (f.outcome == O::fitted)
      w50.push_back(f.energy_at(0.5)), spread.push_back(f.energy_at(0.9) / f.energy_at(0.1));
    else if (f.outcome == O::none_broke)
      w50.push_back(kInf);
    else if (f.outcome == O::all_broke)
      w50.push_back(0.0);
    else
      ++b.not_fitted;
  }
  b.spread_left_out = resamples - static_cast<int>(spread.size());
  // More dropped than one tail holds would move the 2.5 % points by more than their own
  // meaning: no interval then. The percentile points by the nearest rank: the smallest value
  // with at least a share q of the values at or below it.
  auto points = [&](std::vector<double>& v, int left_out, double& lo, double& hi) {
    if (left_out > 0.025 * resamples || v.size() < 40) return;
    std::sort(v.begin(), v.end());
    auto at = [&](double q) {
      const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
      return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
    };
    lo = at(0.025), hi = at(0.975);
  };
  points(w50, b.not_fitted, b.w50_lo, b.w50_hi);
  points(spread, b.spread_left_out, b.spread_lo, b.spread_hi);
  return b;
}

}  // namespace dspdem::report
