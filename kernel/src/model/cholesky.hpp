#pragma once
/// \file
/// Dense Cholesky factorisation and substitution for the model's small symmetric positive
/// definite systems: the implicit axis solve's rows (implicit_axes.cpp) and the fast path's
/// mass matrix per tree (tree_dynamics.cpp). Row-major n x n; a few dozen rows at most.

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

}  // namespace s2sim::model
