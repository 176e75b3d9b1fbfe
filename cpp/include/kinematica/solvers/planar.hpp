// Closed-form IK of planar arms and the SCARA, one target: every branch.
//
// Every revolute axis of these arms is parallel to one direction k; the slide of the PR /
// PRR arms moves across k, the SCARA's slide along it. In the plane normal to k
// (coordinates on e1, e2 = k × e1; angles counter-clockwise seen from the side k points
// to) a revolute joint turns everything after it by ± its angle, so the problem is
// planar. It is written on the joint axes at q = 0 (product of exponentials), so any
// base, tool, offset and DH convention is the same problem: up to three revolute joints,
// an optional slide across k before them, an optional slide along k (it commutes with the
// rest and takes the height).
//
// * Pose targets: the orientation gives the total turn φ (the sum of the revolute turns)
//   and pins the last revolute axis at w = p + R w_tool; the joints before it take that
//   axis to w: a 2R triangle (3R, SCARA: two branches), a slide and a link (PRR: two),
//   one link (2R: one solution), the slide alone (PR: one). The last turn is φ minus the
//   others.
// * Position targets: the joints take the tool origin to the target (2R, PR: two
//   branches). An arm with a third joint in the plane (3R, PRR, SCARA) has a continuum:
//   its last revolute joint is free (singular); its representative turn is the first,
//   from the middle of its range outwards, that puts a candidate within the joint limits
//   (see free_last).
//
// Candidates are never withheld: out of reach each subproblem gives its least-squares
// configuration (the triangle stretched or folded towards the target, the link across
// the slide) for the check to judge by forward kinematics, and gap is the exact distance
// from the target position to the reachable set of the tool origin. On the first axis of
// a folded triangle with equal links every first turn solves it (singular, that joint
// free, and the last one for pose targets: it turns with it). No quantity that grows with
// the target is squared: a target at 1e300 m gives finite candidates and its gap.
//
// An arm is of its class when its axes are parallel (or normal) within the
// classification's tolerance; the solver solves the ideal arm. When the real one differs
// from it by more than round-off (slack: its axes' tilts times the arm's size), the gap
// shrinks by that much, the ideal arm's continua (which the real one may not have) are
// near (a miss there is no proof), and slides put beyond a limit by less than it go onto
// the limit. near also marks targets where two branches merge (MERGE_TOL).
//
// Maxima and minima are std::max / std::min nested left to right, in the order the
// formulas name their terms: each keeps its first argument unless the second is strictly
// greater (smaller), so what a NaN term gives depends on that order, which is fixed.
#pragma once

#include <algorithm>
#include <cmath>

#include "kinematica/check.hpp"
#include "kinematica/config.hpp"
#include "kinematica/ik_types.hpp"
#include "kinematica/so3.hpp"
#include "kinematica/solvers/triangle.hpp"
#include "kinematica/types.hpp"

namespace km {

//! A planar arm (2R, 3R, PR, PRR) or a SCARA, as its solver reads it.
//!
//! Plane coordinates are on e1, e2 = k × e1 relative to origin. Filled once per arm by
//! planar::build (planar_build.hpp).
struct PlanarParams {
    //! The most joints of these arms (the SCARA's four).
    static constexpr int MAX_JOINTS = 4;
    //! The most revolute joints (3R, SCARA).
    static constexpr int MAX_REV = 3;

    int n = 0;               //!< joints of the arm (2 to 4)
    bool pose = false;       //!< true: pose targets; false: position targets (tool origin)
    bool swap = false;       //!< the triangle's branch ψ >= 0 takes slot 0 (SCARA), else ψ <= 0 does
    int slide = -1;          //!< joint index of the slide across k, or -1
    int lift = -1;           //!< joint index of the slide along k (SCARA), or -1
    double lift_sign = 0.0;  //!< k · (that slide's direction): +1 or -1
    int nrev = 0;            //!< number of revolute joints, 1 to 3
    int rev[MAX_REV] = {0, 0, 0};          //!< their joint indices, base to tip
    double sign[MAX_REV] = {0.0, 0.0, 0.0};  //!< k · (their axis direction): +1 or -1
    Vec3 k;       //!< the common axis direction (unit, base frame)
    Vec3 e1;      //!< plane basis e1 (unit, normal to k)
    Vec3 e2;      //!< plane basis e2 = k × e1
    Vec3 origin;  //!< origin of the plane coordinates: on the first revolute axis (base frame, m)
    Vec3 tool;    //!< tool origin at q = 0 (base frame, m)
    Vec3 re1;     //!< R_Mᵀ e1 (M = fk(0): the tool pose at q = 0)
    Vec3 wrist;   //!< the last revolute axis point in the tool frame at q = 0 (m)
    double axis[MAX_REV][2] = {};  //!< the revolute axis points at q = 0, plane coordinates (m)
    double tip[2] = {0.0, 0.0};    //!< the tool origin at q = 0, plane coordinates (m)
    double u[2] = {0.0, 0.0};      //!< the slide direction across k, plane coordinates (unit)
    double reach = 0.0;  //!< sum of the in-plane link lengths (m): the scale of SINGULAR_TOL
    double rmin = 0.0;   //!< least distance of the tool origin from the first revolute axis (m)
    double rmax = 0.0;   //!< largest distance from that axis (or across the slide's line) (m)
    double qlim[MAX_JOINTS][2] = {};  //!< joint limits (rad or m; ±inf where there are none)
    double slack = 0.0;  //!< how far the arm's revolute axes may put the tool from the ideal arm's (m)
    double slide_tilt = 0.0;  //!< |k · slide direction|: the slide's tilt out of the plane (sine)
    double lift_tilt = 0.0;   //!< |k × lift direction|: the SCARA slide's tilt off k (sine)
    double length = 0.0;  //!< sum of the distances between consecutive axes and to the tool (m)

    KM_HD int slots() const { return 2; }
    KM_HD int dof() const { return n; }
    //! What makes these fields no arm the solver can index safely, or nullptr.
    //!
    //! The joint indices must lie within the n joints (Q has n columns); the revolute
    //! count selects rows of axis, rev and sign.
    KM_HD const char* invalid() const {
        if (n < 1 || n > MAX_JOINTS) return "n must be 1 to 4";
        if (nrev < 1 || nrev > MAX_REV) return "nrev must be 1 to 3";
        if (slide < -1 || slide >= n) return "slide must be -1 or a joint index below n";
        if (lift < -1 || lift >= n) return "lift must be -1 or a joint index below n";
        if (nrev + (slide >= 0 ? 1 : 0) + (lift >= 0 ? 1 : 0) > n) {
            return "nrev and the slides must fit in the n joints";
        }
        for (int j = 0; j < nrev; ++j) {
            if (rev[j] < 0 || rev[j] >= n) return "rev must hold joint indices below n";
        }
        return nullptr;
    }
    //! Candidates of one target (slot 0 and 1 the two branches; labels in the builder).
    //!
    //! T: target pose of the tool (base frame); for position targets only its origin is
    //! read. Q: (2, n) out, NaN rows where a branch has no candidate. info (default on
    //! entry): singular and the free joints on a continuum, near, gap.
    KM_HD void solve(const Pose& T, double* Q, SolverInfo& info) const;
};

namespace planar {

//! Representative turns of a free last joint tried, from the middle of its range outwards
//! (each with both signs), until a candidate is within the joint limits (position targets
//! of the 3R, PRR and SCARA arms).
constexpr int FREE_SAMPLES = 33;
//! Column of the first revolute turn in a branch row (column 0: the slide).
constexpr int TURNS = 1;

//! A subproblem's branches: per row the slide (m), then the revolute turns (rad).
using Branches = double[2][1 + PlanarParams::MAX_REV];

//! Distance (m) from the target position to the reachable set of the tool origin.
//!
//! x, y: plane coordinates of the target; dz: its height over the plane.
KM_HD inline double gap(const PlanarParams& P, double x, double y, double dz) {
    const double ax = x - P.axis[0][0];
    const double ay = y - P.axis[0][1];
    double radial;
    if (P.slide >= 0) {
        const double across = std::fabs(ay * P.u[0] - ax * P.u[1]);
        radial = std::max(across - P.rmax, 0.0);
    } else {
        const double r = std::hypot(ax, ay);
        radial = std::max(std::max(r - P.rmax, P.rmin - r), 0.0);
    }
    const double height = P.lift >= 0 ? 0.0 : dz;
    return std::hypot(height, radial);
}

//! e · (R v) with R the rotation of T, summed from 0.0 term by term (the sign of a zero
//! result is that of 0.0 + ..., which atan2 reads).
KM_HD inline double rotated_dot(const Vec3& e, const Pose& T, const Vec3& v) {
    double s = 0.0;
    for (int i = 0; i < 3; ++i) {
        s += e[i] * (T.x[i] * v.x + T.y[i] * v.y + T.z[i] * v.z);
    }
    return s;
}

//! Slides that the ideal arm puts beyond a limit by less than slack (m) go onto it.
//!
//! The real arm's slide is uncertain by that much; the check judges the result.
KM_HD inline void snap_slides(const PlanarParams& P, double* Q, double slack) {
    const int joints[2] = {P.slide, P.lift};
    for (const int j : joints) {
        if (j < 0) continue;
        const double lo = P.qlim[j][0];
        const double hi = P.qlim[j][1];
        for (int row = 0; row < 2; ++row) {
            const double v = Q[row * P.n + j];
            if (lo - slack <= v && v < lo) {
                Q[row * P.n + j] = lo;
            } else if (hi < v && v <= hi + slack) {
                Q[row * P.n + j] = hi;
            }
        }
    }
}

//! The branch slot of a single solution (pose targets of a 2R or PR arm).
//!
//! 2R: the sign of link 2's angle relative to link 1 (as two_link's rows); PR: whether
//! the link points along the slide.
KM_HD inline int slot_of(const PlanarParams& P, const double* row) {
    if (P.slide >= 0) {
        const double bx = P.tip[0] - P.axis[0][0];
        const double by = P.tip[1] - P.axis[0][1];
        const double d = row[TURNS];
        double along = (std::cos(d) * bx - std::sin(d) * by) * P.u[0];
        along += (std::sin(d) * bx + std::cos(d) * by) * P.u[1];
        return along >= 0.0 ? 0 : 1;
    }
    const double ax = P.axis[1][0] - P.axis[0][0];
    const double ay = P.axis[1][1] - P.axis[0][1];
    const double psi = triangle::turn(ax, ay, P.tip[0] - P.axis[1][0], P.tip[1] - P.axis[1][1]);
    const bool below = std::sin(psi + row[TURNS + 1]) <= 0.0;
    return below != P.swap ? 0 : 1;
}

//! Branches of the subproblem solved by the slide and `used` revolute joints: 1 or 2.
KM_HD inline int branch_count(const PlanarParams& P, int used) {
    if (P.slide >= 0) return used == 1 ? 2 : 1;
    return used == 2 ? 2 : 1;
}

//! Place the point at y0 (q = 0) on t with the slide and `used` revolute joints.
//!
//! t, y0: plane coordinates (m). br: one row per branch (branch_count), the slide (m)
//! then the turns of the revolute joints (rad); entries the subproblem does not solve
//! are left as they are. Returns what two_link says (regular for one link or the slide
//! alone; near when a slide and a link merge).
KM_HD inline triangle::Code place(const PlanarParams& P, int used, double tx, double ty,
                                  double y0x, double y0y, Branches& br) {
    double tri[2][2];
    const double ax = P.axis[0][0];
    const double ay = P.axis[0][1];
    if (P.slide < 0 && used == 2) {
        const triangle::Code code =
            triangle::two_link(P.axis[1][0] - ax, P.axis[1][1] - ay, y0x - P.axis[1][0],
                               y0y - P.axis[1][1], tx - ax, ty - ay, tri);
        for (int row = 0; row < 2; ++row) {
            const int src = P.swap ? 1 - row : row;
            br[row][TURNS] = tri[src][0];
            br[row][TURNS + 1] = tri[src][1];
        }
        return code;
    }
    if (P.slide >= 0 && used == 1) {
        const bool near = triangle::slide_link(P.u[0], P.u[1], y0x - ax, y0y - ay, tx - ax,
                                               ty - ay, tri);
        for (int row = 0; row < 2; ++row) {
            br[row][0] = tri[row][0];
            br[row][TURNS] = tri[row][1];
        }
        return near ? triangle::Code::near : triangle::Code::regular;
    }
    if (used == 1) {  // one link
        br[0][TURNS] = triangle::turn(y0x - ax, y0y - ay, tx - ax, ty - ay);
    } else {  // the slide alone
        br[0][0] = (tx - y0x) * P.u[0] + (ty - y0y) * P.u[1];
    }
    return triangle::Code::regular;
}

//! Candidates from a subproblem's branches br: the last turn, the slot, every joint.
//!
//! value: for pose targets the total turn φ (the last turn is what the others leave of
//! it), for a free last joint its representative turn. dz: the target's height over the
//! plane (the SCARA's slide along k takes it). Q: (2, n).
KM_HD inline void emit(const PlanarParams& P, Branches& br, int used, double value, bool pose,
                       double dz, double* Q) {
    const int last = P.nrev - 1;
    const int count = branch_count(P, used);
    for (int row = 0; row < count; ++row) {
        if (used < P.nrev) {
            double total = 0.0;
            for (int j = 0; j < used; ++j) total += br[row][TURNS + j];
            br[row][TURNS + last] = pose ? value - total : value;
        }
        const int slot = count == 2 ? row : slot_of(P, br[row]);
        double* q = Q + slot * P.n;
        if (P.slide >= 0) q[P.slide] = br[row][0];
        for (int j = 0; j < P.nrev; ++j) q[P.rev[j]] = P.sign[j] * br[row][TURNS + j];
        if (P.lift >= 0) q[P.lift] = P.lift_sign * dz;
    }
}

//! True when q (n,) is within the joint limits (revolute angles modulo 2π), as the check.
KM_HD inline bool within_limits(const PlanarParams& P, const double* q) {
    for (int j = 0; j < P.n; ++j) {
        const double lo = P.qlim[j][0] - LIMIT_TOL;
        const double hi = P.qlim[j][1] + LIMIT_TOL;
        double v = q[j];
        if (j != P.slide && j != P.lift) {
            v = wrap(v);
            if (v < lo && v + TWO_PI <= hi) {
                v += TWO_PI;
            } else if (v > hi && v - TWO_PI >= lo) {
                v -= TWO_PI;
            }
        }
        if (!(lo <= v && v <= hi)) return false;
    }
    return true;
}

//! The i-th of FREE_SAMPLES samples of [0, 1], from the middle outwards to both ends.
KM_HD inline double fraction(int i) {
    const int j = (i + 1) / 2;
    const double side = i % 2 == 1 ? 1.0 : -1.0;
    return 0.5 + side * j / (FREE_SAMPLES - 1);
}

//! A value for a wholly free joint j: 0 if within its limits, else their middle.
KM_HD inline double window_rep(const PlanarParams& P, int j) {
    const double lo = P.qlim[j][0];
    const double hi = P.qlim[j][1];
    if ((lo <= 0.0 && 0.0 <= hi) || !std::isfinite(lo + hi)) return 0.0;
    return 0.5 * (lo + hi);
}

//! The length ℓ that puts the slide mid-way in its limits on one branch, or -1.
//!
//! On the forward (backward) branch the slide is along ∓ √(ℓ² − across²) for ℓ in
//! [a, z]; -1 when no such slide is within the limits.
KM_HD inline double slide_length(const PlanarParams& P, double along, double across, double a,
                                 double z, bool fwd) {
    const int j = P.slide;
    const double r_lo = std::sqrt(std::max((a - across) * (a + across), 0.0));
    const double r_hi = std::sqrt(std::max((z - across) * (z + across), 0.0));
    const double lo = P.qlim[j][0];
    const double hi = P.qlim[j][1];
    double r0, r1;
    if (fwd) {  // s = along - r: r = along - s in [along - hi, along - lo]
        r0 = std::max(r_lo, along - hi);
        r1 = std::min(r_hi, along - lo);
    } else {  // s = along + r
        r0 = std::max(r_lo, lo - along);
        r1 = std::min(r_hi, hi - along);
    }
    if (r0 > r1) return -1.0;
    const double r = std::isfinite(r0 + r1) ? 0.5 * (r0 + r1)
                                             : std::min(std::max(0.5 * (r_lo + r_hi), r0), r1);
    return std::hypot(r, across);
}

//! What free_last's tries share: the target, its height, the last two links and their angle.
struct FreeContext {
    double x, y;   //!< the target, plane coordinates (m)
    double dz;     //!< its height over the plane (m)
    double Lb;     //!< link b's length: to the last axis (m)
    double Lc;     //!< link c's length: from the last axis to the tool origin (m)
    double angle;  //!< the angle from link b to link c at q = 0 (rad)
};

//! The last joint's turn (rad) that makes the last two links span ℓ.
//!
//! below: the angle from link b to link c is <= 0 (else >= 0).
KM_HD inline double free_turn(const FreeContext& ctx, double ell, bool below) {
    const double shortest = std::fabs(ctx.Lb - ctx.Lc);
    const double longest = ctx.Lb + ctx.Lc;
    const double S = std::max((longest - ell) * (longest + ell), 0.0);
    const double C = std::max((ell - shortest) * (ell + shortest), 0.0);
    const double psi = 2.0 * std::atan2(std::sqrt(S), std::sqrt(C));
    return (below ? -psi : psi) - ctx.angle;
}

//! Candidates with the free last joint turned by d; what place says.
KM_HD inline triangle::Code free_try(const PlanarParams& P, const FreeContext& ctx, double d,
                                     Branches& br, double* Q) {
    const int last = P.nrev - 1;
    const double lx = P.axis[last][0];
    const double ly = P.axis[last][1];
    const double cx = P.tip[0] - lx;
    const double cy = P.tip[1] - ly;
    const double c = std::cos(d);
    const double s = std::sin(d);
    const triangle::Code code =
        place(P, last, ctx.x, ctx.y, lx + c * cx - s * cy, ly + s * cx + c * cy, br);
    emit(P, br, last, d, false, ctx.dz, Q);
    return code;
}

//! Position targets of an arm with a third joint in the plane: its last revolute joint is free.
//!
//! The last two links, b (to the last axis) and c (from it to the tool origin), span any
//! length ℓ in [|Lb − Lc|, Lb + Lc]; the joints before reach the target (x, y) with ℓ in
//! some range. The representative is the first of these lengths (each with both signs of
//! the angle between b and c) that puts a candidate within the joint limits, else the
//! first: after a slide, the lengths that put it mid-way in its limits on either branch;
//! then FREE_SAMPLES lengths from the middle of the range outwards. A tool origin on the
//! last axis (Lc = 0) leaves that joint wholly free: 0, or the middle of its limits.
//!
//! Returns what place says of the remaining triangle.
KM_HD inline triangle::Code free_last(const PlanarParams& P, double x, double y, double dz,
                                      Branches& br, double* Q, SolverInfo& info) {
    const int last = P.nrev - 1;
    const int jl = P.rev[last];
    const bool slide = P.slide >= 0;
    const double lx = P.axis[last][0];
    const double ly = P.axis[last][1];
    const double bx = lx - P.axis[last - 1][0];
    const double by = ly - P.axis[last - 1][1];
    const double cx = P.tip[0] - lx;
    const double cy = P.tip[1] - ly;
    const double rx = x - P.axis[0][0];
    const double ry = y - P.axis[0][1];
    const double along = rx * P.u[0] + ry * P.u[1];
    double lo, hi;
    if (slide) {  // ℓ at least the distance across the slide
        lo = std::fabs(ry * P.u[0] - rx * P.u[1]);
        hi = INF;
    } else {  // the 2R triangle before it: |r - L1| <= ℓ <= r + L1
        const double r = std::hypot(rx, ry);
        const double L1 = std::hypot(P.axis[1][0] - P.axis[0][0], P.axis[1][1] - P.axis[0][1]);
        lo = std::fabs(r - L1);
        hi = r + L1;
    }
    const double Lb = std::hypot(bx, by);
    const double Lc = std::hypot(cx, cy);
    const double shortest = std::fabs(Lb - Lc);
    const double longest = Lb + Lc;
    const double a = std::max(shortest, lo);
    const double z = std::min(longest, hi);
    const double tol = triangle::SINGULAR_TOL * P.reach;
    const bool wholly = Lc <= tol;
    if (wholly || z - a > tol) {
        info.singular = true;
        info.set_free(jl);
    }
    const FreeContext ctx{x, y, dz, Lb, Lc, triangle::turn(bx, by, cx, cy)};
    if (wholly) {  // the other joints do not depend on it
        return free_try(P, ctx, window_rep(P, jl) * P.sign[last], br, Q);
    }
    if (a > z) {  // out of reach: the nearest length
        return free_try(P, ctx, free_turn(ctx, std::min(std::max(a, shortest), longest), false),
                        br, Q);
    }
    const int first = slide ? 2 : 0;  // lengths from the slide's limits first
    for (int t = 0; t < first + FREE_SAMPLES; ++t) {
        double ell;
        if (t < first) {
            ell = slide_length(P, along, lo, a, z, t == 0);
            if (ell < 0.0) continue;
        } else {
            ell = a + fraction(t - first) * (z - a);
        }
        for (int side = 0; side < 2; ++side) {
            const triangle::Code code = free_try(P, ctx, free_turn(ctx, ell, side == 1), br, Q);
            if (within_limits(P, Q) || within_limits(P, Q + P.n)) return code;
        }
    }
    return free_try(P, ctx, free_turn(ctx, 0.5 * (a + z), false), br, Q);
}

}  // namespace planar

KM_HD inline void PlanarParams::solve(const Pose& T, double* Q, SolverInfo& info) const {
    using triangle::Code;
    for (int i = 0; i < 2 * n; ++i) Q[i] = NaN;
    planar::Branches br = {};
    const int last = nrev - 1;
    double ox = T.p.x - origin.x;
    double oy = T.p.y - origin.y;
    double oz = T.p.z - origin.z;
    const double x = e1.x * ox + e1.y * oy + e1.z * oz;
    const double y = e2.x * ox + e2.y * oy + e2.z * oz;
    const double dz = k.x * (T.p.x - tool.x) + k.y * (T.p.y - tool.y) + k.z * (T.p.z - tool.z);
    // The arm's axes are parallel (or normal) to k within the classification's
    // tolerance: the ideal arm solved here may put the tool up to `slack` away from the
    // real one. Beyond round-off, a gap shrinks by it.
    double sl = slack + slide_tilt * (std::hypot(std::hypot(ox, oy), oz) + length);
    sl += lift_tilt * (std::fabs(dz) + length);
    double g = planar::gap(*this, x, y, dz);
    const bool approximate = sl > triangle::SINGULAR_TOL * reach;
    if (approximate) g -= sl;
    info.gap = g > triangle::SINGULAR_TOL * reach ? g : NaN;  // beyond round-off
    Code code;
    if (pose) {  // the orientation: the total turn, and where the last revolute axis goes
        const double phi =
            std::atan2(planar::rotated_dot(e2, T, re1), planar::rotated_dot(e1, T, re1));
        for (int i = 0; i < 3; ++i) {
            double w = T.x[i] * wrist.x + T.y[i] * wrist.y;
            w += T.z[i] * wrist.z;
            if (i == 0) {
                ox += w;
            } else if (i == 1) {
                oy += w;
            } else {
                oz += w;
            }
        }
        code = planar::place(*this, last, e1.x * ox + e1.y * oy + e1.z * oz,
                             e2.x * ox + e2.y * oy + e2.z * oz, axis[last][0], axis[last][1], br);
        planar::emit(*this, br, last, phi, true, dz, Q);
        if (code == Code::fold) info.set_free(rev[last]);  // the last joint turns with the first
    } else if (nrev + (slide >= 0 ? 1 : 0) == 3) {
        code = planar::free_last(*this, x, y, dz, br, Q, info);
    } else {
        code = planar::place(*this, nrev, x, y, tip[0], tip[1], br);
        planar::emit(*this, br, nrev, 0.0, false, dz, Q);
    }
    if (code == Code::fold) {
        info.singular = true;
        info.set_free(rev[0]);
    }
    // Merging branches, or a continuum of the ideal arm that the real one may not have
    // (its axes parallel within tolerance only): a miss is no proof.
    if (code == Code::near || (approximate && info.singular)) info.near = true;
    if (approximate) planar::snap_slides(*this, Q, sl);
}

}  // namespace km
