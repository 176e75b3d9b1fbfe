// Closed-form IK of 3R elbow arms (anthropomorphic, or with a shoulder offset), one target.
//
// Axis 1 (h1) is perpendicular to axes 2 and 3, which are parallel (direction k). As a
// product of exponentials on the axes at q = 0, T(q) = E1(q1) E2(q2) E3(q3) M: turns about
// axes parallel to k keep heights along k and compose into one turn φ = d2 + d3 about k.
//
// * Position targets (the tool origin p): k · Rot(h1, −q1)(p − p1) must equal the tool's
//   height k · (x − p1), an equation A cos θ + B sin θ = e in θ = −q1 (two roots, as in
//   the lecture notes' q1 = atan2(py, px) and q1 + π); then the arm's plane holds a 2R
//   triangle (two roots each, the lecture notes' cos q3 = (r² − a2² − a3²)/(2 a2 a3)),
//   solved by triangle::two_link. Up to four solutions. A target on axis 1 with the
//   tool's height 0 leaves q1 free (singular: representatives at q1 = 0 and π); on the
//   shoulder with equal links, q2 is free.
// * Pose targets: a 3R arm has one solution per reachable pose, and the orientation alone
//   fixes it where the position cannot (on axis 1, at the fold): Rot(h1, q1) k = R Mᵀ k
//   gives q1 (k is not on axis 1), Rot(h1, −q1) R Mᵀ = Rot(k, φ) gives φ, and then
//   Rot(d2) a = t − Rot(φ) b in the arm's plane gives d2. The candidate takes the slot of
//   its branch; the check judges the whole pose.
//
// Out of reach the candidates are least-squares ones (the height equation's nearest root,
// the triangle stretched or folded towards the target) and gap is a proven lower bound of
// the distance to the reachable positions: the height equation's miss, and the tool's
// distance from the foot of the common normal of axes 1 and 2 against the range it can
// take. near marks targets where two roots merge (MERGE_TOL), or q1 is uncertain (the
// target that close to axis 1), and continua of an arm whose axes 2 and 3 are parallel
// within tolerance only (slack; the gap shrinks by it).
#pragma once

#include <algorithm>
#include <cmath>

#include "kinematica/config.hpp"
#include "kinematica/geometry.hpp"
#include "kinematica/ik_types.hpp"
#include "kinematica/solvers/triangle.hpp"
#include "kinematica/types.hpp"

namespace km {

//! A 3R elbow arm, as its solver reads it. Filled once per arm by elbow::build
//! (elbow_build.hpp).
struct ElbowParams {
    bool pose = false;  //!< true: pose targets; false: position targets (tool origin)
    Vec3 h1;  //!< axis 1 direction (unit, base frame)
    Vec3 p1;  //!< a point on axis 1 (m)
    Vec3 k;   //!< axes 2 and 3 direction k (unit)
    Vec3 e1;  //!< basis e1 of the plane normal to k
    Vec3 e2;  //!< e2 = k × e1
    Vec3 hk;  //!< h1 × k
    Vec3 p2;  //!< a point on axis 2 (m)
    double a[2] = {0.0, 0.0};   //!< link 2, axis 2 to axis 3 at q = 0, plane coordinates (m)
    double b[2] = {0.0, 0.0};   //!< link 3, axis 3 to the tool origin at q = 0, plane coordinates (m)
    double up[2] = {0.0, 0.0};  //!< h1 × k in plane coordinates: the side elbow "up" refers to
    double s2 = 1.0;      //!< k · (axis 2 direction): +1 or -1
    double s3 = 1.0;      //!< k · (axis 3 direction): +1 or -1
    double height = 0.0;  //!< k · (x − p1): the tool's height along k over axis 1 (m)
    Vec3 rk;    //!< R_Mᵀ k (M = fk(0): the tool pose at q = 0)
    Vec3 re1;   //!< R_Mᵀ e1
    Vec3 foot;  //!< foot on axis 1 of the common normal of axes 1 and 2 (m)
    double offset = 0.0;  //!< length of that common normal (m)
    double rmin = 0.0;    //!< least distance of the tool origin from the normal's foot on axis 2 (m)
    double rmax = 0.0;    //!< largest such distance (m)
    double scale = 0.0;   //!< size of the arm (m): the scale of SINGULAR_TOL
    double slack = 0.0;   //!< how far axis 3's tilt off k may put the tool from the ideal arm's (m)

    KM_HD int slots() const { return 4; }
    KM_HD int dof() const { return 3; }
    //! Candidates of one target: slots shoulder right/left x elbow up/down.
    //!
    //! T: target pose of the tool (base frame); for position targets only its origin is
    //! read. Q: (4, 3) out, NaN rows where a branch has no candidate. info (default on
    //! entry): singular and the free joints on a continuum, near where branches merge
    //! (MERGE_TOL), gap.
    KM_HD void solve(const Pose& T, double* Q, SolverInfo& info) const;
};

namespace elbow {

//! A cos θ + B sin θ = e: the height of Rot(h1, θ) v along k must be the tool's.
struct Height {
    double A, B, e;
};

//! Where a turn of the target about axis 1 puts it.
struct Placed {
    Vec3 u;       //!< Rot(h1, θ) (p − p1)
    double t[2];  //!< the tool's target in the arm's plane relative to axis 2 (m)
    double sigma; //!< u · (h1 × k): which side of axis 1 the target is on (the shoulder branch)
};

//! Turn v = p − p1 by θ = −q1 about axis 1.
KM_HD inline Placed place(const ElbowParams& P, double theta, const Vec3& v) {
    Placed out;
    out.u = rotate_about(P.h1, std::cos(theta), std::sin(theta), v);
    out.t[0] = 0.0;
    out.t[1] = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double w = out.u[i] + P.p1[i] - P.p2[i];
        out.t[0] += P.e1[i] * w;
        out.t[1] += P.e2[i] * w;
    }
    out.sigma = dot(P.hk, out.u);
    return out;
}

//! True when elbow up is the triangle's branch ψ <= 0 (the target on the h1 side).
KM_HD inline bool elbow_up_first(const ElbowParams& P, const double* t) {
    return t[0] * P.up[0] + t[1] * P.up[1] >= 0.0;
}

//! A, B, e of A cos θ + B sin θ = e: the height of Rot(h1, θ) v along k.
KM_HD inline Height height(const ElbowParams& P, const Vec3& v) {
    const double kh = dot(P.k, P.h1);
    const double hv = dot(P.h1, v);
    return {dot(P.k, v) - kh * hv, -dot(P.hk, v) /* k · (h1 × v) */, P.height - kh * hv};
}

//! The four candidates of the tool origin at p = p1 + v (abe: height()).
KM_HD inline void position(const ElbowParams& P, const Vec3& v, const Height& abe, double* Q,
                           SolverInfo& info) {
    using triangle::Code;
    using triangle::MERGE_TOL;
    double roots[2];
    const double rho = std::hypot(abe.A, abe.B);
    const double tol = triangle::SINGULAR_TOL * P.scale;
    // an arm whose axes 2 and 3 are parallel within tolerance only puts the tool up to its
    // slack from where the exact arm does: the height equation and the triangle are known
    // to within it, and roots merging within it are proposed apart, one on each side (as
    // far as the slack allows: from there the repair carries each to the solution on its
    // side), here and in two_link
    const double slack = P.slack > tol ? P.slack : 0.0;
    if (rho <= tol) {  // on axis 1: any q1 or none
        roots[0] = 0.0;
        roots[1] = PI;
        if (std::fabs(abe.e) <= tol) {
            info.singular = true;
            info.set_free(0);
        }
    } else {  // least-squares roots when out of reach
        const double e = slack > 0.0 && rho - std::fabs(abe.e) < slack
                             ? abe.e - std::copysign(slack, abe.e)  // straddle the merge
                             : abe.e;
        trig_linear(abe.A / rho, abe.B / rho, e / rho, roots);
        const double c = abe.e / rho;  // the roots merge where |c| -> 1; q1 is uncertain where rho -> 0
        if ((1.0 - c) * (1.0 + c) < MERGE_TOL * MERGE_TOL || rho < MERGE_TOL * P.scale) {
            info.near = true;
        }
    }
    const double sigma0 = place(P, roots[0], v).sigma;
    const double sigma1 = place(P, roots[1], v).sigma;
    const int first = sigma0 >= sigma1 ? 0 : 1;  // the shoulder-right root
    for (int shoulder = 0; shoulder < 2; ++shoulder) {
        const double theta = shoulder == 0 ? roots[first] : roots[1 - first];
        const Placed pl = place(P, theta, v);
        double br[2][2];
        const Code code =
            triangle::two_link(P.a[0], P.a[1], P.b[0], P.b[1], pl.t[0], pl.t[1], br, slack);
        if (code == Code::fold) {
            info.singular = true;
            info.set_free(1);
        } else if (code == Code::near) {
            info.near = true;
        }
        const bool up_first = elbow_up_first(P, pl.t);
        for (int row = 0; row < 2; ++row) {
            const int elbow = up_first ? row : 1 - row;
            double* q = Q + 3 * (2 * shoulder + elbow);
            q[0] = -theta;
            q[1] = P.s2 * br[row][0];
            q[2] = P.s3 * br[row][1];
        }
    }
}

//! The one candidate of pose T, in the slot of its branch (v = p − p1).
KM_HD inline void pose(const ElbowParams& P, const Pose& T, const Vec3& v, double* Q) {
    const Vec3 kt = T.rotate(P.rk);
    const Vec3 f = T.rotate(P.re1);
    const double q1 = subproblem1(P.k, kt, P.h1);
    const Vec3 g = rotate_about(P.h1, std::cos(q1), -std::sin(q1), f);
    const double phi = std::atan2(dot(P.e2, g), dot(P.e1, g));
    const Placed pl = place(P, -q1, v);
    const double c = std::cos(phi);
    const double s = std::sin(phi);
    const double bx = P.b[0];
    const double by = P.b[1];
    const double d2 =
        triangle::turn(P.a[0], P.a[1], pl.t[0] - (c * bx - s * by), pl.t[1] - (s * bx + c * by));
    const double d3 = phi - d2;
    const double psi = triangle::turn(P.a[0], P.a[1], bx, by) + d3;  // link 3 relative to link 2
    const bool up = (std::sin(psi) <= 0.0) == elbow_up_first(P, pl.t);
    const int slot = (pl.sigma >= 0.0 ? 0 : 2) + (up ? 0 : 1);
    double* q = Q + 3 * slot;
    q[0] = q1;
    q[1] = P.s2 * d2;
    q[2] = P.s3 * d3;
}

}  // namespace elbow

KM_HD inline void ElbowParams::solve(const Pose& T, double* Q, SolverInfo& info) const {
    for (int i = 0; i < 12; ++i) Q[i] = NaN;
    const Vec3 v{T.p.x - p1.x, T.p.y - p1.y, T.p.z - p1.z};
    const elbow::Height abe = elbow::height(*this, v);
    if (pose) {
        elbow::pose(*this, T, v, Q);
    } else {
        elbow::position(*this, v, abe, Q, info);
    }
    const double miss = std::fabs(abe.e) - std::hypot(abe.A, abe.B);  // the height equation's, a distance
    const double dx = T.p.x - foot.x;
    const double dy = T.p.y - foot.y;
    const double dz = T.p.z - foot.z;
    const double r = std::hypot(std::hypot(dx, dy), dz);
    const double a0 = offset;
    double gap = std::max(std::max(std::max(miss, r - a0 - rmax), rmin - a0 - r), 0.0);
    const double tol = triangle::SINGULAR_TOL * scale;
    if (slack > tol) {  // axes 2 and 3 not exactly parallel
        gap -= slack;
        if (info.singular) info.near = true;  // a continuum of the ideal arm: a miss is no proof
    }
    info.gap = gap > tol ? gap : NaN;  // beyond round-off
}

}  // namespace km
