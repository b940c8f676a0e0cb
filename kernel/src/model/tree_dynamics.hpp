#pragma once
/// \file
/// The forward dynamics of a Simbody matter subsystem whose mobilizers are all Free, Ball,
/// Pin, Slider, Universal or Weld, computed without Simbody: the small-tree fast path.
/// Simbody's realize chain costs three quarters of a small robot's step in stage bookkeeping
/// and cache access (bench/peers/results/history.md, "Instructions per step": robots_1 263 k
/// instructions a step through Simbody, 68.8 k on the fast path); the same equations here, over
/// plain arrays, give its accelerations to rounding (tests/kernel/model/tree_dynamics_test.cpp
/// compares them to 1e-12). The Simbody state keeps q and u: this class only reads them.
///
/// Conventions are Simbody's: body index 0 is Ground; a body's pose X_GB = X_GP·X_PF·X_FM(q)·X_MB;
/// its velocity is (ω, v of its origin) in Ground; body loads are (torque about the body origin,
/// force) in Ground; a Free mobilizer's q is the quaternion of R_FM then p_FM, its u is ω_FM
/// then v_FM, both in F; a Pin turns about the common Z of F and M, a Slider moves along X; a
/// Universal turns about F's X by q0, then about the new Y by q1 (R_FM = Rx(q0)·Ry(q1), u = q');
/// a Ball is a Free without translation (its q the quaternion of R_FM, its u ω_FM in F).
/// No Simbody header here (kernel/src/model's Simbody translation units are C++17).

#include <s2sim/math.hpp>

#include <vector>

namespace s2sim::model {

class TreeDynamics {
 public:
  enum class Joint { free, pin, slider, weld, universal, ball };

  /// One mobilized body, in Simbody's order (parents first); `parent` 0 is Ground.
  struct BodySpec {
    int parent = 0;
    Joint joint = Joint::weld;
    Pose X_PF;           // the mobilizer's frame on the parent
    Pose X_BM;           // and on the body
    int q0 = 0, u0 = 0;  // its first coordinate and speed in the state
    double mass_kg = 0;
    Vec3 com_B;              // body frame
    Mat3 central_inertia_B;  // about the centre of mass, body frame (kg·m²)
  };

  /// Builds the model from the bodies (Ground excluded) and the state's sizes.
  TreeDynamics(const std::vector<BodySpec>& bodies, int nq, int nu);
  /// New mass properties of a body (index as Simbody's, not Ground): what the next
  /// accelerations() takes.
  void set_mass(int body, double mass_kg, const Vec3& com_B, const Mat3& central_inertia_B);

  /// Poses and velocities of every body for the coordinates q and speeds u (Simbody's
  /// Position and Velocity stages); nothing to do when q and u are those of the last call,
  /// the velocities only when q is.
  void kinematics(const double* q, const double* u);
  /// Counts the configurations kinematics() has computed: what depends on q alone (a loop's
  /// Jacobian) is current while this is unchanged.
  long configuration() const { return configuration_; }
  /// The coordinates q of the last kinematics().
  const double* coordinates() const { return last_q_.data(); }
  /// A body's pose and velocity (index as Simbody's: 0 is Ground); after kinematics().
  const Pose& pose(int body) const { return pose_[body]; }
  const Twist& twist(int body) const { return twist_[body]; }

  /// u' for the loads: `body_loads` six numbers per body (torque about its origin, then
  /// force, Ground frame; Ground's first), `mobility_forces` one per speed. After kinematics();
  /// factors the mass matrix for solve().
  void accelerations(const double* body_loads, const double* mobility_forces, double* udot);
  /// Per body (index as Simbody's; Ground's untouched) the spatial force its mobilizer
  /// transmits to it from its parent, torque about M's origin then force, Ground: what its
  /// subtree needs for the accelerations `udot` less the loads `body_loads` applied to it
  /// (Simbody's calcMobilizerReactionForces, mobility forces included). After accelerations()
  /// at the same kinematics, with its body loads.
  void reactions(const double* body_loads, const double* udot, Wrench* at_M);
  /// The origin of a body's mobilizer frame M, Ground; after kinematics().
  const Vec3& joint_origin(int body) const { return joint_origin_[static_cast<std::size_t>(body)]; }
  /// The origin of a body's mobilizer frame F on its parent, Ground; after kinematics().
  Vec3 frame_origin(int body) const;
  /// x = M^-1·g with the mass matrix of the last accelerations() (its configuration).
  void solve(const double* g, double* x) const;
  /// The same within the tree that holds `body` alone (g and x over every speed; only that
  /// tree's are read and written): its speed range into [u_begin, u_end).
  void solve_tree_of(int body, const double* g, double* x, int& u_begin, int& u_end) const;
  /// f = Jᵀ·loads: the generalized forces of body loads (six numbers per body as in
  /// accelerations(), Ground's first); after kinematics().
  void generalized_forces(const double* body_loads, double* f);

  /// The structure, for the loop constraints (loop_constraints.hpp): a body's parent (-1 for
  /// Ground), its first speed and its number of speeds.
  int parent(int body) const { return bodies_[static_cast<std::size_t>(body)].parent; }
  int first_speed(int body) const { return bodies_[static_cast<std::size_t>(body)].u0; }
  int speed_count(int body) const { return bodies_[static_cast<std::size_t>(body)].dofs; }
  /// The velocity (ω, v of its origin, Ground) of the body owning speed k per unit of that
  /// speed, its parent held; after kinematics().
  const Twist& column(int k) const { return column_[static_cast<std::size_t>(k)]; }
  /// A body's acceleration (α, a of its origin, Ground) with every u' zero: the
  /// velocity-product terms; after accelerations().
  const Twist& bias_acceleration(int body) const {
    return bias_acceleration_[static_cast<std::size_t>(body)];
  }

 private:
  struct Body : BodySpec {
    int dofs = 0;  // speeds of its mobilizer
    Pose X_MB;     // inverse of X_BM
  };
  struct Tree {
    int u_begin, u_end;  // its speeds are contiguous (Simbody numbers them body by body)
    int matrix;          // offset of its n x n block in mass_
  };
  std::vector<Body> bodies_;  // [0] is Ground
  std::vector<Tree> trees_;
  std::vector<int> tree_of_body_;
  int nq_ = 0, nu_ = 0;
  std::vector<double> last_q_, last_u_;  // of the last kinematics()
  bool kinematics_valid_ = false;
  long configuration_ = 0;

  // Scratch, sized at construction (stepping does not allocate).
  std::vector<Pose> pose_;
  std::vector<Twist> twist_;
  std::vector<Vec3> joint_origin_;      // p_GM: the mobilizer's M origin in Ground
  std::vector<Mat3> frame_rotation_;    // R_GF: the mobilizer's F frame in Ground
  std::vector<Vec3> relative_angular_;  // ω of the body relative to its parent, Ground
  std::vector<Vec3> relative_linear_;   // v of M's origin relative to F, Ground
  std::vector<Vec3> relative_bias_;     // a Universal's ω_1 × ω_2: its axis turning (Ground)
  std::vector<Twist> bias_increment_;   // a body's velocity products beyond its parent's
  std::vector<Twist> acceleration_;     // reactions(): each body's (α, a of its origin)
  std::vector<Wrench> reaction_load_;   // reactions(): each subtree's, about its body origin
  std::vector<Twist> column_;           // per speed: the body's (ω, v) per unit speed
  std::vector<Twist> bias_acceleration_;
  std::vector<Wrench> subtree_load_;  // the force each subtree needs, about its body origin
  // A subtree's mass and its first and second moments about its body's origin, Ground axes.
  struct Composite {
    double mass_kg = 0;
    Vec3 first_moment;   // kg·m
    Mat3 second_moment;  // kg·m², the inertia about the origin
  };
  std::vector<Composite> composite_;
  // Per tree its mass matrix block (lower triangle, only the entries of a speed and its
  // ancestors: the others are zero), then its factor L, M = Lᵀ·L, in the same entries.
  std::vector<double> mass_;
  std::vector<double> rhs_;
  // Per speed the speed it hangs from, as an index within its tree (-1: none): the previous
  // speed of its own body, else the last speed of its nearest ancestor body with speeds. A row
  // of M, and of its factor, is non-zero only at the speed's chain of these.
  std::vector<int> speed_parent_;

  /// The two halves of kinematics(): poses and columns from q; velocities from u.
  void positions(const double* q);
  void velocities(const double* u);
  /// The stages of accelerations(): the velocity-product accelerations (base to tip); the
  /// loads each subtree needs for them less the applied ones, and the composite bodies (tip to
  /// base); the mass matrix's lower triangle and the right side τ − bias.
  void bias_accelerations();
  void subtree_loads(const double* body_loads);
  /// Adds to `load` (about body i's origin, Ground) what body i needs for the acceleration A
  /// (α, a of its origin) less what is applied to it: Newton–Euler about its centre of mass,
  /// moved to its origin. Returns `load`; its centre of mass's arm c and its inertia I about it
  /// (Ground) come out too.
  const Wrench& add_own_load(std::size_t i, const Twist& A, const double* body_loads, Wrench& load,
                             Vec3& c, Mat3& I) const;
  void mass_matrix_and_right_side(const double* mobility_forces);
  /// M = Lᵀ·L, tip to base, without fill-in (Featherstone's LTL factorisation).
  void factor(const Tree& t);
  /// x = M^-1·b within tree t (b and x point at its first speed; x may be b); after factor(t).
  void substitute(const Tree& t, const double* b, double* x) const;
};

}  // namespace s2sim::model
