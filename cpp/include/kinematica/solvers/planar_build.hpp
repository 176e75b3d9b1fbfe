// The planar family's builder (planar 2R, 3R, PR, PRR arms and the SCARA): from a chain's
// joint axes at q = 0 and its tool pose to the PlanarParams planar.hpp solves with.
//
// Which arm it is comes from the axes alone (lines.hpp's relations): 2R with parallel
// axes; PR with the slide normal to the turn; 3R with three parallel axes; PRR with the
// slide normal to two parallel turns; RRPR (the SCARA) with all four parallel.
//
// Arms it declines (nullopt: the numeric solver takes them): any other chain, and one
// whose in-plane link the solver needs is no longer than the line geometry's length
// tolerance (a joint that moves nothing, or two coinciding axes).
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "../arm_axes.hpp"
#include "../chain.hpp"
#include "../lines.hpp"
#include "planar.hpp"

namespace km::planar {

//! The arm kinds the family solves (their branch labels are the spec module's).
enum class Kind { none, planar_2r, planar_pr, planar_3r, planar_prr, scara };

namespace build_detail {

//! A unit basis e1, e2 = k × e1 of the plane normal to the unit vector k: e1 is k crossed
//! with the coordinate axis of k's smallest component (the first of equal ones), normalised.
inline void plane_basis(const Vec3& k, Vec3& e1, Vec3& e2) {
    const double ax = std::fabs(k.x), ay = std::fabs(k.y), az = std::fabs(k.z);
    int i = 0;
    if (ay < ax) i = 1;
    if (az < (i == 0 ? ax : ay)) i = 2;
    Vec3 axis{0.0, 0.0, 0.0};
    axis[i] = 1.0;
    e1 = cross(k, axis);
    const double r = norm(e1);
    e1 = Vec3{e1.x / r, e1.y / r, e1.z / r};
    e2 = cross(k, e1);
}

//! a · b with a zero always +0 (as numpy's sums, which start from +0, give it): a signed
//! zero in a plane coordinate would turn an atan2 by 2π and the candidates with it.
inline double dot0(const Vec3& a, const Vec3& b) { return dot(a, b) + 0.0; }

//! R_Mᵀ v of the pose M, each entry a dot0.
inline Vec3 unrotate0(const Pose& M, const Vec3& v) {
    return {dot0(M.x, v), dot0(M.y, v), dot0(M.z, v)};
}

//! v divided by its length.
inline Vec3 unit(const Vec3& v) {
    const double r = norm(v);
    return {v.x / r, v.y / r, v.z / r};
}

//! +1 when v > 0, else -1.
inline double sign(double v) { return v > 0.0 ? 1.0 : -1.0; }

//! The length of a plane vector (x, y).
inline double length2(double x, double y) { return std::sqrt(x * x + y * y); }

}  // namespace build_detail

//! The kind of arm the axes make, or Kind::none.
inline Kind kind_of(const ArmAxes& A) {
    std::string types;
    for (int i = 0; i < A.n; ++i) types += A.prismatic[i] ? 'P' : 'R';
    const auto par = [&A](int i, int j) { return lines::lines_parallel(A.h[i], A.h[j]); };
    const auto perp = [&A](int i, int j) { return lines::lines_perpendicular(A.h[i], A.h[j]); };
    if (types == "RR" && par(0, 1)) return Kind::planar_2r;
    if (types == "PR" && perp(0, 1)) return Kind::planar_pr;
    if (types == "RRR" && par(0, 1) && par(0, 2)) return Kind::planar_3r;
    if (types == "PRR" && par(1, 2) && perp(0, 1)) return Kind::planar_prr;
    if (types == "RRPR" && par(0, 1) && par(0, 2) && par(0, 3)) return Kind::scara;
    return Kind::none;
}

//! The planar solver of an arm from its axes (arm_axes), for pose targets or (pose false)
//! for position targets of the tool origin; nullopt for the arms the header lists.
inline std::optional<PlanarParams> build(const ArmAxes& A, bool pose = true) {
    using namespace build_detail;
    const Kind kind = kind_of(A);
    if (kind == Kind::none) return std::nullopt;
    const int n = A.n;
    const Vec3* h = A.h.data();
    const Vec3* p = A.p.data();
    const Pose& M = A.home;
    int rev[PlanarParams::MAX_REV] = {0, 0, 0};
    int nrev = 0;
    for (int i = 0; i < n; ++i)
        if (!A.prismatic[i]) rev[nrev++] = i;
    const int slide = A.prismatic[0] ? 0 : -1;
    int lift = -1;
    if (kind == Kind::scara)
        for (int i = 0; i < n && lift < 0; ++i)
            if (A.prismatic[i]) lift = i;
    const Vec3 k = unit(h[rev[0]]);
    Vec3 e1, e2;
    plane_basis(k, e1, e2);
    const Vec3 origin = p[rev[0]];
    const auto plane = [&](const Vec3& x, double* out) {
        const Vec3 d = x - origin;
        out[0] = dot0(d, e1);
        out[1] = dot0(d, e2);
    };
    PlanarParams P;
    for (int j = 0; j < nrev; ++j) plane(p[rev[j]], P.axis[j]);
    plane(M.p, P.tip);
    // the in-plane links after the first axis: between consecutive axes, then to the tool
    double lengths[PlanarParams::MAX_REV];
    for (int j = 0; j < nrev; ++j) {
        const double* to = j + 1 < nrev ? P.axis[j + 1] : P.tip;
        lengths[j] = length2(to[0] - P.axis[j][0], to[1] - P.axis[j][1]);
    }
    // a link within the line geometry's length tolerance makes the arm degenerate (a joint
    // that moves nothing, or two coinciding axes): the numeric method takes it
    const bool all_links = kind == Kind::planar_2r || kind == Kind::planar_pr;
    const int needed = all_links ? nrev : nrev - 1;
    for (int j = 0; j < needed; ++j)
        if (lengths[j] <= A.length_tol()) return std::nullopt;
    P.n = n;
    P.pose = pose;
    P.swap = kind == Kind::scara;
    P.slide = slide;
    P.lift = lift;
    if (lift >= 0) P.lift_sign = sign(dot(h[lift], k));
    P.nrev = nrev;
    for (int j = 0; j < nrev; ++j) {
        P.rev[j] = rev[j];
        P.sign[j] = sign(dot(h[rev[j]], k));
    }
    P.k = k, P.e1 = e1, P.e2 = e2, P.origin = origin, P.tool = M.p;
    P.re1 = unrotate0(M, e1);
    P.wrist = unrotate0(M, p[rev[nrev - 1]] - M.p);
    if (slide >= 0) {
        const double ux = dot0(h[0], e1), uy = dot0(h[0], e2), r = length2(ux, uy);
        P.u[0] = ux / r;
        P.u[1] = uy / r;
    }
    double reach = 0.0, longest = lengths[0];
    for (int j = 0; j < nrev; ++j) {
        reach += lengths[j];
        if (lengths[j] > longest) longest = lengths[j];
    }
    P.reach = reach;
    P.rmax = reach;
    const double inner = 2.0 * longest - reach;
    P.rmin = inner > 0.0 ? inner : 0.0;
    for (int i = 0; i < n; ++i) {
        P.qlim[i][0] = A.qlo[static_cast<size_t>(i)];
        P.qlim[i][1] = A.qhi[static_cast<size_t>(i)];
    }
    // How far from the ideal arm this one is (its axes parallel to k within the
    // classification's tolerance): a turn about an axis tilted by δ moves every point
    // within `length` of it by at most 2 δ length more or less.
    double length = 0.0;
    for (int i = 0; i < n; ++i) length += norm((i + 1 < n ? p[i + 1] : M.p) - p[i]);
    double tilts = 0.0;
    for (int j = 0; j < nrev; ++j) tilts += norm(cross(h[rev[j]], k));
    P.length = length;
    P.slack = 2.0 * tilts * length;
    if (slide >= 0) P.slide_tilt = std::fabs(dot(h[slide], k));
    if (lift >= 0) P.lift_tilt = norm(cross(h[lift], k));
    return P;
}

//! The planar solver of a chain for pose targets, or nullopt (the arms the header lists).
inline std::optional<PlanarParams> build(const Chain& chain) { return build(arm_axes(chain)); }

}  // namespace km::planar
