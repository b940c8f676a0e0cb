#pragma once
/// \file
/// Dense Cholesky factorisation and substitution for small symmetric positive definite
/// systems: the implicit axis solve's rows (model/implicit_axes.cpp, model/axis_modes.cpp; the
/// tree's mass matrix has its own sparse factor, model/tree_dynamics.cpp) and the exact stop
/// groups (contact/stop_graph.cpp), contact friction's blocks (model/friction_sweeps.cpp); and a
/// pivoted one for the semidefinite systems of redundant
/// loop constraints (model/loop_constraints.cpp). Row-major n x n; a few dozen rows at most.

#include <cmath>
#include <type_traits>

namespace s2sim::common {

namespace detail {

// The bodies of the factorisation and the substitution, for a size given at run time (int) or
// at compile time (std::integral_constant, whose loops the compiler unrolls): the same
// operations in the same order, so the same numbers.
template <class Size>
inline bool cholesky_factor(double* A, Size size) {
  const int n = size;
  bool positive = true;
  for (int j = 0; j < n; ++j) {
    double d = A[j * n + j];
    for (int k = 0; k < j; ++k)
      d -= A[j * n + k] * A[j * n + k];
    positive = positive && d > 0;
    d = std::sqrt(d);
    A[j * n + j] = d;
    for (int i = j + 1; i < n; ++i) {
      double v = A[i * n + j];
      for (int k = 0; k < j; ++k)
        v -= A[i * n + k] * A[j * n + k];
      A[i * n + j] = v / d;
    }
  }
  return positive;
}

template <class Size>
inline void cholesky_substitute(const double* L, Size size, const double* b, double* x) {
  const int n = size;
  int first = 0;
  while (first < n && b[first] == 0.0)
    x[first++] = 0.0;
  for (int i = first; i < n; ++i) {  // L·y = b
    double v = b[i];
    for (int k = first; k < i; ++k)
      v -= L[i * n + k] * x[k];
    x[i] = v / L[i * n + i];
  }
  for (int i = n; i-- > 0;) {  // Lᵀ·x = y
    double v = x[i];
    for (int k = i + 1; k < n; ++k)
      v -= L[k * n + i] * x[k];
    x[i] = v / L[i * n + i];
  }
}

}  // namespace detail

/// Replaces A's lower triangle with L, A = L·Lᵀ (the upper triangle is not read). Returns
/// whether every pivot was positive; past a bad one it goes on (its NaNs propagate) so that the
/// caller decides.
inline bool cholesky_factor(double* A, int n) {
  return detail::cholesky_factor(A, n);
}

/// x = A^-1·b from cholesky_factor's L; x may be b. Leading zeros of b (a unit vector's) are
/// skipped: they give zeros.
inline void cholesky_substitute(const double* L, int n, const double* b, double* x) {
  detail::cholesky_substitute(L, n, b, x);
}

/// The same two for an n known at compile time, unrolled: the same numbers, fewer
/// instructions on the small blocks solved many times a step (contact friction's).
template <int N>
inline bool cholesky_factor(double* A) {
  return detail::cholesky_factor(A, std::integral_constant<int, N>{});
}
template <int N>
inline void cholesky_substitute(const double* L, const double* b, double* x) {
  detail::cholesky_substitute(L, std::integral_constant<int, N>{}, b, x);
}

/// Solves A·x = b for a symmetric positive semidefinite A whose rank may be below n (loop
/// constraints counted twice, a planar four-bar's out-of-plane rows): Cholesky with the
/// largest remaining diagonal as pivot, stopping where what remains is below
/// `relative_tolerance` times A's largest diagonal. The unknowns of the rows left out are zero:
/// for b in A's range (G·u for A = G·Gᵀ, say) that is an exact solution. Only A's lower
/// triangle is read; A keeps it. `scratch` holds n·n + 2·n doubles, `order` n ints. Returns the
/// rank found.
inline int semidefinite_solve(const double* A, int n, const double* b, double* x, int* order,
                              double* scratch, double relative_tolerance) {
  // Left-looking, pivots chosen by index: L's rows stay at their original index (L[r·n + k],
  // k the step), so nothing is swapped.
  double* L = scratch;
  double* d = scratch + n * n;  // what remains of each diagonal
  double* y = d + n;
  double largest = 0;
  for (int i = 0; i < n; ++i) {
    order[i] = i;
    d[i] = A[i * n + i];
    largest = std::fmax(largest, d[i]);
  }
  const double floor = relative_tolerance * largest;
  int rank = 0;
  for (; rank < n; ++rank) {
    const int j = rank;
    int p = j;
    for (int i = j + 1; i < n; ++i)
      if (d[order[i]] > d[order[p]]) p = i;
    if (!(d[order[p]] > floor)) break;
    const int t = order[j];
    order[j] = order[p];
    order[p] = t;
    const int c = order[j];
    const double pivot = std::sqrt(d[c]);
    L[c * n + j] = pivot;
    for (int i = j + 1; i < n; ++i) {
      const int r = order[i];
      double v = r > c ? A[r * n + c] : A[c * n + r];
      for (int k = 0; k < j; ++k)
        v -= L[r * n + k] * L[c * n + k];
      v /= pivot;
      L[r * n + j] = v;
      d[r] -= v * v;
    }
  }
  for (int j = 0; j < rank; ++j) {  // L·y = b on the rows kept
    const int r = order[j];
    double v = b[r];
    for (int k = 0; k < j; ++k)
      v -= L[r * n + k] * y[k];
    y[j] = v / L[r * n + j];
  }
  for (int j = rank; j-- > 0;) {  // Lᵀ·z = y
    double v = y[j];
    for (int i = j + 1; i < rank; ++i)
      v -= L[order[i] * n + j] * y[i];
    y[j] = v / L[order[j] * n + j];
  }
  for (int j = 0; j < n; ++j)
    x[order[j]] = j < rank ? y[j] : 0.0;
  return rank;
}

}  // namespace s2sim::common
