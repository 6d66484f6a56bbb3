// The energy ledger's closing error watched over a run ([checks] energy_balance_warn). The
// blow-up check stops a run only when the energy held grows past energy_blowup_factor (10)
// times its budget; a
// ledger that opens slowly (a contact creating a few per cent of the impact energy, a step
// too large for a stiff spring) runs to the end and shows only as a number in series.csv.
// A batch user reads the log: at the first series row whose error passes the limit, one
// warning names the step, the time and the terms then. A warning, not a stop: studies of the step or the
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

  /// The warning's text the first time e's balance error exceeds the limit; nothing before
  /// or after.
  std::optional<std::string> update(const Energy& e, long step, Real t) {
    if (warned_ || limit_ <= 0) return std::nullopt;
    const Real err = e.balance_error();
    if (!(err > limit_)) return std::nullopt;
    warned_ = true;
    return fmt::format(
        "energy balance off by {:.3g} of its largest term at step {}, t = {:.6g} s (checks.energy_balance_warn = "
        "{:g}): kinetic {:.4g}, internal {:.4g}, joints {:.4g}, contact springs {:.4g}, fracture {:.4g}, friction "
        "{:.4g}, damping {:.4g}, less the kick's term {:.4g} J against initial {:.4g} + work {:.4g} J; series.csv's "
        "balance_error shows how it grew (warned once per run)",
        err, step, t, limit_, e.kinetic, e.internal, e.joint_elastic, e.contact_elastic, e.fracture_I + e.fracture_II,
        e.friction, e.damping + e.contact_damping, e.kick, e.initial, e.external_work);
  }
  bool warned() const { return warned_; }

 private:
  Real limit_;
  bool warned_ = false;
};

}  // namespace dspdem
