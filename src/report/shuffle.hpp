// Shuffles for permutation tests that give the same p on every machine, standard library and
// thread count: std::shuffle and std::uniform_int_distribution leave their algorithms to the
// library, so the same seed would relabel differently under libstdc++ and libc++.
#pragma once
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace dspdem::report {

/// A uniform integer in [0, n), n >= 1: the rejection keeps it unbiased.
inline std::uint64_t uniform_below(std::mt19937_64& g, std::uint64_t n) {
  const std::uint64_t limit = std::mt19937_64::max() - std::mt19937_64::max() % n;
  for (;;) {
    const std::uint64_t r = g();
    if (r < limit) return r % n;
  }
}

/// Fisher-Yates (Durstenfeld's form): every order equally likely.
template <class T>
void shuffle_in_place(std::vector<T>& v, std::mt19937_64& g) {
  for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[uniform_below(g, i)]);
}

}  // namespace dspdem::report
