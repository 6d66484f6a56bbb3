// The energy ledger's closing error watched over a run ([checks] energy_balance_warn). The
// blow-up check stops a run only when the energy held grows past energy_blowup_factor (10)
// times its budget; a
// ledger that opens slowly (a contact creating a few per cent of the impact energy, a step
// too large for a stiff spring) runs to the end and shows only as a number in series.csv.
// A batch user reads the log: once the error has passed the limit on two rows in a row, one
// warning names the step, the time and the terms of the first. A warning, not a stop: studies of the step or the
// penalty run on purpose where the ledger opens. Not kept in checkpoints: a restarted run
// warns again if its ledger is still open.
#pragma once
#include <fmt/format.h>

#include <optional>
#include <string>

#include "time/integrator.hpp"

namespace dspdem {

class BalanceWatch {
 public:
  /// limit: the balance error (|balance| / largest term) that warns; 0: never.
  explicit BalanceWatch(Real limit) : limit_(limit) {}

  /// The warning's text the first time e's balance error has exceeded the limit on two series
  /// rows in a row (or on the run's last row); nothing before or after. One row is not
  /// enough: when a ledger has hardly begun (a platen's first touch of a body at rest, with
  /// millijoules in the books), the step's own booking of the touch reads as a per cent or
  /// so on that row and as 1e-4 on the next, with the same microjoules missing. A ledger
  /// that opens stays open, and is named at the first row it was open on.
  std::optional<std::string> update(const Energy& e, long step, Real t, bool last_row = false) {
    if (warned_ || limit_ <= 0) return std::nullopt;
    const Real err = e.balance_error();
    if (!(err > limit_)) {
      first_.reset();
      return std::nullopt;
    }
    const std::string terms = fmt::format(
        "kinetic {:.4g}, internal {:.4g}, joints {:.4g}, contact springs {:.4g}, fracture {:.4g}, friction {:.4g}, "
        "damping {:.4g}, less the kick's term {:.4g} J against initial {:.4g} + work {:.4g} J",
        e.kinetic, e.internal, e.joint_elastic, e.contact_elastic, e.fracture_I + e.fracture_II, e.friction,
        e.damping + e.contact_damping, e.kick, e.initial, e.external_work);
    if (!first_ && !last_row) {
      first_ = First{err, step, t, terms};
      return std::nullopt;
    }
    warned_ = true;
    const First f = first_ ? *first_ : First{err, step, t, terms};
    std::string then;
    if (first_) then = fmt::format("; at step {}, t = {:.6g} s, still {:.3g}", step, t, err);
    return fmt::format(
        "energy balance off by {:.3g} of its largest term at step {}, t = {:.6g} s (checks.energy_balance_warn = "
        "{:g}): {}{}; series.csv's balance_error shows how it grew (warned once per run)",
        f.err, f.step, f.t, limit_, f.terms, then);
  }
  bool warned() const { return warned_; }

 private:
  struct First {
    Real err;
    long step;
    Real t;
    std::string terms;
  };
  Real limit_;
  bool warned_ = false;
  std::optional<First> first_;  ///< the row that passed the limit, until the next confirms it
};

}  // namespace dspdem
