#include "gl_math.hpp"

namespace s2sim::render {

Mat4 inverse(const Mat4& a) {
  // Gauss-Jordan on a 4x8 augmented matrix: small, clear and fast enough for once a click.
  double w[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 8; ++j)
      w[i][j] = j < 4 ? a.at(i, j) : (j - 4 == i ? 1.0 : 0.0);
  for (int c = 0; c < 4; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(w[r][c]) > std::fabs(w[pivot][c])) pivot = r;
    if (std::fabs(w[pivot][c]) < 1e-12) return Mat4{};
    for (int j = 0; j < 8; ++j)
      std::swap(w[c][j], w[pivot][j]);
    const double d = w[c][c];
    for (int j = 0; j < 8; ++j)
      w[c][j] /= d;
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double f = w[r][c];
      for (int j = 0; j < 8; ++j)
        w[r][j] -= f * w[c][j];
    }
  }
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      r.at(i, j) = static_cast<float>(w[i][j + 4]);
  return r;
}

}  // namespace s2sim::render
