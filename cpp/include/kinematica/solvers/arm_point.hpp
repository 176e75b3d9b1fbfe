// Where joints 1-3 (R, R, R|P) put a point: every solution, honest at the edges.
//
// Joints 1 and 2 are revolute (lines (h1, p1), (h2, p2) at q = 0); joint 3 is revolute
// or prismatic. A point c fixed after joint 3 must reach a target c_t. Write u(q3) for
// the vector from p2 to the point once joint 3 has moved, d = c_t - p1, ζ = h1ᵀd its
// height along axis 1 and ρ its distance from axis 1; joint 1 keeps both. In the plane
// normal to h2 (orthonormal e1, e2, e1 × e2 = h2) joint 2 turns the part (u1, u2) of u to
// (v1, v2); with H = h2ᵀu, L = |u|², cα = h1ᵀh2, g = h1ᵀe2 and a the distance of axes 1
// and 2 (δ = p2 - p1 = a e1):
//
//     h1ᵀ(x - p1) = ζ      →   g v2 = ζ - cα H
//     |x - p1|²   = |d|²   →   2 a v1 = |d|² - a² - L
//     joint 2 keeps |v|    →   v1² + v2² = u1² + u2²
//
// Three shoulders, decided once per arm (kinematica.ik.analytic.arm_point):
//
// * meet (a = 0, or within 1e-9 of it: PUMA, Stanford): |u(q3)| = |d| gives q3 (two
//   roots, in half-angle form), v2 follows and a + v1 = ±sqrt(ρ² - m²),
//   m = (H - cα ζ)/g (the shoulder sign);
// * parallel: H(q3) = cα ζ gives q3 (SP4, or linear for a slide); the point is where the
//   circles of radius ρ about axis 1 and |u⊥| about axis 2 cross:
//   v1 = (ρ² - |u⊥|²)/2a - a/2, v2 = ±sqrt(...)/2a (Heron's form);
// * skew (general): with axes 2 and 3 parallel H is constant, so v2 and
//   a + v1 = ±sqrt(ρ² - m²) (shoulder front, back) come first, then q3 from
//   |u|² = v1² + v2² + H²; otherwise Pieper's quartic (arm_quartic.hpp).
//
// Then q2 = atan2(u1 v2 - u2 v1, u1 v1 + u2 v2) and q1 turns the point onto the target
// about axis 1. Every radicand is a product of a signed difference of accurate lengths
// (ρ from the target's coordinates, never |d|² - ζ²; |u| - Dmin, never |u|² - Dmin² near
// 0) and positive factors, so that a point a few nanometres from an axis, or an arm
// folded back onto its shoulder, is placed to round-off, not to the square root of it
// (clamped_root).
//
// At the edges: a point on axis 1 (ρ below SINGULAR_TOL times the arm's size) leaves q1
// free, one on axis 2 leaves q2 free (0 is given and the joint flagged); a fold's signed
// distance within round-off (DOUBLE_ROOT_TOL) is a double root, one just past it
// (NEAR_TOL) gives mirrored candidates for the check; both flag the target as near a
// fold, as does a target within NEAR_SET_TOL (relative) of axis 1 or 2. Targets beyond
// the reach get a proven gap before any square is taken.
//
// Maxima and minima here are Python's (max(a, b) is b if b > a else a): the order of the
// arguments decides what a NaN gives, as it did in the reference implementation.
#pragma once

#include <cmath>
#include <cstring>

#include "../config.hpp"
#include "../geometry.hpp"
#include "../trig.hpp"
#include "../types.hpp"
#include "arm_quartic.hpp"

namespace km::decoupled {

//! A point within this distance (times the arm's size) of axis 1 leaves q1 free; within
//! it of axis 2, q2. Far below the default position tolerance (1e-10 m): any
//! representative of the free joint then reaches the target.
constexpr double SINGULAR_TOL = 1e-12;
//! A target within this distance (times the arm's size) of axis 1 or of axis 2, or a
//! wrist within this sine of aligning axes 4 and 6, is near a singular set: the joint
//! that turns about it is then determined only to round-off over this (1e-7, the check's
//! duplicate threshold), and the target is flagged.
constexpr double NEAR_SET_TOL = 1e-9;
//! A fold's signed distance within this fraction of its scale (and of the arm's size) of
//! 0 is round-off: a double root, one solution (as the check's dedupe would have it),
//! not two split by round-off and pulled further apart by ill-conditioned joints.
constexpr double DOUBLE_ROOT_TOL = 1e-14;
//! Targets farther than this (metres) from axis 1's foot point are beyond any arm: no
//! squares are taken of their coordinates (1e154² overflows).
constexpr double HUGE_REACH = 1e100;

//! Python's max(a, b): b if b > a, else a.
KM_HD inline double py_max(double a, double b) { return b > a ? b : a; }
//! Python's min(a, b): b if b < a, else a.
KM_HD inline double py_min(double a, double b) { return b < a ? b : a; }

//! The shoulder geometry (axes 1 and 2).
enum class Shoulder : int {
    meet = 0,      //!< axes 1 and 2 meet (or all but: an offset of 1e-10)
    parallel = 1,  //!< axes 1 and 2 parallel
    general = 2,   //!< skew
};

//! What ArmPoint::place reports besides the candidates.
struct ArmState {
    bool free[3] = {false, false, false};  //!< q1, q2, q3 left free (a continuum)
    bool near = false;      //!< near a singular set or a fold
    double gap = 0.0;       //!< lower bound of the distance of the target to the reachable points (m)
    double rho = 0.0;       //!< distance of the target from axis 1 (m)
    double azimuth = 0.0;   //!< the target's angle about axis 1 (rad), from a1
    //! The last slot's (xa, xb) and the q1 they gave: the two slots of a shoulder branch
    //! share them when H is constant (axes 2 and 3 parallel), and the same bits give the
    //! same q1 without a second atan2.
    double xa = NaN, xb = NaN, q1 = NaN;
};

//! u1, u2, H, L at one q3.
struct ArmValues {
    double u1 = 0.0, u2 = 0.0, H = 0.0, L = 0.0;
};

//! sqrt(diff · other), clamped where diff (a fold's signed distance) is ~0.
//!
//! A radicand is written as a signed difference diff (it vanishes at a fold, where two
//! roots merge) times positive factors other. diff within DOUBLE_ROOT_TOL · (size +
//! scale) of 0 is round-off: a double root (0 comes back). A negative diff down to
//! -(NEAR_TOL · size + DOUBLE_ROOT_TOL · scale) gives sqrt(|diff| · other): the target is
//! just past the fold as computed, but the arm's true roots (round-off, an axis offset of
//! 1e-10 the closed form neglects) may lie on either side, so both mirrored candidates go
//! to the check, which polishes them onto the true roots or rejects them. Below, NaN. A
//! double root and a target past the fold raise `near`.
//!
//! Args: diff (e.g. of two lengths), size its scale (e.g. their sum), other the other
//! factors (>= 0; negative: NaN, another factor failed), scale the arm's size (lengths)
//! or 1: the round-off where size is ~0.
KM_HD inline double clamped_root(double diff, double size, double other, double scale,
                                 bool& near) {
    const double roundoff = DOUBLE_ROOT_TOL * scale;
    if (std::fabs(diff) <= DOUBLE_ROOT_TOL * size + roundoff) {
        near = true;
        return 0.0;
    }
    if (diff < 0.0) {
        if (diff < -(NEAR_TOL * size + roundoff)) return NaN;
        near = true;
    }
    if (other < 0.0) return NaN;
    return std::sqrt(std::fabs(diff) * other);
}

//! The geometry of joints 1-3 placing a point fixed after joint 3 (base frame, q = 0).
struct ArmPoint {
    Shoulder kind = Shoulder::general;
    bool prismatic = false;   //!< joint 3 slides
    bool parallel23 = false;  //!< axes 2 and 3 parallel
    Vec3 p1{};                //!< foot point of axis 1
    Vec3 h1{}, h2{}, h3{};    //!< the axis directions
    Vec3 a1{}, b1{};          //!< with h1, a right-handed frame of axis 1
    //! Components along a1, b1 (columns) of h2, e1, e2 and p2 - p1 (rows).
    double xframe[4][2] = {};
    //! u1, u2, H, L(q3) = X[0] + X[1] cos q3 + X[2] sin q3 (revolute) or
    //! X[0] + X[1] q3 + X[2] q3² (slide).
    double u1[3] = {}, u2[3] = {}, H[3] = {}, L[3] = {};
    double a = 0.0;       //!< distance of axes 1 and 2, along e1 (signed, ~0 when they meet)
    double ca = 0.0;      //!< cos α = h1ᵀh2
    double g = 0.0;       //!< h1ᵀe2
    double elbow = 0.0;   //!< sign deciding "elbow up" (axes 2 ∥ 3)
    //! Slot 2A + B of a meeting shoulder takes the upper root of |u(q3)| = |d|.
    bool upper_root[2][2] = {{true, false}, {true, false}};
    double scale = 1.0;   //!< a length of the arm's size (m), for tolerances
    //! Bounds of |x - p1| (r) and of h1ᵀ(x - p1) (z) over the reachable points.
    double r_lo = 0.0, r_hi = INF, z_lo = -INF, z_hi = INF;
    //! Rows turn [X0², X0, Y0², Y0, 1] into the Fourier coefficients [g0, a1, b1, a2, b2]
    //! of Pieper's F (skew shoulder, revolute joint 3).
    double fourier[5][5] = {};
    // |u(q3)| in half-angle form (revolute): with m = |U0⊥| (U0 off axis 3), n = |U1|,
    // |u|² = Dmin² + 4mn cos²ψ = Dmax² - 4mn sin²ψ, ψ = (q3 - β)/2; a slide:
    // q3 = -b ± sqrt(D² - m²), b = U0ᵀh3, m = |U0⊥|.
    double beta = 0.0, dmin = 0.0, dmax = 0.0;
    double b3 = 0.0, m3 = 0.0;
    //! A second pass settles nearly meeting axes 1, 2 or nearly parallel 2, 3.
    bool refine = false;

    //! u1, u2, H, L at q3 (rad; a slide's q3 in m).
    KM_HD ArmValues values(double q3) const {
        ArmValues v;
        if (prismatic) {
            v.u1 = u1[0] + q3 * (u1[1] + q3 * u1[2]);
            v.u2 = u2[0] + q3 * (u2[1] + q3 * u2[2]);
            v.H = H[0] + q3 * (H[1] + q3 * H[2]);
            v.L = L[0] + q3 * (L[1] + q3 * L[2]);
        } else {
            double s3, c3;
            sincos(q3, s3, c3);
            v.u1 = u1[0] + c3 * u1[1] + s3 * u1[2];
            v.u2 = u2[0] + c3 * u2[1] + s3 * u2[2];
            v.H = H[0] + c3 * H[1] + s3 * H[2];
            v.L = L[0] + c3 * L[1] + s3 * L[2];
        }
        return v;
    }

    //! Distance of a target at |d| = r, h1ᵀd = ζ outside the shell (and slab).
    //!
    //! Every reachable point lies in r_lo <= |x - p1| <= r_hi (triangle inequality on
    //! x - p1 = δ + R2 u with umin <= |u| <= umax) and, with axes 1 and 2 parallel,
    //! z_lo <= h1ᵀ(x - p1) <= z_hi: a proven lower bound of the distance to the
    //! reachable set (0 inside).
    KM_HD double shell_gap(double r, double zeta) const {
        double gap = py_max(0.0, r - r_hi);
        gap = py_max(gap, r_lo - r);
        gap = py_max(gap, zeta - z_hi);
        return py_max(gap, z_lo - zeta);
    }

    //! Every (q1, q2, q3) putting the point at ct (base frame) into Q3 (four slots, NaN
    //! rows where a branch has no real solution), and what else is known of the target.
    KM_HD void place(const Vec3& ct, double Q3[4][3], ArmState& st) const {
        st = ArmState{};
        for (int k = 0; k < 4; ++k) {
            for (int j = 0; j < 3; ++j) Q3[k][j] = NaN;
        }
        double zeta = 0.0, da = 0.0, db = 0.0;  // ct - p1 along h1, a1, b1
        for (int i = 0; i < 3; ++i) {
            const double di = ct[i] - p1[i];
            zeta += di * h1[i];
            da += di * a1[i];
            db += di * b1[i];
        }
        const double big = py_max(py_max(std::fabs(zeta), std::fabs(da)), std::fabs(db));
        if (!(big < HUGE_REACH)) {  // NaN, or beyond any arm: no squares of it
            st.gap = big >= HUGE_REACH ? big - r_hi : NaN;
            st.rho = NaN;
            st.azimuth = NaN;
            if (!(st.gap > 0.0)) st.near = true;  // unbounded reach (a slide): no proof either way
            return;
        }
        const double rho = std::hypot(da, db);
        st.rho = rho;
        st.azimuth = std::atan2(db, da);
        const double dd = zeta * zeta + rho * rho;
        st.gap = shell_gap(std::sqrt(dd), zeta);
        if (rho < NEAR_SET_TOL * scale) st.near = true;
        if (kind == Shoulder::parallel) {
            parallel_shoulder(zeta, Q3, st);
        } else if (kind == Shoulder::meet || parallel23) {
            closed(zeta, dd, Q3, st);
        } else {
            general_position(zeta, dd, Q3, st);
        }
    }

    //! Slot k: q2 turns (u1, u2) onto (v1, v2), q1 turns the point onto the target.
    //!
    //! A free q1 (target on axis 1) or q2 (point on axis 2) is set to 0 and flagged; a NaN
    //! anywhere makes the whole row NaN.
    KM_HD void slot(int k, double q3, double v1, double v2, const ArmValues& vals,
                    ArmState& st, double Q3[4][3]) const {
        const double tiny = SINGULAR_TOL * scale;
        const double up2 = vals.u1 * vals.u1 + vals.u2 * vals.u2;
        const double near_set = NEAR_SET_TOL * scale;
        if (up2 < near_set * near_set) st.near = true;
        double q2;
        if (up2 < tiny * tiny) {
            q2 = 0.0;
            st.free[1] = true;
        } else {
            q2 = std::atan2(vals.u1 * v2 - vals.u2 * v1, vals.u1 * v1 + vals.u2 * v2);
        }
        double q1;
        if (st.rho < tiny) {
            q1 = 0.0;
            st.free[0] = true;
        } else {
            const double xa = vals.H * xframe[0][0] + v1 * xframe[1][0] + v2 * xframe[2][0] +
                              xframe[3][0];
            const double xb = vals.H * xframe[0][1] + v1 * xframe[1][1] + v2 * xframe[2][1] +
                              xframe[3][1];
            if (std::memcmp(&xa, &st.xa, sizeof xa) == 0 && std::memcmp(&xb, &st.xb, sizeof xb) == 0) {
                q1 = st.q1;
            } else {
                q1 = st.azimuth - std::atan2(xb, xa);
                if (q1 <= -PI) {
                    q1 += TWO_PI;
                } else if (q1 > PI) {
                    q1 -= TWO_PI;
                }
                st.xa = xa;
                st.xb = xb;
                st.q1 = q1;
            }
        }
        if (std::isnan(q1 + q2 + q3 + v1 + v2)) {
            Q3[k][0] = NaN;
            Q3[k][1] = NaN;
            Q3[k][2] = NaN;
        } else {
            Q3[k][0] = q1;
            Q3[k][1] = q2;
            Q3[k][2] = q3;
        }
    }

    //! The two q3 with a cos q3 + b sin q3 = rhs into out[2]; NaN when none.
    //!
    //! A target just past the double root (by NEAR_TOL of a² + b²) keeps the double root
    //! (see clamped_root).
    KM_HD static void q3_pair(double a, double b, double rhs, ArmState& st, double* out) {
        const double r2 = a * a + b * b;
        const double disc = r2 - rhs * rhs;
        if (std::fabs(disc) <= DOUBLE_ROOT_TOL * r2 || (-NEAR_TOL * r2 <= disc && disc < 0.0)) {
            st.near = true;
        }
        const TrigRoots found = trig_linear(a, b, rhs, out);
        if (found == TrigRoots::two && std::fabs(disc) <= DOUBLE_ROOT_TOL * r2) {  // one double root
            out[0] = std::atan2(b * rhs, a * rhs);
            out[1] = out[0];
        }
        // any_or_none: a = b = 0, q3 moves nothing here (the builder excludes it)
        if (found == TrigRoots::any_or_none || (found == TrigRoots::none && disc < -NEAR_TOL * r2)) {
            out[0] = NaN;
            out[1] = NaN;
        }
    }

    //! The two q3 with |u(q3)| = D into out[2] (upper root first), NaN when none.
    //!
    //! Half-angle form: cos²ψ = (D² - Dmin²)/4mn and sin²ψ = (Dmax² - D²)/4mn, each a
    //! product of differences of lengths, so that a point folded back onto axis 2
    //! (Dmin = 0: equal link lengths) or stretched out is placed to round-off. A slide:
    //! q3 = -b ± sqrt(D² - m²).
    KM_HD void q3_distance(double D, ArmState& st, double* out) const {
        if (prismatic) {
            const double s = clamped_root(D - m3, D + m3, D + m3, scale, st.near);
            out[0] = s - b3;
            out[1] = -s - b3;
            return;
        }
        const double c = clamped_root(D - dmin, D + dmin, D + dmin, scale, st.near);  // 2 sqrt(mn) cos ψ
        const double s = clamped_root(dmax - D, dmax + D, dmax + D, scale, st.near);  // 2 sqrt(mn) sin ψ
        const double psi = std::atan2(s, c);
        out[0] = beta + 2.0 * psi;
        out[1] = beta - 2.0 * psi;
    }

    //! (v1, v2) at the height Hq = h2ᵀu: g v2 = ζ - cα Hq, a + v1 = ±√(ρ² - m²).
    //!
    //! m = (Hq - cα ζ)/g is the part of the target's distance from axis 1 that the
    //! shoulder cannot turn away; `sign` picks the shoulder branch.
    KM_HD void shoulder_v(double zeta, double rho, double Hq, double sign, ArmState& st,
                          double* v) const {
        const double m = std::fabs((Hq - ca * zeta) / g);
        v[0] = -a + sign * clamped_root(rho - m, rho + m, rho + m, scale, st.near);
        v[1] = (zeta - ca * Hq) / g;
    }

    //! Axes 1 and 2 meet (a ~ 0), or are skew with axes 2 ∥ 3 (H ~ constant).
    //!
    //! Then |u(q3)|² = |d|² - a² - 2a v1 (meet: |d|²) gives q3, and (v1, v2) follow from
    //! H(q3); with H constant they come first and |u|² = v1² + v2² + H². One more pass
    //! with H and v1 at the found q3 settles the small coupling of nearly meeting axes (an
    //! offset of 1e-10) or nearly parallel axes 2 and 3.
    KM_HD void closed(double zeta, double dd, double Q3[4][3], ArmState& st) const {
        const double rho = st.rho;
        const bool meet = kind == Shoulder::meet;
        const int passes = refine ? 2 : 1;
        ArmValues vals;
        double roots[2] = {NaN, NaN};
        // The first pass's roots depend on the shoulder branch A only (meet: on neither),
        // so they, and a meeting shoulder's values at them, are computed once for the
        // slots that share them: the same operations on the same values, the same bits.
        double at_d[2] = {NaN, NaN};  // meet: the roots of |u| = |d|, shared by every slot
        ArmValues at_vals[2];         // meet: the values at them
        double v[2] = {NaN, NaN};
        double D = std::hypot(zeta, rho);
        if (meet) {
            q3_distance(D, st, at_d);
            at_vals[0] = values(at_d[0]);
            at_vals[1] = values(at_d[1]);
        }
        for (int A = 0; A < 2; ++A) {
            const double sign = A == 0 ? 1.0 : -1.0;
            double v_a[2] = {NaN, NaN};  // not meet: v and D at H0, and their roots
            double D_a = NaN;
            double roots_a[2] = {NaN, NaN};
            double H_v = NaN, v_h[2] = {NaN, NaN};  // v at the last height H (this branch)
            if (!meet) {
                shoulder_v(zeta, rho, H[0], sign, st, v_a);
                D_a = std::sqrt(v_a[0] * v_a[0] + v_a[1] * v_a[1] + H[0] * H[0]);
                q3_distance(D_a, st, roots_a);
            }
            for (int B = 0; B < 2; ++B) {
                if (!meet) {
                    v[0] = v_a[0];
                    v[1] = v_a[1];
                    D = D_a;
                }
                double q3 = NaN;
                for (int it = 0; it < passes; ++it) {
                    if (it == 0) {
                        roots[0] = meet ? at_d[0] : roots_a[0];
                        roots[1] = meet ? at_d[1] : roots_a[1];
                    } else {
                        q3_distance(D, st, roots);
                    }
                    if (meet) {
                        q3 = upper_root[A][B] ? roots[0] : roots[1];
                    } else {  // elbow up first: the second root is "up" where elbow · v1 > 0
                        const int first = elbow * v[0] > 0.0 ? 1 : 0;
                        q3 = B == 0 ? roots[first] : roots[1 - first];
                    }
                    if (meet && it == 0) {
                        vals = upper_root[A][B] ? at_vals[0] : at_vals[1];
                    } else {
                        vals = values(q3);
                    }
                    // (H is the same at every q3 when axes 2 and 3 are parallel: so is v)
                    if (std::memcmp(&vals.H, &H_v, sizeof H_v) != 0) {
                        shoulder_v(zeta, rho, vals.H, sign, st, v_h);
                        H_v = vals.H;
                    }
                    v[0] = v_h[0];
                    v[1] = v_h[1];
                    if (it + 1 == passes) break;  // D is for the next pass
                    if (meet) {
                        D = std::sqrt(py_max(dd - a * a - 2.0 * a * v[0], 0.0));
                    } else {
                        D = std::sqrt(v[0] * v[0] + v[1] * v[1] + vals.H * vals.H);
                    }
                }
                slot(2 * A + B, q3, v[0], v[1], vals, st, Q3);
            }
        }
    }

    //! 2a times the height where circles of radii r1, r2 with centres a apart cross.
    //!
    //! Heron's form sqrt((r1+r2+a)(r1+r2-a)(a+r2-r1)(a+r1-r2)): the factor nearest 0 is
    //! the fold (the circles touch), the others are positive.
    KM_HD static double circles(double r1, double r2, double a, double scale, bool& near) {
        const double f2 = r1 + r2 - a;
        const double f3 = a + r2 - r1;
        const double f4 = a + r1 - r2;
        const double other = r1 + r2 + a;
        if (std::fabs(f2) <= std::fabs(f3) && std::fabs(f2) <= std::fabs(f4)) {
            return clamped_root(f2, other, other * f3 * f4, scale, near);
        }
        if (std::fabs(f3) <= std::fabs(f4)) return clamped_root(f3, other, other * f2 * f4, scale, near);
        return clamped_root(f4, other, other * f2 * f3, scale, near);
    }

    //! Axes 1 and 2 parallel: H(q3) = cα ζ, then two circles in the plane of axis 1.
    KM_HD void parallel_shoulder(double zeta, double Q3[4][3], ArmState& st) const {
        const double rho = st.rho;
        double roots[2];
        const double rhs = ca * zeta - H[0];
        if (prismatic) {
            roots[0] = rhs / H[1];
            roots[1] = NaN;
        } else {
            q3_pair(H[1], H[2], rhs, st, roots);
        }
        for (int A = 0; A < 2; ++A) {
            const double sign = A == 0 ? 1.0 : -1.0;
            for (int B = 0; B < 2; ++B) {
                const double q3 = roots[B];
                const ArmValues vals = values(q3);
                const double up = std::sqrt(vals.u1 * vals.u1 + vals.u2 * vals.u2);
                const double v1 = (rho - up) * (rho + up) / (2.0 * a) - 0.5 * a;
                const double v2 = sign * circles(rho, up, a, scale, st.near) / (2.0 * a);
                slot(2 * A + B, q3, v1, v2, vals, st, Q3);
            }
        }
    }

    //! Pieper's roots q3[4] for a target; true for a self-motion.
    KM_HD bool q3_roots(double zeta, double dd, double* q, ArmState& st) const {
        const double L0 = L[0];
        const double H0 = H[0];
        if (prismatic) {
            const double sa2 = g * g;
            const double a2 = a * a;
            const double L1 = L[1];
            const double H1 = H[1];
            const double x1 = -L1;
            const double x0 = dd - a2 - L0;
            const double y1 = -ca * H1;
            const double y0 = zeta - ca * H0;
            // X = -q² + x1 q + x0, Y = y1 q + y0, L - H² = P0 q² + P1 q + P2
            const double k[5] = {
                sa2,
                -2.0 * sa2 * x1,
                sa2 * (x1 * x1 - 2.0 * x0) + 4.0 * a2 * y1 * y1 - 4.0 * a2 * sa2 * (1.0 - H1 * H1),
                2.0 * sa2 * x1 * x0 + 8.0 * a2 * y1 * y0 - 4.0 * a2 * sa2 * (L1 - 2.0 * H1 * H0),
                sa2 * x0 * x0 + 4.0 * a2 * y0 * y0 - 4.0 * a2 * sa2 * (L0 - H0 * H0),
            };
            slide_roots(k, q, st.near);
            return false;
        }
        const double X0 = dd - a * a - L0;
        const double Y0 = zeta - ca * H0;
        const double Xs = dd + a * a + std::fabs(L0);  // the sizes X0 and Y0 were computed at
        const double Ys = std::fabs(zeta) + std::fabs(ca * H0);
        const double scale2 = scale * scale;
        const double inv = 1.0 / (scale2 * scale2);
        double F[5];
        double size = 0.0;
        for (int j = 0; j < 5; ++j) {
            F[j] = (X0 * X0 * fourier[0][j] + X0 * fourier[1][j] + Y0 * Y0 * fourier[2][j] +
                    Y0 * fourier[3][j] + fourier[4][j]) *
                   inv;
            size += (Xs * Xs * std::fabs(fourier[0][j]) + Xs * std::fabs(fourier[1][j]) +
                     Ys * Ys * std::fabs(fourier[2][j]) + Ys * std::fabs(fourier[3][j]) +
                     std::fabs(fourier[4][j])) *
                    inv;
        }
        return trig_roots(F, size, q, st.near);
    }

    //! Skew axes 1, 2, axis 3 not parallel to axis 2: Pieper's roots, one slot each
    //! (ascending q3, NaN-padded).
    KM_HD void general_position(double zeta, double dd, double Q3[4][3], ArmState& st) const {
        double roots[4];
        if (q3_roots(zeta, dd, roots, st)) st.free[2] = true;
        for (int k = 0; k < 4; ++k) {
            double q3 = roots[k];
            const ArmValues vals = values(q3);
            const double v1 = (dd - a * a - vals.L) * (0.5 / a);
            const double v2 = (zeta - ca * vals.H) / g;
            const double miss = std::fabs(std::hypot(v1, v2) - std::hypot(vals.u1, vals.u2));
            if (miss > NEAR_TOL * scale) q3 = NaN;  // a complex root taken for real: drop it
            slot(k, q3, v1, v2, vals, st, Q3);
        }
    }
};

}  // namespace km::decoupled
