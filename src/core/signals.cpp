#include "core/signals.hpp"

namespace dspdem {

ScopedSignals::ScopedSignals(std::initializer_list<int> signals, void (*handler)(int))
    : signals_(signals), old_(signals.size()), handler_(handler) {
  for (std::size_t k = 0; k < signals_.size(); ++k) sigaction(signals_[k], nullptr, &old_[k]);
  install();
}

void ScopedSignals::install() {
  if (!held_) return;
  struct sigaction act {};
  act.sa_handler = handler_;
  sigemptyset(&act.sa_mask);
  for (std::size_t k = 0; k < signals_.size(); ++k)
    if (old_[k].sa_handler != SIG_IGN) sigaction(signals_[k], &act, nullptr);
}

void ScopedSignals::restore() {
  if (!held_) return;
  held_ = false;
  for (std::size_t k = 0; k < signals_.size(); ++k) sigaction(signals_[k], &old_[k], nullptr);
}

}  // namespace dspdem
