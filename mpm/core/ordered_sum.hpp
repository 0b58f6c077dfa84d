#pragma once
// Sums over a parallel loop that are bitwise the same on every run and on any thread count: the
// terms are summed in fixed chunks of kSumChunk (each in index order, whichever thread runs it),
// then the chunk sums in chunk order. An OpenMP reduction would add the threads' partial sums in
// the order the threads finish, and a per-thread split would change with the thread count.
#include <omp.h>

#include <algorithm>
#include <vector>

namespace ecm::mpm {

inline constexpr long kSumChunk = 1024;  // a grid of 160 x 160 nodes is 25 chunks: two threads share them evenly

// The sum of term(i) for i in [0, n) (term may also have side effects on element i).
template <class T, class Term>
T orderedSum(int threads, long n, T zero, Term&& term) {
  const long chunks = (n + kSumChunk - 1) / kSumChunk;
  std::vector<T> partial(static_cast<std::size_t>(chunks), zero);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (long c = 0; c < chunks; ++c) {
    T mine = zero;
    const long end = std::min(n, (c + 1) * kSumChunk);
    for (long i = c * kSumChunk; i < end; ++i) mine += term(i);
    partial[static_cast<std::size_t>(c)] = mine;
  }
  T total = zero;
  for (const T& p : partial) total += p;
  return total;
}

}  // namespace ecm::mpm
