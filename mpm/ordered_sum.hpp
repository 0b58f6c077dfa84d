#pragma once
// Sums over a parallel loop that are bitwise the same on every run with the same thread count.
// An OpenMP reduction adds the threads' partial sums in the order the threads finish, which
// changes the last bits from run to run on three threads or more; here each thread sums a fixed
// contiguous range (static schedule) and the partial sums are added in thread order.
#include <omp.h>

#include <vector>

namespace ecm::mpm {

// The sum of term(i) for i in [0, n) (term may also have side effects on element i).
template <class T, class Term>
T orderedSum(int threads, long n, T zero, Term&& term) {
  std::vector<T> partial(static_cast<std::size_t>(threads), zero);
#pragma omp parallel num_threads(threads)
  {
    T mine = zero;
#pragma omp for schedule(static)
    for (long i = 0; i < n; ++i) mine += term(i);
    partial[static_cast<std::size_t>(omp_get_thread_num())] = mine;
  }
  T total = zero;
  for (const T& p : partial) total += p;
  return total;
}

}  // namespace ecm::mpm
