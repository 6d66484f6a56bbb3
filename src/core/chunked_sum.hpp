// Sums over a loop that runs in parallel yet do not depend on the thread count: the range is
// cut into chunks of a fixed size (not one per thread), each chunk sums its own part, and the
// parts are added in chunk order. The result is the same to the bit on any number of threads
// (though not that of one serial sum over the whole range).
#pragma once
#include <array>
#include <cstddef>
#include <vector>

#include "core/types.hpp"

namespace dspdem {

/// Runs body(begin, end) over [0, n) in chunks of `chunk` indices, in parallel, and returns
/// the sum in chunk order of the N partial sums each call returns (std::array<Real, N>).
template <int N, class Body>
std::array<Real, N> chunked_sums(std::size_t n, Body&& body, std::size_t chunk = 2048) {
  const long nc = static_cast<long>((n + chunk - 1) / chunk);
  std::vector<std::array<Real, N>> part(static_cast<std::size_t>(nc));
#pragma omp parallel for schedule(static) if (nc > 1)
  for (long c = 0; c < nc; ++c) {
    const std::size_t b = static_cast<std::size_t>(c) * chunk;
    part[static_cast<std::size_t>(c)] = body(b, b + chunk < n ? b + chunk : n);
  }
  std::array<Real, N> s{};
  for (const auto& p : part)
    for (int i = 0; i < N; ++i) s[i] += p[i];
  return s;
}

}  // namespace dspdem
