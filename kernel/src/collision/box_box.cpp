// Box against box: the separating-axis test, then the edge-edge point or the clipped face.
// Every sum is written in the order FCL's Eigen expressions evaluate it (left to right, but a
// row of a column-major matrix dotted with a vector, which Eigen sums as x0 + (x1 + x2)), so
// that the result matches boxBox2 to the bit.
#include "collision/box_box.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace s2sim::collision {
namespace {

/// The axis of least penetration among the 15, in boxBox2's terms.
struct Axis {
  int code = 0;  ///< 1-3 a face of a, 4-6 a face of b, 7-15 a's edge (code-7)/3 x b's (code-7)%3
  double separation_m = 0;  ///< negative: the overlap along the axis
  Vec3 normal;              ///< unit, world frame, from a toward b
};

/// The best axis so far while the 15 are tried.
struct Search {
  double best = -std::numeric_limits<double>::max();
  int code = 0;
  int face_column = -1;  ///< the face normal's column in a's or b's rotation; -1 for an edge axis
  bool face_of_a = true;
  bool invert = false;    ///< the axis points from b toward a: flip it
  Vec3 edge_normal_in_a;  ///< for codes 7-15, unit, in a's frame
};

/// Edge I of a (its local axis) cross edge J of b: false when this axis separates the boxes.
/// `rel` is b's rotation in a's frame, `q` its absolute values padded, `pp` b's centre in a's
/// frame. Indices are template arguments so that the nine axes unroll with no index arithmetic.
template <int I, int J>
bool edge_axis_overlaps(const double ha[3], const double hb[3], const double pp[3], const Mat3& rel,
                        const double q[3][3], Search& search) {
  constexpr int i1 = (I + 1) % 3, i2 = (I + 2) % 3;
  constexpr int ilo = i1 < i2 ? i1 : i2, ihi = i1 < i2 ? i2 : i1;
  constexpr int jlo = J == 0 ? 1 : 0, jhi = J == 2 ? 1 : 2;
  // boxBox2 prefers faces: an edge axis must overlap 5 % less than the best so far to win.
  constexpr double kFacePreference = 1.05;
  const double along = pp[i2] * rel.m[i1][J] - pp[i1] * rel.m[i2][J];
  double s = std::abs(along) - (ha[ilo] * q[ihi][J] + ha[ihi] * q[ilo][J] + hb[jlo] * q[I][jhi] +
                                hb[jhi] * q[I][jlo]);
  if (s > 0) return false;
  double n[3] = {0, 0, 0};
  n[i1] = -rel.m[i2][J];
  n[i2] = rel.m[i1][J];
  const Vec3 axis{n[0], n[1], n[2]};
  const double length = norm(axis);
  if (!(length > std::numeric_limits<double>::epsilon())) return true;  // parallel edges
  s /= length;
  if (s * kFacePreference > search.best) {
    search.best = s, search.face_column = -1, search.invert = along < 0;
    search.code = 7 + 3 * I + J;
    search.edge_normal_in_a = axis / length;
  }
  return true;
}

template <int I>
bool edge_axes_overlap(const double ha[3], const double hb[3], const double pp[3], const Mat3& rel,
                       const double q[3][3], Search& search) {
  return edge_axis_overlaps<I, 0>(ha, hb, pp, rel, q, search) &&
         edge_axis_overlaps<I, 1>(ha, hb, pp, rel, q, search) &&
         edge_axis_overlaps<I, 2>(ha, hb, pp, rel, q, search);
}

/// The axis along which the boxes overlap least, or code 0 when one separates them. `ha`, `hb`
/// half sides, `r1`, `r2` rotations, `p` from a's centre to b's (world).
Axis least_overlap_axis(const double ha[3], const Mat3& r1, const double hb[3], const Mat3& r2,
                        const Vec3& p) {
  const Mat3 r1t = r1.transposed();
  const Vec3 pv = r1t * p;  // b's centre in a's frame
  const double pp[3] = {pv.x, pv.y, pv.z};
  const Mat3 rel = r1t * r2;  // b's axes in a's frame
  double q[3][3];             // |rel|
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      q[i][j] = std::abs(rel.m[i][j]);

  Search search;
  // Face normals of a, then of b: the overlap is |centre distance| minus the two projections.
  for (int i = 0; i < 3; ++i) {
    const double along = pp[i];
    const double reach = q[i][0] * hb[0] + (q[i][1] * hb[1] + q[i][2] * hb[2]);
    const double s = std::abs(along) - (reach + ha[i]);
    if (s > 0) return {};
    if (s > search.best)
      search.best = s, search.face_column = i, search.face_of_a = true, search.invert = along < 0,
      search.code = 1 + i;
  }
  for (int j = 0; j < 3; ++j) {
    const double along = dot(r2.column(j), p);
    const double reach = q[0][j] * ha[0] + q[1][j] * ha[1] + q[2][j] * ha[2];
    const double s = std::abs(along) - (reach + hb[j]);
    if (s > 0) return {};
    if (s > search.best)
      search.best = s, search.face_column = j, search.face_of_a = false, search.invert = along < 0,
      search.code = 4 + j;
  }

  // Cross products of parallel edges have zero length: pad |rel| so that round-off cannot
  // make a near-zero axis separate the boxes (Gottschalk's epsilon, scaled by the boxes).
  const double largest =
      std::max({ha[0], ha[1], ha[2], hb[0], hb[1], hb[2], 1.0});  // sides under 1 m count as 1
  const double pad = largest * 10.0 * std::numeric_limits<double>::epsilon();
  for (auto& row : q)
    for (double& x : row)
      x += pad;
  if (!edge_axes_overlap<0>(ha, hb, pp, rel, q, search) ||
      !edge_axes_overlap<1>(ha, hb, pp, rel, q, search) ||
      !edge_axes_overlap<2>(ha, hb, pp, rel, q, search))
    return {};

  Axis axis;
  axis.code = search.code;
  axis.separation_m = search.best;
  axis.normal = search.face_column >= 0 ? (search.face_of_a ? r1 : r2).column(search.face_column)
                                        : r1 * search.edge_normal_in_a;
  if (search.invert) axis.normal = -axis.normal;
  return axis;
}

/// The point of an edge-edge contact: midway between the closest points of the two edges.
Vec3 edge_edge_point(const double ha[3], const Pose& a, const double hb[3], const Pose& b,
                     const Axis& axis) {
  Vec3 on_a = a.position;  // a point of a's edge: the corner most along the normal
  for (int j = 0; j < 3; ++j) {
    const double sign = dot(a.rotation.column(j), axis.normal) > 0 ? 1 : -1;
    on_a += a.rotation.column(j) * (ha[j] * sign);
  }
  Vec3 on_b = b.position;  // and of b's edge, most against it
  for (int j = 0; j < 3; ++j) {
    const double sign = dot(b.rotation.column(j), axis.normal) > 0 ? -1 : 1;
    on_b += b.rotation.column(j) * (hb[j] * sign);
  }
  const Vec3 ua = a.rotation.column((axis.code - 7) / 3);
  const Vec3 ub = b.rotation.column((axis.code - 7) % 3);
  // Closest approach of the lines on_a + alpha ua and on_b + beta ub.
  const Vec3 d = on_b - on_a;
  const double uaub = dot(ua, ub);
  const double q1 = dot(ua, d);
  const double q2 = -dot(ub, d);
  double det = 1 - uaub * uaub;
  double alpha = 0, beta = 0;
  if (det > static_cast<double>(0.0001f)) {  // else nearly parallel: keep the corners
    det = 1 / det;
    alpha = (q1 + uaub * q2) * det;
    beta = (uaub * q1 + q2) * det;
  }
  on_a += ua * alpha;
  on_b += ub * beta;
  return (on_a + on_b) * 0.5;
}

/// Clips the quadrilateral `quad` (4 points x,y) by the rectangle |x| < half[0], |y| < half[1],
/// one side after the other (-x, +x, -y, +y); writes up to 8 points to `out` and returns how
/// many. Like boxBox2, stops as soon as a pass has produced 8 points.
int clip_quad_by_rectangle(const double half[2], const double quad[8], double out[16]) {
  double buffers[2][16];
  const double* in = quad;
  int in_count = 4;
  int pass = 0;
  for (int dir = 0; dir <= 1; ++dir) {
    for (int sign = -1; sign <= 1; sign += 2, ++pass) {
      double* res = buffers[pass % 2];
      int count = 0;
      const double limit = sign * half[dir];
      for (int k = 0; k < in_count; ++k) {
        const double* here = in + 2 * k;
        const double* next = k + 1 < in_count ? here + 2 : in;
        const bool here_inside = sign * here[dir] < half[dir];
        if (here_inside) {
          res[2 * count] = here[0];
          res[2 * count + 1] = here[1];
          if (++count == 8) break;
        }
        if (here_inside != (sign * next[dir] < half[dir])) {
          const int other = 1 - dir;
          res[2 * count + other] = here[other] + (next[other] - here[other]) /
                                                     (next[dir] - here[dir]) * (limit - here[dir]);
          res[2 * count + dir] = limit;
          if (++count == 8) break;
        }
      }
      in = res;
      in_count = count;
      if (count == 8) {
        dir = 2;  // done: leave both loops
        break;
      }
    }
  }
  for (int k = 0; k < 2 * in_count; ++k)
    out[k] = in[k];
  return in_count;
}

/// Chooses `keep` of the `count` polygon points (x,y) spread around it: point `first`, then
/// the points whose angles about the centroid are nearest to first's plus multiples of 2π/keep.
void spread_points(int count, const double xy[16], int keep, int first, int chosen[8]) {
  double cx = 0, cy = 0;
  if (count == 1) {
    cx = xy[0], cy = xy[1];
  } else if (count == 2) {
    cx = 0.5 * (xy[0] + xy[2]), cy = 0.5 * (xy[1] + xy[3]);
  } else {  // the polygon's centroid
    double area = 0;
    for (int i = 0; i < count - 1; ++i) {
      const double q = xy[i * 2] * xy[i * 2 + 3] - xy[i * 2 + 2] * xy[i * 2 + 1];
      area += q;
      cx += q * (xy[i * 2] + xy[i * 2 + 2]);
      cy += q * (xy[i * 2 + 1] + xy[i * 2 + 3]);
    }
    const double q = xy[count * 2 - 2] * xy[1] - xy[0] * xy[count * 2 - 1];
    const double scale = std::abs(area + q) > std::numeric_limits<double>::epsilon()
                             ? 1 / (3 * (area + q))
                             : static_cast<double>(1e18f);
    cx = scale * (cx + q * (xy[count * 2 - 2] + xy[0]));
    cy = scale * (cy + q * (xy[count * 2 - 1] + xy[1]));
  }
  double angle[8];
  for (int i = 0; i < count; ++i)
    angle[i] = std::atan2(xy[i * 2 + 1] - cy, xy[i * 2] - cx);
  bool available[8];
  for (int i = 0; i < count; ++i)
    available[i] = true;
  available[first] = false;
  chosen[0] = first;
  for (int j = 1; j < keep; ++j) {
    double target = j * (2 * kPi / keep) + angle[first];
    if (target > kPi) target -= 2 * kPi;
    double nearest = 1e9;
    chosen[j] = first;
    for (int i = 0; i < count; ++i) {
      if (!available[i]) continue;
      double diff = std::abs(angle[i] - target);
      if (diff > kPi) diff = 2 * kPi - diff;
      if (diff < nearest) nearest = diff, chosen[j] = i;
    }
    available[chosen[j]] = false;
  }
}

/// Appends a contact in FclPairs' form: `at_m` midway through the overlap, `normal_ab` from a
/// toward b, `depth_m` in the grown box. Keeps touching points only.
void emit(const Vec3& at_m, const Vec3& normal_ab, double depth_m, double grown_m,
          ContactPoint* out, int& n) {
  if (n == kMaxBoxBoxPoints || !(depth_m > 0)) return;
  out[n] = {at_m + normal_ab * (0.5 * depth_m), -normal_ab, depth_m - grown_m, n};
  ++n;
}

/// Points of a face contact (axis codes 1-6): the incident face of one box clipped by the
/// reference face of the other, deepest and spread points kept when more than 4.
int face_points(const double ha[3], const Pose& a, const double hb[3], const Pose& b,
                const Axis& axis, double grown_m, ContactPoint* out) {
  const bool a_is_reference = axis.code <= 3;
  const Pose& ref = a_is_reference ? a : b;
  const Pose& inc = a_is_reference ? b : a;
  const double* half_ref = a_is_reference ? ha : hb;
  const double* half_inc = a_is_reference ? hb : ha;
  const Vec3 normal_out = a_is_reference ? axis.normal : -axis.normal;  // out of ref's face

  // The incident face: the face of inc most against the reference normal.
  const Vec3 nv = inc.rotation.transposed() * normal_out;
  const double nr[3] = {nv.x, nv.y, nv.z};
  const double an[3] = {std::abs(nr[0]), std::abs(nr[1]), std::abs(nr[2])};
  int normal_axis = 0, in1 = 0, in2 = 0;
  if (an[1] > an[0]) {
    if (an[1] > an[2])
      in1 = 0, normal_axis = 1, in2 = 2;
    else
      in1 = 0, in2 = 1, normal_axis = 2;
  } else {
    if (an[0] > an[2])
      normal_axis = 0, in1 = 1, in2 = 2;
    else
      in1 = 0, in2 = 1, normal_axis = 2;
  }
  const Vec3 to_face = inc.rotation.column(normal_axis) * half_inc[normal_axis];
  const Vec3 centre = nr[normal_axis] < 0 ? inc.position - ref.position + to_face
                                          : inc.position - ref.position - to_face;

  // The reference face's normal axis and its two in-plane axes.
  const int ref_axis = a_is_reference ? axis.code - 1 : axis.code - 4;
  const int ref1 = ref_axis == 0 ? 1 : 0, ref2 = ref_axis == 2 ? 1 : 2;

  // The incident face's corners in the reference face's 2D coordinates.
  const Vec3 ref1_dir = ref.rotation.column(ref1), ref2_dir = ref.rotation.column(ref2);
  const Vec3 inc1_dir = inc.rotation.column(in1), inc2_dir = inc.rotation.column(in2);
  const double c1 = dot(ref1_dir, centre), c2 = dot(ref2_dir, centre);
  double m11 = dot(inc1_dir, ref1_dir), m12 = dot(inc2_dir, ref1_dir);
  double m21 = dot(inc1_dir, ref2_dir), m22 = dot(inc2_dir, ref2_dir);
  const double k1 = m11 * half_inc[in1], k2 = m21 * half_inc[in1];
  const double k3 = m12 * half_inc[in2], k4 = m22 * half_inc[in2];
  const double quad[8] = {c1 - k1 - k3, c2 - k2 - k4, c1 - k1 + k3, c2 - k2 + k4,
                          c1 + k1 + k3, c2 + k2 + k4, c1 + k1 - k3, c2 + k2 - k4};
  const double rectangle[2] = {half_ref[ref1], half_ref[ref2]};
  double xy[16];
  const int clipped = clip_quad_by_rectangle(rectangle, quad, xy);
  if (clipped < 1) return 0;

  // Back to 3D on the incident face (relative to ref's centre); keep the points below the
  // reference face, compacting xy alongside.
  Vec3 points[8];
  double depth[8];
  const double inv_det = 1.0 / (m11 * m22 - m12 * m21);
  m11 *= inv_det, m12 *= inv_det, m21 *= inv_det, m22 *= inv_det;
  int kept = 0;
  for (int j = 0; j < clipped; ++j) {
    const double u = m22 * (xy[j * 2] - c1) - m12 * (xy[j * 2 + 1] - c2);
    const double v = -m21 * (xy[j * 2] - c1) + m11 * (xy[j * 2 + 1] - c2);
    points[kept] = centre + inc1_dir * u + inc2_dir * v;
    depth[kept] = half_ref[ref_axis] - dot(normal_out, points[kept]);
    if (depth[kept] >= 0) {
      xy[kept * 2] = xy[j * 2];
      xy[kept * 2 + 1] = xy[j * 2 + 1];
      ++kept;
    }
  }
  if (kept < 1) return 0;

  int order[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  int count = kept;
  if (kept > kMaxBoxBoxPoints) {
    int deepest = 0;
    for (int i = 1; i < kept; ++i)
      if (depth[i] > depth[deepest]) deepest = i;
    spread_points(kept, xy, kMaxBoxBoxPoints, deepest, order);
    count = kMaxBoxBoxPoints;
  }
  // boxBox2 puts each point midway through the overlap, moving along its normal from ref's face.
  const Vec3 half_step = a_is_reference ? axis.normal : -axis.normal;
  int n = 0;
  for (int j = 0; j < count; ++j) {
    const int i = order[j];
    const Vec3 midway = points[i] + ref.position + half_step * (depth[i] / 2);
    emit(midway, axis.normal, depth[i], grown_m, out, n);
  }
  return n;
}

}  // namespace

int box_box(const Vec3& half_a_m, const Pose& pose_a, const Vec3& half_b_m, const Pose& pose_b,
            ContactPoint* out, double margin_m) {
  const double ha[3] = {half_a_m.x, half_a_m.y, half_a_m.z};
  const double hb[3] = {half_b_m.x + margin_m, half_b_m.y + margin_m, half_b_m.z + margin_m};
  const Axis axis = least_overlap_axis(ha, pose_a.rotation, hb, pose_b.rotation,
                                       pose_b.position - pose_a.position);
  if (axis.code == 0) return 0;
  if (axis.code <= 6) return face_points(ha, pose_a, hb, pose_b, axis, margin_m, out);
  int n = 0;
  emit(edge_edge_point(ha, pose_a, hb, pose_b, axis), axis.normal, -axis.separation_m, margin_m,
       out, n);
  return n;
}

}  // namespace s2sim::collision
