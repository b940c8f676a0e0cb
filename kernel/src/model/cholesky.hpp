#pragma once
/// \file
/// Dense Cholesky factorisation and substitution for the model's small symmetric positive
/// definite systems: the implicit axis solve's rows (implicit_axes.cpp) and the fast path's
/// mass matrix per tree (tree_dynamics.cpp); and a pivoted one for the semidefinite systems of
/// redundant loop constraints (loop_constraints.cpp). Row-major n x n; a few dozen rows at most.

#include <cmath>

namespace s2sim::model {

/// Replaces A's lower triangle with L, A = L·Lᵀ (the upper triangle is not read). Returns
/// whether every pivot was positive; past a bad one it goes on (its NaNs propagate) so that the
/// caller decides.
inline bool cholesky_factor(double* A, int n) {
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

/// x = A^-1·b from cholesky_factor's L; x may be b. Leading zeros of b (a unit vector's) are
/// skipped: they give zeros.
inline void cholesky_substitute(const double* L, int n, const double* b, double* x) {
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

/// Solves A·x = b for a symmetric positive semidefinite A whose rank may be below n (loop
/// constraints counted twice, a planar four-bar's out-of-plane rows): Cholesky with the
/// largest remaining diagonal as pivot, stopping where what remains is below
/// `relative_tolerance` times A's largest diagonal. The unknowns of the rows left out are zero:
/// for b in A's range (G·u for A = G·Gᵀ, say) that is an exact solution. A and b are
/// overwritten; `order` holds n ints of scratch. Returns the rank found.
inline int semidefinite_solve(double* A, int n, double* b, double* x, int* order,
                              double relative_tolerance) {
  double largest = 0;
  for (int i = 0; i < n; ++i) {
    order[i] = i;
    largest = std::fmax(largest, A[i * n + i]);
  }
  const double floor = relative_tolerance * largest;
  int rank = 0;
  for (; rank < n; ++rank) {
    const int j = rank;
    int p = j;
    for (int i = j + 1; i < n; ++i)
      if (A[i * n + i] > A[p * n + p]) p = i;
    if (!(A[p * n + p] > floor)) break;
    if (p != j) {  // the symmetric swap of rows and columns j and p
      for (int k = 0; k < n; ++k) {
        const double t = A[j * n + k];
        A[j * n + k] = A[p * n + k];
        A[p * n + k] = t;
      }
      for (int k = 0; k < n; ++k) {
        const double t = A[k * n + j];
        A[k * n + j] = A[k * n + p];
        A[k * n + p] = t;
      }
      const double t = b[j];
      b[j] = b[p];
      b[p] = t;
      const int o = order[j];
      order[j] = order[p];
      order[p] = o;
    }
    const double d = std::sqrt(A[j * n + j]);
    A[j * n + j] = d;
    for (int i = j + 1; i < n; ++i) {
      A[i * n + j] /= d;
      A[j * n + i] = A[i * n + j];
    }
    for (int i = j + 1; i < n; ++i)  // the trailing block, both triangles (for the swaps)
      for (int k = j + 1; k < n; ++k)
        A[i * n + k] -= A[i * n + j] * A[k * n + j];
  }
  for (int i = 0; i < rank; ++i) {  // L·y = b on the rows kept
    double v = b[i];
    for (int k = 0; k < i; ++k)
      v -= A[i * n + k] * b[k];
    b[i] = v / A[i * n + i];
  }
  for (int i = rank; i-- > 0;) {  // Lᵀ·z = y
    double v = b[i];
    for (int k = i + 1; k < rank; ++k)
      v -= A[k * n + i] * b[k];
    b[i] = v / A[i * n + i];
  }
  for (int i = 0; i < n; ++i)
    x[order[i]] = i < rank ? b[i] : 0.0;
  return rank;
}

}  // namespace s2sim::model
