// The energy ledger's watch ([checks] energy_balance_warn): silent while the ledger closes,
// one warning naming the step, time and terms when it first opens past the limit, none after.
#include <gtest/gtest.h>

#include <cmath>

#include "time/balance_watch.hpp"

using namespace dspdem;

namespace {
// A ledger of 100 J of impact energy whose kinetic energy is `kinetic` and whose friction
// took 40 J: closed at kinetic = 60, open by (kinetic - 60) / 100 otherwise.
Energy ledger(Real kinetic) {
  Energy e;
  e.initial = 100, e.friction = 40, e.kinetic = kinetic;
  return e;
}
}  // namespace

TEST(BalanceWatch, WarnsOnceWhenTheErrorFirstPassesTheLimit) {
  BalanceWatch w(0.01);
  EXPECT_FALSE(w.update(ledger(60.0), 0, 0.0));
  EXPECT_FALSE(w.update(ledger(60.9), 10, 1e-6));  // 0.9 %: below
  const auto msg = w.update(ledger(62.0), 20, 2e-6);
  ASSERT_TRUE(msg);
  EXPECT_TRUE(w.warned());
  for (const char* s : {"0.02 of its largest term", "step 20", "t = 2e-06 s", "energy_balance_warn = 0.01",
                        "friction 40", "initial 100"})
    EXPECT_NE(msg->find(s), std::string::npos) << s << " in " << *msg;
  // Worse later, or back below and above again: no second warning.
  EXPECT_FALSE(w.update(ledger(70.0), 30, 3e-6));
  EXPECT_FALSE(w.update(ledger(60.0), 40, 4e-6));
  EXPECT_FALSE(w.update(ledger(70.0), 50, 5e-6));
}

TEST(BalanceWatch, EnergyLostWarnsAsEnergyCreatedDoes) {
  BalanceWatch w(0.01);
  EXPECT_TRUE(w.update(ledger(58.0), 5, 1e-6));  // 2 J missing
}

TEST(BalanceWatch, ZeroLimitNeverWarnsAndANaNLedgerIsLeftToTheIntegrator) {
  BalanceWatch off(0.0);
  EXPECT_FALSE(off.update(ledger(90.0), 1, 0.0));
  // A NaN ledger is the integrator's to report (non-finite state, with its element); the
  // watch does not claim it.
  // (The NaN is in a term after the first: std::max over the terms then keeps 100 as the
  // largest, and the error itself is NaN.)
  Energy e = ledger(60.0);
  e.friction = std::nan("");
  ASSERT_TRUE(std::isnan(e.balance_error()));
  BalanceWatch w(0.01);
  EXPECT_FALSE(w.update(e, 1, 0.0));
  EXPECT_FALSE(w.warned());
}
