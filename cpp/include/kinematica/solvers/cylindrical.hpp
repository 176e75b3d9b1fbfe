// Closed-form IK of cylindrical arms (turn, lift, reach, and an optional roll), one target.
//
// A revolute joint turns about an axis (direction k, through o), a slide lifts along k, a
// second slide reaches across k, and a fourth joint, if any, is revolute about an axis not
// parallel to k (the roll). The turn and the lift commute (a translation along an axis
// commutes with a turn about it), so their order in the chain does not matter. On the joint
// axes at q = 0 (product of exponentials), T(q) = Rot(k, q1) Lift(q2) Reach(q3) Roll(q4) M:
//
// * Orientation: R Mᵀ = Rot(k, q1) Rot(h4, q4) (the slides do not turn). With a roll, the
//   roll axis h4 must go where R Mᵀ takes it: subproblem 1 about k gives q1, and q4 turns
//   a vector normal to h4 to Rot(k, −q1) R Mᵀ of it. Without one, R Mᵀ = Rot(k, q1) gives q1.
// * Position: Rot(k, −q1) (p − o) = x − o + q2 lift + q3 s, with x the tool origin after
//   the roll (the roll turns it on a circle about h4). Across k this fixes q3 (the reach is
//   the only motion there), along k then q2: a pose target has one solution, in the slot of
//   its branch.
// * Position targets (the roll, if any, is free: three equations, four joints; its
//   representative is 0 where that reaches, see roll_for): |v⊥ + q3 s⊥| = |p⊥|, the distance from axis 1 across k, is a
//   quadratic in q3 whose two roots are the two branches: "reach forward" (the reach points
//   toward the target) and "reach backward" (it points away, the arm over axis 1). q1 turns
//   the point onto the target, q2 takes the height. On axis 1 with the reach's line through
//   it, q1 is free (singular).
//
// Out of reach the candidates are least-squares ones (the double root at the nearest
// distance) and gap is the distance from the target to the reachable set of the tool origin
// across k: the reach's line passes axis 1 at offset c, the roll moves the tool at most rho
// off it, so no tool origin comes closer to axis 1 than c − rho. No quantity that grows with
// the target is squared: a target at 1e300 m gives finite candidates and its gap.
//
// An arm is of the family when its axes are parallel (the turn and the lift) within the
// classification's tolerance; the solver solves the ideal arm, and where the real one differs
// from it by more than round-off (slack) the gap shrinks by that much and a continuum is near.
#pragma once

#include <cmath>

#include "kinematica/config.hpp"
#include "kinematica/geometry.hpp"
#include "kinematica/ik_types.hpp"
#include "kinematica/solvers/triangle.hpp"
#include "kinematica/types.hpp"

namespace km {

//! A cylindrical arm (RPP or RPPR, the first two in either order), as its solver reads it.
//! Filled once per arm by cylindrical::build (cylindrical_build.hpp).
struct CylindricalParams {
    int n = 0;              //!< joints: 3 (turn, lift, reach) or 4 (and the roll)
    bool pose = false;      //!< true: pose targets; false: position targets (tool origin)
    int turn = 0;           //!< joint index of the turn about k: 0 or 1
    int lift = 1;           //!< joint index of the lift along k: 1 or 0 (the reach is 2, the roll 3)
    double lift_sign = 1.0; //!< k · (the lift's direction): +1 or -1
    Vec3 k;       //!< the turn's axis direction (unit, base frame)
    Vec3 o;       //!< a point on the turn's axis (m)
    Vec3 s;       //!< the reach's direction at q = 0 (unit)
    Vec3 sp;      //!< its part across k: s − (k · s) k
    double sk = 0.0;  //!< k · s
    double ss = 0.0;  //!< |sp|²: > 0 (the reach is not along k)
    Vec3 nrm;     //!< unit k × sp: the direction across both k and the reach
    Vec3 tool;    //!< the tool origin at q = 0 (m)
    Vec3 h4;      //!< the roll's axis direction (unit; n = 4)
    Vec3 c4;      //!< the foot of the tool origin on the roll's axis at q = 0 (m; n = 3: tool)
    double rho = 0.0;  //!< the tool origin's distance from the roll's axis (m; n = 3: 0)
    Vec3 w4;      //!< a unit vector normal to h4
    Vec3 rh4;     //!< R_Mᵀ h4 (M = fk(0): the tool pose at q = 0)
    Vec3 rw4;     //!< R_Mᵀ w4
    Vec3 e1;      //!< a unit vector normal to k (n = 3: the orientation's q1)
    Vec3 re1;     //!< R_Mᵀ e1
    double offset = 0.0;  //!< |nrm · (c4 − o)|: how far the reach's line passes axis 1 (m)
    double scale = 0.0;   //!< size of the arm (m): the scale of SINGULAR_TOL
    double slack = 0.0;   //!< how far the lift's tilt off k may put the tool from the ideal arm's (m)

    KM_HD int slots() const { return 2; }
    KM_HD int dof() const { return n; }
    //! What makes these fields no arm the solver can index safely, or nullptr.
    KM_HD const char* invalid() const {
        if (n != 3 && n != 4) return "n must be 3 or 4";
        if (!((turn == 0 && lift == 1) || (turn == 1 && lift == 0))) {
            return "turn and lift must be joints 0 and 1, in either order";
        }
        if (!(ss > 0.0)) return "ss must be positive (the reach is not along k)";
        return nullptr;
    }
    //! Candidates of one target: slot 0 reach forward, slot 1 reach backward.
    //!
    //! T: target pose of the tool (base frame); for position targets only its origin is
    //! read. Q: (2, n) out, NaN rows where a branch has no candidate. info (default on
    //! entry): singular and the free joints on a continuum, near where the branches merge
    //! (triangle::MERGE_TOL), gap.
    KM_HD void solve(const Pose& T, double* Q, SolverInfo& info) const;
};

namespace cylindrical {

//! The lift and the reach that take the point v (relative to o, after the turn is undone)
//! to u, the target relative to o turned back by q1: u − v = q2 lift + q3 s, solved across
//! k for q3 and along k for q2 (the part along nrm is the miss the check sees).
KM_HD inline void slides(const CylindricalParams& P, const Vec3& u, const Vec3& v, double* q) {
    const Vec3 d{u.x - v.x, u.y - v.y, u.z - v.z};
    const double q3 = dot(P.sp, d) / P.ss;
    q[P.lift] = P.lift_sign * (dot(P.k, d) - q3 * P.sk);
    q[2] = q3;
}

//! The slot of a configuration's branch: forward when the reach points toward the target
//! (the point's part along sp, seen from axis 1, is not negative).
KM_HD inline int slot_of(const CylindricalParams& P, const Vec3& v, double q3) {
    return dot(P.sp, v) + q3 * P.ss >= 0.0 ? 0 : 1;
}

//! The one candidate of pose T, in the slot of its branch (d = p − o).
KM_HD inline void pose(const CylindricalParams& P, const Pose& T, const Vec3& d, double* Q) {
    double q[4] = {0.0, 0.0, 0.0, 0.0};
    Vec3 x = P.tool;
    if (P.n == 4) {
        q[P.turn] = subproblem1(P.h4, T.rotate(P.rh4), P.k);
        const double c = std::cos(q[P.turn]);
        const double s = std::sin(q[P.turn]);
        const Vec3 g = rotate_about(P.k, c, -s, T.rotate(P.rw4));
        q[3] = subproblem1(P.w4, g, P.h4);
        const Vec3 r{P.tool.x - P.c4.x, P.tool.y - P.c4.y, P.tool.z - P.c4.z};
        const Vec3 turned = rotate_about(P.h4, std::cos(q[3]), std::sin(q[3]), r);
        x = Vec3{P.c4.x + turned.x, P.c4.y + turned.y, P.c4.z + turned.z};
    } else {
        q[P.turn] = subproblem1(P.e1, T.rotate(P.re1), P.k);
    }
    const Vec3 u = rotate_about(P.k, std::cos(q[P.turn]), -std::sin(q[P.turn]), d);
    const Vec3 v{x.x - P.o.x, x.y - P.o.y, x.z - P.o.z};
    slides(P, u, v, q);
    double* row = Q + P.n * slot_of(P, v, q[2]);
    for (int j = 0; j < P.n; ++j) row[j] = q[j];
}

//! The roll's representative for a position target at distance r from axis 1 across k,
//! and the tool origin x it gives: 0 where the reach's line then passes axis 1 within r,
//! else the turn nearest 0 that puts the line through axis 1 (every target then has two
//! distinct branches), or the nearest to it where none does.
//!
//! The roll turns the tool origin on a circle about its axis; the line's offset from axis 1
//! is then A + a cos q4 + b sin q4 (signed, along nrm).
KM_HD inline double roll_for(const CylindricalParams& P, double r, Vec3& x) {
    x = P.tool;
    if (P.n != 4 || !(P.rho > 0.0)) return 0.0;
    const Vec3 r0{P.tool.x - P.c4.x, P.tool.y - P.c4.y, P.tool.z - P.c4.z};
    const double A = dot(P.nrm, Vec3{P.c4.x - P.o.x, P.c4.y - P.o.y, P.c4.z - P.o.z});
    const double a = dot(P.nrm, r0);
    const double b = dot(P.nrm, cross(P.h4, r0));
    double q4 = 0.0;
    if (std::fabs(A + a) > r) {  // at 0 the line passes too far: through axis 1 if it can
        double roots[2];  // (else as near as it can: trig_linear's least-squares angle)
        trig_linear(a, b, -A, roots);
        q4 = std::fabs(roots[0]) <= std::fabs(roots[1]) ? roots[0] : roots[1];
    }
    const Vec3 turned = rotate_about(P.h4, std::cos(q4), std::sin(q4), r0);
    x = Vec3{P.c4.x + turned.x, P.c4.y + turned.y, P.c4.z + turned.z};
    return q4;
}

//! The distance of o + d from axis 1 (through o along k): no component squared.
KM_HD inline double across(const CylindricalParams& P, const Vec3& d) {
    const double kd = dot(P.k, d);
    return std::hypot(std::hypot(d.x - kd * P.k.x, d.y - kd * P.k.y), d.z - kd * P.k.z);
}

//! The two candidates of the tool origin at p = o + d, r = across(d) from axis 1 (the
//! roll, if any, free).
KM_HD inline void position(const CylindricalParams& P, const Vec3& d, double r, double* Q,
                           SolverInfo& info) {
    const double tol = triangle::SINGULAR_TOL * P.scale;
    Vec3 x;
    const double q4 = roll_for(P, r, x);
    const Vec3 v{x.x - P.o.x, x.y - P.o.y, x.z - P.o.z};
    // Across k: |v⊥ + q3 sp| = r; v⊥ + q3 sp = (b + q3) sp + c nrm, so
    // q3 = −b ± sqrt(r² − c²) / |sp| with c the reach line's offset from axis 1.
    const double b = dot(P.sp, v) / P.ss;
    const double c = std::fabs(dot(P.nrm, v));
    const double root = r > c ? std::sqrt(r - c) * std::sqrt(r + c) / std::sqrt(P.ss) : 0.0;
    if (r - c < triangle::MERGE_TOL * P.scale) info.near = true;  // the branches merge
    const bool on_axis = r <= tol && c <= tol;
    if (on_axis) {  // every turn puts the point on the target
        info.singular = true;
        info.set_free(P.turn);
    }
    if (P.n == 4) {  // three equations, four joints: the roll is free
        info.singular = true;
        info.set_free(3);
    }
    for (int slot = 0; slot < 2; ++slot) {
        double q[4] = {0.0, 0.0, 0.0, q4};
        q[2] = slot == 0 ? -b + root : -b - root;
        const Vec3 reached{v.x + q[2] * P.s.x, v.y + q[2] * P.s.y, v.z + q[2] * P.s.z};
        q[P.turn] = on_axis ? 0.0 : subproblem1(reached, d, P.k);
        const Vec3 u = rotate_about(P.k, std::cos(q[P.turn]), -std::sin(q[P.turn]), d);
        slides(P, u, v, q);
        double* row = Q + P.n * slot;
        for (int j = 0; j < P.n; ++j) row[j] = q[j];
    }
}

}  // namespace cylindrical

KM_HD inline void CylindricalParams::solve(const Pose& T, double* Q, SolverInfo& info) const {
    for (int i = 0; i < 2 * n; ++i) Q[i] = NaN;
    const Vec3 d{T.p.x - o.x, T.p.y - o.y, T.p.z - o.z};
    const double r = cylindrical::across(*this, d);
    if (pose) {
        cylindrical::pose(*this, T, d, Q);
    } else {
        cylindrical::position(*this, d, r, Q, info);
    }
    // No tool origin comes closer to axis 1 than offset − rho across k.
    double gap = offset - rho - r;
    gap = gap > 0.0 ? gap : 0.0;
    const double tol = triangle::SINGULAR_TOL * scale;
    if (slack > tol) {  // the lift not exactly along k
        gap -= slack;
        if (info.singular) info.near = true;  // a continuum of the ideal arm: a miss is no proof
    }
    info.gap = gap > tol ? gap : NaN;  // beyond round-off
}

}  // namespace km
