// Planar subproblems of the small arms: the 2R triangle, and a slide then a link.
//
// Points are written in plane coordinates (x, y) on a basis e1, e2 = k × e1 of the plane
// normal to the joints' common axis direction k; a turn by d is counter-clockwise seen
// from the side k points to. The triangle is solved by half-angle formulas that keep
// their accuracy at the folds:
//     4 L1 L2 sin²(ψ/2) = (L1 + L2 − r)(L1 + L2 + r),
//     4 L1 L2 cos²(ψ/2) = (r − |L1 − L2|)(r + |L1 − L2|),
// so that a target 1e-9 m from the first axis of a folded triangle with equal links keeps
// both solutions, and no quantity that grows with the target is squared. Out of reach
// both give their least-squares configuration (stretched or folded towards the target;
// the link across the slide).
#pragma once

#include <algorithm>
#include <cmath>

#include "kinematica/config.hpp"

namespace km::triangle {

//! Round-off of the small arms' geometry, relative to the arm's reach. A target this
//! close to the first axis of a folded triangle whose links differ by at most as much is
//! on the fold: every turn of the first joint reaches it. The same measure tells a free
//! last joint (a range of its turns reaches the target) from an isolated solution, and a
//! gap from round-off (a smaller one is not reported).
constexpr double SINGULAR_TOL = 1e-12;
//! Two branches whose angles are within twice this (rad) of each other are merging: as
//! close as the check's DEDUP_TOL, where round-off of the target moves them by as much,
//! and both may be given as one. The same relative distance from the first axis makes
//! the first turn that uncertain.
constexpr double MERGE_TOL = 1e-7;

//! What two_link says of a target.
enum class Code : int {
    regular = 0,  //!< two distinct branches (or a least-squares configuration out of reach)
    near = 1,     //!< the branches merge, or the first turn is uncertain (MERGE_TOL)
    fold = 2,     //!< on the fold continuum: every first turn solves
};

//! The rotation (rad) that turns the direction of (ax, ay) onto (bx, by).
//!
//! 0 when either vector is zero (atan2(0, 0)).
KM_HD inline double turn(double ax, double ay, double bx, double by) {
    return std::atan2(ax * by - ay * bx, ax * bx + ay * by);
}

//! The 2R triangle: turns d1, d2 with Rot(d1) (a + Rot(d2) b) = t.
//!
//! a: link 1 (first axis to second) at q = 0; b: link 2 (second axis to the point) at
//! q = 0; t: target of the point relative to the first axis (plane coordinates, m).
//! out: rows for ψ <= 0 and ψ >= 0 (ψ the angle of link 2 relative to link 1), columns
//! d1, d2 (rad, from q = 0). Out of reach both rows hold the triangle stretched (or
//! folded) towards t, its least-squares configuration.
//!
//! Returns fold on the fold continuum (t on the first axis with equal links, within
//! SINGULAR_TOL of the reach), where every d1 solves; near when the branches merge (ψ
//! within MERGE_TOL of 0 or π, at or beyond the reach's edges) or t is within MERGE_TOL
//! of the reach from the first axis; else regular.
//!
//! slack (m, default 0): the triangle is a nearby arm's, which puts the point up to slack
//! from where this one does (its axes parallel only within tolerance). Its S and C are
//! then known only to within (2 r + slack) slack (r² moves by at most that): where either
//! is below it, the real arm's two branches may straddle the fold however this triangle
//! sees it (reached twice, or not at all). The rows are then the branches with S (or C)
//! raised by that much, one on each side of the fold and at least as far from it as the
//! real arm's: a Gauss-Newton repair on the real arm carries each to the solution on its
//! side (from outside a fold's double root Newton's iterates stay outside, on their
//! side). The code is this triangle's.
KM_HD inline Code two_link(double ax, double ay, double bx, double by, double tx, double ty,
                           double (&out)[2][2], double slack = 0.0) {
    const double L1 = std::hypot(ax, ay);
    const double L2 = std::hypot(bx, by);
    const double r = std::hypot(tx, ty);
    const double far = L1 + L2;
    const double near = std::fabs(L1 - L2);
    const double S0 = (far - r) * (far + r);    // 4 L1 L2 sin²(ψ/2)
    const double C0 = (r - near) * (r + near);  // 4 L1 L2 cos²(ψ/2)
    const double margin = slack * (2.0 * r + slack);
    const bool straddle = margin > 0.0 && (S0 < margin || C0 < margin);
    const double S = straddle && S0 < margin ? S0 + margin : S0;
    const double C = straddle && C0 < margin ? C0 + margin : C0;
    double psi, vx, vy;
    if (S <= 0.0) {  // stretched (a double root) or beyond
        psi = 0.0;
        vx = far;
        vy = 0.0;
    } else if (C <= 0.0) {  // folded or inside the hole
        psi = PI;
        vx = L1 - L2;
        vy = 0.0;
    } else {  // r < L1 + L2 here: r * r cannot overflow
        const double sS = std::sqrt(S);
        const double sC = std::sqrt(C);
        psi = 2.0 * std::atan2(sS, sC);
        if (straddle) {  // S + C is no longer 4 L1 L2: the point of the raised ψ
            vx = L1 + L2 * std::cos(psi);
            vy = L2 * std::sin(psi);
        } else {
            vx = (r * r + (L1 - L2) * far) / (2.0 * L1);  // the point in link 1's frame
            vy = sS * sC / (2.0 * L1);                     // the triangle's height over link 1
        }
    }
    const double a0 = std::atan2(ay, ax);
    const double psi0 = turn(ax, ay, bx, by);
    for (int row = 0; row < 2; ++row) {
        const double sg = row == 0 ? -1.0 : 1.0;
        out[row][0] = turn(vx, sg * vy, tx, ty) - a0;
        out[row][1] = sg * psi - psi0;
    }
    const double tol = SINGULAR_TOL * far;
    if (r <= tol && near <= tol) return Code::fold;
    const double merge = MERGE_TOL * MERGE_TOL * L1 * L2;  // 4 L1 L2 sin²(MERGE_TOL / 2)
    return std::min(S0, C0) < merge || r < MERGE_TOL * far ? Code::near : Code::regular;
}

//! A slide then a link: s, d with s u + Rot(d) b = t (t from the axis at s = 0).
//!
//! out: rows "link forward" (s the smaller root: the link points along +u) and "link
//! backward"; columns s (m), d (rad). Beyond reach, both rows hold the link across the
//! slide towards t.
//!
//! Returns true when the branches merge: the link within MERGE_TOL of across the slide
//! (or beyond reach).
KM_HD inline bool slide_link(double ux, double uy, double bx, double by, double tx, double ty,
                             double (&out)[2][2]) {
    const double L = std::hypot(bx, by);
    const double along = tx * ux + ty * uy;
    const double across = std::fabs(ty * ux - tx * uy);
    const double root = across < L ? std::sqrt((L - across) * (L + across)) : 0.0;
    for (int row = 0; row < 2; ++row) {
        const double s = row == 0 ? along - root : along + root;
        out[row][0] = s;
        out[row][1] = turn(bx, by, tx - s * ux, ty - s * uy);
    }
    return root < MERGE_TOL * L;
}

}  // namespace km::triangle
