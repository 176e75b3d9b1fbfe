// Time-optimal jerk-limited motion of one joint between two states at rest in acceleration
// (position p, velocity v, acceleration 0), and the synchronisation of several joints.
//
// Limits: |v| <= V, |a| <= A, |j| <= J. A *ramp* changes the velocity by Δ with zero
// acceleration at both ends: jerk +J (to the acceleration reached), a phase at |a| = A if
// |Δ| > A²/J, jerk -J back to zero. It lasts R(Δ) = 2√(|Δ|/J), or |Δ|/A + A/J at the
// acceleration limit, and since its acceleration is symmetric about its midpoint it covers
// (v_start + v_end)/2 · R(Δ).
//
// The set of profiles of duration T from (v0, 0) to (v1, 0) within the limits is convex (the
// constraints are convex in the jerk function and the end state is linear in it), so the
// displacements reachable in time T form an interval [Dmin(T), Dmax(T)]. Dmax(T) is reached
// by ramping up to the highest velocity vp the time allows, cruising there (only at vp = V)
// and ramping down to v1: vp(T) solves R(vp - v0) + R(vp - v1) = T, in closed form. Its
// derivative dDmax/dT grows with T, so Dmax is convex in T; Dmin, the mirror image, is
// concave. (The derivative is not vp(T) alone: a longer T also lengthens the ramps. From
// rest to rest it is 1.5·vp while the ramps stay below the acceleration limit A and
// vp + A²/2J once they reach it, equal at vp = A²/J; for other end velocities the growth
// was checked numerically, and the durations agree with ruckig's on 10,000 random cases.)
// Hence, for a displacement D:
//   - the shortest duration is the first T >= R(v1 - v0) with Dmin(T) <= D <= Dmax(T): a
//     root of Dmax(T) = D (D above the direct ramp's displacement) or of Dmin(T) = D;
//   - the durations a joint can take are [t_min, ∞) less at most one open interval, where
//     the concave Dmin(T) rises above D (both velocities the same sign, D small: the joint
//     cannot slow down enough to cover so little until it can turn back);
//   - a profile of any feasible duration T is the convex combination of the extreme
//     profiles of that T whose displacement is D: λ·jerk_max(t) + (1 - λ)·jerk_min(t)
//     holds every limit (each profile does) and ends exactly at (p0 + D, v1, 0).
// A set of joints takes the shortest duration no joint's blocked interval holds.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace km::jerk {

//! Most phases of one joint's profile: two extreme profiles of seven phases each, cut at the
//! union of their switch times.
constexpr int MAX_PHASES = 14;
//! Iterations of the safeguarded Newton search of a duration (each halves the bracket at
//! worst; 200 covers a double's range).
constexpr int MAX_ITERATIONS = 200;

//! One joint's limits, each positive.
struct Limits {
    double v = 1.0;  //!< speed
    double a = 1.0;  //!< acceleration
    double j = 1.0;  //!< jerk
};

//! A profile's shape: ramp to vp, cruise tc at vp, ramp to the end velocity. The ramps'
//! velocity changes are kept exactly where known (an extreme shape's peak a few ulps above
//! the start velocity would lose them in vp - v0); NaN: from vp.
struct Shape {
    double vp = 0.0;
    double tc = 0.0;
    double rise = std::numeric_limits<double>::quiet_NaN();  //!< vp - v0
    double fall = std::numeric_limits<double>::quiet_NaN();  //!< v1 - vp
};

//! A joint's profile as phases of constant jerk from its start state.
struct Profile {
    int phases = 0;
    double t[MAX_PHASES] = {};  //!< durations (s)
    double j[MAX_PHASES] = {};  //!< jerks
};

namespace detail {

//! Duration of a ramp changing the velocity by dv (sign ignored).
inline double ramp_time(double dv, const Limits& L) {
    const double d = std::fabs(dv);
    return d * L.j <= L.a * L.a ? 2.0 * std::sqrt(d / L.j) : d / L.a + L.a / L.j;
}

//! d R / d|Δ| (inf at Δ = 0).
inline double ramp_slope(double dv, const Limits& L) {
    const double d = std::fabs(dv);
    return d * L.j <= L.a * L.a ? 1.0 / std::sqrt(d * L.j) : 1.0 / L.a;
}

//! The shape's first velocity change (vp - v0) and its last (v1 - vp).
inline double rise_of(const Shape& s, double v0) { return std::isnan(s.rise) ? s.vp - v0 : s.rise; }
inline double fall_of(const Shape& s, double v1) { return std::isnan(s.fall) ? v1 - s.vp : s.fall; }

//! Duration of the shape from v0 to v1.
inline double shape_time(const Shape& s, double v0, double v1, const Limits& L) {
    return ramp_time(rise_of(s, v0), L) + s.tc + ramp_time(fall_of(s, v1), L);
}

//! Displacement of the shape from v0 to v1.
inline double shape_distance(const Shape& s, double v0, double v1, const Limits& L) {
    const double r = rise_of(s, v0), f = fall_of(s, v1);
    return 0.5 * (2.0 * v0 + r) * ramp_time(r, L) + s.vp * s.tc + 0.5 * (2.0 * v1 - f) * ramp_time(f, L);
}

//! The excess e >= 0 of the peak over max(w0, w1) at which two ramps (up by c + e, down by
//! e, c = |w1 - w0|) last T: the closed form of each regime (both triangular; the larger at
//! the acceleration limit; both at it).
inline double peak_excess(double T, double c, const Limits& L) {
    const double full = L.a * L.a / L.j;  // Δv of a ramp that just reaches A
    const double e1 = std::max(0.0, full - c);
    const double sj = std::sqrt(L.j);
    if (T <= ramp_time(c + e1, L) + ramp_time(e1, L)) {  // both triangular
        const double s = 0.5 * T * sj;                   // √(c + e) + √e
        const double r = 0.5 * (s - c / s);
        return r > 0.0 ? r * r : 0.0;
    }
    if (T <= ramp_time(c + full, L) + ramp_time(full, L)) {  // e <= full < c + e
        // (c + r²)/A + A/J + 2r/√J = T for r = √e
        const double q = (c / L.a + L.a / L.j - T) / L.a;
        const double disc = 1.0 / L.j - q;
        const double r = L.a * (std::sqrt(std::max(disc, 0.0)) - 1.0 / sj);
        return r > 0.0 ? r * r : 0.0;
    }
    return std::max(0.0, 0.5 * L.a * (T - 2.0 * L.a / L.j - c / L.a));
}

//! The extreme shape of duration T >= R(v1 - v0): the highest peak (up) or the lowest.
inline Shape extreme(double T, double v0, double v1, bool up, const Limits& L) {
    const double sg = up ? 1.0 : -1.0;
    const double w0 = sg * v0, w1 = sg * v1, m = std::max(w0, w1);
    const double c = std::fabs(w1 - w0);
    Shape s;
    const double tv = ramp_time(L.v - w0, L) + ramp_time(L.v - w1, L);
    const double e = T >= tv ? L.v - m : std::min(L.v - m, peak_excess(T, c, L));
    s.vp = sg * (m + e);
    s.tc = T >= tv ? T - tv : 0.0;
    s.rise = sg * (w0 == m ? e : c + e);
    s.fall = -sg * (w1 == m ? e : c + e);
    return s;
}

//! Mirrored frame of one joint's problem: velocities w = sg·v, displacement sg·D >= the
//! direct ramp's, so the shortest move is on the upper (Dmax) branch.
struct Frame {
    double w0, w1, d;
};

//! The peak of a branch's shape without cruise at r: base + r² (upper) or base - r² (lower).
inline double peak_at(double base, bool upper, double r) { return upper ? base + r * r : base - r * r; }

//! A branch's shape without cruise at r, its velocity changes exact: the ramp from the
//! base's own end velocity changes it by r², the other by the ends' gap more.
inline Shape branch_shape(const Frame& f, double base, bool upper, double r) {
    const double e = r * r, sg = upper ? 1.0 : -1.0;
    Shape s;
    s.vp = peak_at(base, upper, r);
    s.rise = sg * ((f.w0 == base ? 0.0 : std::fabs(base - f.w0)) + e);
    s.fall = -sg * ((f.w1 == base ? 0.0 : std::fabs(base - f.w1)) + e);
    return s;
}

//! d distance / dr of a branch's shape without cruise at r (vp = base ± r²): each ramp
//! covers (w + vp)/2 · R(|vp - w|), and in r a triangular ramp's R is smooth (√Δ = r at
//! the ramp that starts at the base).
inline double distance_slope(const Frame& f, double base, bool upper, double r, const Limits& L) {
    const Shape s = branch_shape(f, base, upper, r);
    const double dvp = upper ? 2.0 * r : -2.0 * r;
    const double full = L.a * L.a / L.j;
    double out = 0.0;
    for (const auto& [w, dv] : {std::pair{f.w0, s.rise}, std::pair{f.w1, -s.fall}}) {
        // dv = vp - w; dR/dr = R'(|dv|) d|dv|/dr, with the limit 2/√J where |dv| = r² -> 0
        const double d = std::fabs(dv), side = dv >= 0.0 ? 1.0 : -1.0;
        double dR;
        if (d * L.j <= L.a * L.a && d > 0.0) {
            dR = side * dvp / std::sqrt(d * L.j);
        } else if (d > full) {
            dR = side * dvp / L.a;
        } else {
            dR = 2.0 / std::sqrt(L.j);
        }
        out += 0.5 * dvp * ramp_time(d, L) + 0.5 * (w + s.vp) * dR;
    }
    return out;
}

//! The peak of a shape without cruise whose distance is f.d on one branch, r in [rlo, rhi]
//! where "distance >= d" (nonneg; else "<= d") holds on one end and not the other and is
//! monotone in r (the branches' distances are convex or concave in the duration, which is
//! monotone in r). Safeguarded Newton in r, keeping the bracket; returns the r where
//! Newton's step falls within round-off, or else the bracket's end where the predicate
//! holds (the side on which the caller's duration is feasible).
inline double solve_peak(const Frame& f, double base, bool upper, double rlo, double rhi, bool nonneg,
                         const Limits& L, double start = -1.0) {
    const auto g = [&](double r) { return shape_distance(branch_shape(f, base, upper, r), f.w0, f.w1, L) - f.d; };
    const auto ok = [nonneg](double gv) { return nonneg ? gv >= 0.0 : gv <= 0.0; };
    const double ghi = g(rhi), glo = g(rlo);
    if (ok(ghi) == ok(glo)) {  // no change of side: round-off at a root on an end
        return ok(ghi) || std::fabs(ghi) < std::fabs(glo) ? rhi : rlo;
    }
    double good = rhi, bad = rlo;
    if (!ok(ghi)) std::swap(good, bad);
    double x = start > std::min(rlo, rhi) && start < std::max(rlo, rhi) ? start : good;
    for (int it = 0; it < MAX_ITERATIONS; ++it) {
        const double gx = g(x);
        if (ok(gx)) {
            good = x;
        } else {
            bad = x;
        }
        if (gx == 0.0) break;
        const double width = std::fabs(good - bad);
        if (!(width > 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::fabs(good), std::fabs(bad)))) {
            break;
        }
        const double step = gx / distance_slope(f, base, upper, x, L);
        // converged: the next step is within round-off of x (Newton's error is then about
        // its square), so x is the root to a few ulps, on either side of it
        if (std::fabs(step) <= 4.0 * std::numeric_limits<double>::epsilon() * std::fabs(x)) return x;
        double next = x - step;
        const double mlo = std::min(good, bad), mhi = std::max(good, bad);
        if (!(next > mlo && next < mhi)) next = 0.5 * (good + bad);
        x = next;
    }
    return good;
}

}  // namespace detail

namespace detail {

//! The frame of one joint's move in which D is at or above the direct ramp's (a tie: the one
//! with the velocities' sum >= 0, whose upper branch rises from the direct ramp at once); t0
//! the direct ramp's duration R(v1 - v0).
inline Frame frame_of(double D, double v0, double v1, double t0) {
    const double direct = 0.5 * (v0 + v1) * t0;
    const double sg = D > direct || (D == direct && v0 + v1 >= 0.0) ? 1.0 : -1.0;
    return Frame{sg * v0, sg * v1, sg * D};
}

//! The excess e of the upper branch's peak over max(w0, w1) whose distance is d if both
//! ramps were at the acceleration limit (then distance is quadratic in e): Newton's start.
inline double trapezoid_guess(const Frame& f, const Limits& L) {
    const double m = std::max(f.w0, f.w1), c = std::fabs(f.w1 - f.w0), k = L.a / L.j;
    // e²/A + e (2m/A + k) + (2m - c) c / (2A) + k (2m - c/2) - d = 0
    const double b = 2.0 * m / L.a + k;
    const double c0 = (2.0 * m - c) * c / (2.0 * L.a) + k * (2.0 * m - 0.5 * c) - f.d;
    const double disc = b * b - 4.0 * c0 / L.a;
    return disc > 0.0 ? std::max(0.0, 0.5 * L.a * (std::sqrt(disc) - b)) : 0.0;
}

//! The peak's r = √e of the upper branch's shape without cruise whose distance is f.d (m
//! the larger velocity, c the velocities' gap): one ramp changes the velocity by r², the
//! other by c + r², and the distance is (2m + r²)/2 · R(r²) + (2m - c + r²)/2 · R(c + r²),
//! below d at r = 0 (the direct ramp) and at or above it at rhi, and crossing d once
//! between (it grows, or dips and then grows: convex in the duration). Safeguarded Newton
//! (solve_peak's), each step one square root and the slope in closed form; duration: the
//! shape's at the root, R(r²) + R(c + r²).
inline double upper_peak(const Frame& f, double m, double c, const Limits& L, double start, double rhi,
                         double& duration) {
    const double sj = std::sqrt(L.j);
    // R(dv) and dR/dr, where d dv/dr = 2r
    const auto ramp = [&L, sj](double dv, double r, double& R, double& dR) {
        if (dv * L.j <= L.a * L.a) {
            R = 2.0 * std::sqrt(dv / L.j);
            dR = R > 0.0 ? 4.0 * r / (R * L.j) : 2.0 / sj;
        } else {
            R = dv / L.a + L.a / L.j;
            dR = 2.0 * r / L.a;
        }
    };
    const double slope1 = 2.0 / sj;
    double good = rhi, bad = 0.0, t_good = std::numeric_limits<double>::quiet_NaN();
    double x = start > 0.0 && start < rhi ? start : rhi;
    for (int it = 0; it < MAX_ITERATIONS; ++it) {
        const double e = x * x;
        double R1, dR1, R2, dR2;
        if (e * L.j <= L.a * L.a) {  // the ramp by r² below A: R = 2r/√J, its slope constant
            R1 = x * slope1;
            dR1 = slope1;
        } else {
            ramp(e, x, R1, dR1);
        }
        ramp(c + e, x, R2, dR2);
        const double g = 0.5 * (2.0 * m + e) * R1 + 0.5 * (2.0 * m - c + e) * R2 - f.d;
        if (g >= 0.0) {
            good = x;
            t_good = R1 + R2;
        } else {
            bad = x;
        }
        if (g == 0.0) break;
        const double width = std::fabs(good - bad);
        if (!(width > 4.0 * std::numeric_limits<double>::epsilon() * std::max(good, bad))) break;
        const double slope = x * (R1 + R2) + 0.5 * (2.0 * m + e) * dR1 + 0.5 * (2.0 * m - c + e) * dR2;
        const double step = g / slope;
        // converged: Newton's error after a step δ is of order δ²/x (quadratic convergence),
        // below round-off once δ <= √ε·x: x - step is the root, and its duration that at x
        // less step times its slope (the next term, of order step², lost). Against a
        // long-double root (2·10⁶ random moves): at most 60 ulps of the duration, 3 at the
        // 99.9th percentile (iterating on to a step of 4ε·x: 30 and 4), one iteration fewer.
        if (std::fabs(step) <= std::sqrt(std::numeric_limits<double>::epsilon()) * x) {
            duration = R1 + R2 - step * (dR1 + dR2);
            return x - step;
        }
        double next = x - step;
        if (!(next > std::min(good, bad) && next < std::max(good, bad))) next = 0.5 * (good + bad);
        x = next;
    }
    if (std::isnan(t_good)) {
        double R1, R2, dR;
        ramp(good * good, good, R1, dR);
        ramp(c + good * good, good, R2, dR);
        t_good = R1 + R2;
    }
    duration = t_good;
    return good;
}

}  // namespace detail

//! The shortest duration of one joint's move from (0, v0, 0) to (D, v1, 0), |v0|, |v1| <= L.v.
//! The upper branch in the frame of the move rises from the direct ramp (vp = max(w0, w1))
//! after a dip while vp < 0: the first r where its distance reaches d.
inline double shortest(double D, double v0, double v1, const Limits& L) {
    using detail::shape_distance;
    using detail::shape_time;
    const double t0 = detail::ramp_time(v1 - v0, L);
    const detail::Frame f = detail::frame_of(D, v0, v1, t0);
    const double m = std::max(f.w0, f.w1);
    const Shape top{L.v, 0.0};
    const double reach = shape_distance(top, f.w0, f.w1, L);
    double t;
    if (f.d >= reach) {
        t = shape_time(top, f.w0, f.w1, L) + (f.d - reach) / L.v;
    } else if (f.d <= 0.5 * (f.w0 + f.w1) * t0) {  // the direct ramp itself (a tie)
        t = t0;
    } else {
        const double start = std::sqrt(detail::trapezoid_guess(f, L));
        // the distance is below d at r = 0 (the direct ramp) and above it at the top speed
        detail::upper_peak(f, m, std::fabs(f.w1 - f.w0), L, start, std::sqrt(L.v - m), t);
    }
    return std::max(t, t0);
}

//! T if one joint's move can take the duration T >= its shortest; else the end of the
//! interval of durations it cannot take that holds T. That interval is where the lower
//! branch in the frame of the move (concave in the duration) covers more than d: only when
//! both velocities go the way of the move, which the joint cannot slow down from enough to
//! cover so little until it has time to turn back.
inline double unblocked(double T, double D, double v0, double v1, const Limits& L) {
    using detail::shape_distance;
    // a velocity at rest or the two opposed: mn <= 0 below, whatever the frame
    if (!((v0 > 0.0 && v1 > 0.0) || (v0 < 0.0 && v1 < 0.0))) return T;
    const detail::Frame f = detail::frame_of(D, v0, v1, detail::ramp_time(v1 - v0, L));
    const double mn = std::min(f.w0, f.w1);
    if (mn <= 0.0) return T;
    const Shape low = detail::extreme(T, f.w0, f.w1, false, L);
    const double over = shape_distance(low, f.w0, f.w1, L) - f.d;
    // within round-off of d: T is where the interval ends (a duration found by this function)
    if (over <= 8.0 * std::numeric_limits<double>::epsilon() * (std::fabs(f.d) + L.v * T)) return T;
    const Shape bottom{-L.v, 0.0};
    const double far = shape_distance(bottom, f.w0, f.w1, L);
    if (far >= f.d) return detail::shape_time(bottom, f.w0, f.w1, L) + (far - f.d) / L.v;
    const double r = std::sqrt(std::max(0.0, mn - low.vp));
    const double rb = detail::solve_peak(f, mn, false, r, std::sqrt(mn + L.v), false, L);
    return std::max(T, detail::shape_time(detail::branch_shape(f, mn, false, rb), f.w0, f.w1, L));
}

namespace detail {

//! The seven phases of a shape: ramp to vp, cruise, ramp to v1.
inline int shape_phases(const Shape& s, double v0, double v1, const Limits& L, double* t, double* j) {
    int k = 0;
    const auto ramp = [&](double dv) {
        const double d = std::fabs(dv), sj = dv >= 0.0 ? L.j : -L.j;
        double t1, t2;
        if (d * L.j <= L.a * L.a) {
            t1 = std::sqrt(d / L.j);
            t2 = 0.0;
        } else {
            t1 = L.a / L.j;
            t2 = d / L.a - L.a / L.j;
        }
        t[k] = t1, j[k++] = sj;
        t[k] = t2, j[k++] = 0.0;
        t[k] = t1, j[k++] = -sj;
    };
    ramp(rise_of(s, v0));
    t[k] = s.tc, j[k++] = 0.0;
    ramp(fall_of(s, v1));
    return k;
}

}  // namespace detail

namespace detail {

//! The shape of duration T with one peak vp between lo.vp and hi.vp and a cruise there
//! (tc = T less its two ramps) that covers D. Its distance is vp·T - (vp - v0)/2·R(vp - v0)
//! - (vp - v1)/2·R(vp - v1), whose slope in vp is tc plus a positive part: it rises from
//! the lowest extreme's to the highest's while every shape between has room for its ramps
//! (tc >= 0), and then one safeguarded Newton search (a few steps) finds vp. The ramps'
//! sum R(vp - v0) + R(vp - v1) is largest between the ends' velocities (R is concave,
//! growing from 0), at their midpoint by symmetry, where it is 2·R(|v1 - v0|/2): if that
//! exceeds T, the shapes of duration T are not one connected family, and the answer is
//! false (so it is where the ends' velocities lie far apart for T: the caller combines
//! the extremes).
inline bool cruise_shape(double T, double D, double v0, double v1, const Shape& lo, const Shape& hi,
                         double dlo, double dhi, const Limits& L, Shape& out) {
    if (2.0 * ramp_time(0.5 * (v1 - v0), L) > T) return false;
    const double sj = std::sqrt(L.j), full = L.a * L.a / L.j;
    // x·R(|x|)/2 and its slope (R(|x|) + |x|·R'(|x|))/2
    const auto half = [&](double x, double& slope) {
        const double d = std::fabs(x);
        if (d <= full) {
            const double r = std::sqrt(d) / sj;  // √(d/J)
            slope = 1.5 * r;
            return x * r;
        }
        slope = d / L.a + 0.5 * L.a / L.j;
        return 0.5 * x * (d / L.a + L.a / L.j);
    };
    const auto g = [&](double vp, double& slope) {
        double s0, s1;
        const double out0 = half(vp - v0, s0), out1 = half(vp - v1, s1);
        slope = T - s0 - s1;
        return vp * T - out0 - out1 - D;
    };
    double a = lo.vp, b = hi.vp;  // g(a) <= 0 <= g(b)
    const double tol = 2.0 * std::numeric_limits<double>::epsilon() * L.v;  // vp's round-off at the limit
    double vp = a + (b - a) * ((D - dlo) / (dhi - dlo));
    for (int it = 0; it < MAX_ITERATIONS; ++it) {
        if (!(vp > a && vp < b)) vp = 0.5 * (a + b);
        double slope;
        const double gv = g(vp, slope);
        if (gv == 0.0) break;
        if (gv < 0.0) {
            a = vp;
        } else {
            b = vp;
        }
        const double step = slope > 0.0 ? gv / slope : 0.0;
        if (std::fabs(step) <= tol || b - a <= tol) break;
        vp -= step;
    }
    const double tc = T - ramp_time(vp - v0, L) - ramp_time(vp - v1, L);
    if (!(tc >= 0.0)) return false;
    out = Shape{vp, tc};
    return true;
}

}  // namespace detail

//! One joint's profile of duration T (one it can take) from (0, v0, 0) to (D, v1, 0). Where
//! the shapes of duration T with one peak and a cruise at it form one family from the
//! lowest to the highest (a joint with time to spare), the one of them that covers D: it
//! slows to a cruise and speeds up at most once, so it does not wander past its target.
//! Else the convex combination of the two extreme shapes of T that covers D (file
//! comment), which holds every limit whatever T.
inline void profile(double T, double D, double v0, double v1, const Limits& L, Profile& out) {
    using detail::shape_distance;
    const double t0 = detail::ramp_time(v1 - v0, L);
    const double Tm = std::max(T, t0);
    const Shape hi = detail::extreme(Tm, v0, v1, true, L), lo = detail::extreme(Tm, v0, v1, false, L);
    const double dhi = shape_distance(hi, v0, v1, L), dlo = shape_distance(lo, v0, v1, L);
    double lam = dhi > dlo ? (D - dlo) / (dhi - dlo) : 1.0;
    lam = std::min(1.0, std::max(0.0, lam));
    Shape mid;
    if (lam > 0.0 && lam < 1.0 && detail::cruise_shape(Tm, D, v0, v1, lo, hi, dlo, dhi, L, mid)) {
        out.phases = detail::shape_phases(mid, v0, v1, L, out.t, out.j);
        return;
    }
    double th[7], jh[7], tl[7], jl[7];
    detail::shape_phases(hi, v0, v1, L, th, jh);
    detail::shape_phases(lo, v0, v1, L, tl, jl);
    if (lam == 1.0 || lam == 0.0) {
        const double* tt = lam == 1.0 ? th : tl;
        const double* jj = lam == 1.0 ? jh : jl;
        out.phases = 7;
        for (int k = 0; k < 7; ++k) out.t[k] = tt[k], out.j[k] = jj[k];
        return;
    }
    // merge the two switch sequences; each merged phase's jerk is the weighted sum
    int a = 0, b = 0, k = 0;
    double ra = th[0], rb = tl[0];  // time left in the current phase of each
    while (a < 7 && b < 7 && k < MAX_PHASES) {
        const double step = std::min(ra, rb);
        if (step > 0.0) {
            out.t[k] = step;
            out.j[k++] = lam * jh[a] + (1.0 - lam) * jl[b];
        }
        ra -= step;
        rb -= step;
        if (ra <= 0.0 && ++a < 7) ra = th[a];
        if (rb <= 0.0 && ++b < 7) rb = tl[b];
    }
    out.phases = k;
}

//! The shortest duration every joint of a segment can take, given each joint's shortest
//! t: the largest of them, moved past any interval of durations a joint cannot take (the
//! smallest T >= max t that no joint's interval holds). skip >= 0: that joint is left out.
//! binding (n entries, or nullptr): set where leaving the joint out could shorten the result
//! (its t alone is the largest, or it moved T); a joint that is not binding can take the
//! result with any velocities whose t is no larger and whose interval does not hold it.
inline double synchronised(int n, const double* p0, const double* v0, const double* p1, const double* v1,
                           const Limits* L, const double* t, int skip = -1, unsigned char* binding = nullptr) {
    double T = 0.0, second = 0.0;
    int top = -1;
    for (int i = 0; i < n; ++i) {
        if (i == skip) continue;
        if (top < 0 || t[i] > T) {
            second = top < 0 ? 0.0 : T;
            T = t[i];
            top = i;
        } else {
            second = std::max(second, t[i]);
        }
    }
    if (binding != nullptr) {
        for (int i = 0; i < n; ++i) binding[i] = i == top && T > second ? 1 : 0;
    }
    for (int pass = 0; pass <= n; ++pass) {
        bool moved = false;
        for (int i = 0; i < n; ++i) {
            if (i == skip || !(T > t[i])) continue;
            const double later = unblocked(T, p1[i] - p0[i], v0[i], v1[i], L[i]);
            if (later > T) {
                T = later;
                moved = true;
                if (binding != nullptr) binding[i] = 1;
            }
        }
        if (!moved) break;
    }
    return T;
}

//! The shortest synchronised duration of a segment of n joints from positions p0 and
//! velocities v0 to p1, v1, accelerations zero at both ends (velocities within the limits);
//! t: n entries, filled with each joint's shortest.
inline double segment_time(int n, const double* p0, const double* v0, const double* p1, const double* v1,
                           const Limits* L, double* t) {
    for (int i = 0; i < n; ++i) t[i] = shortest(p1[i] - p0[i], v0[i], v1[i], L[i]);
    return synchronised(n, p0, v0, p1, v1, L, t);
}

}  // namespace km::jerk
