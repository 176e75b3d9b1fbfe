// The exact trajectory of a jerk-limited move through waypoints (jerk_via.hpp's choice of
// velocities and durations) and its samples.
//
// Segment i runs from waypoint i at knots[i] to waypoint i+1 at knots[i+1]; each joint's
// profile of the segment's duration (jerk.hpp's profile()) is a sequence of phases of
// constant jerk. The segment is cut at the union of its joints' switch times (switches
// closer than PIECE_RTOL of the duration merged) into pieces, each a cubic per joint in the
// local time τ = t - breaks[p]: (p, v, a/2, j/6) of the phase that holds the piece, at the
// piece's start. A segment's first piece starts at its waypoint exactly (τ = 0 in the first
// phase), so every waypoint is hit to the bit at its knot.
//
// A state-to-state move (ruckig's profiles: a brake of two phases, then seven, per joint,
// each phase's start state as ruckig integrated it) is cut the same way (state_pieces), and
// each joint's end is then settled on its target (settle): ruckig accepts an end within
// 1e-8 of the target, which a quintic smoothstep inside one zero-jerk phase takes out.
//
// Samples: uniform within each segment (spacing <= dt), every knot among them; each
// sample from the piece that holds it (the right-hand one at a break), by one function
// per segment.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "kinematica/jerk.hpp"

namespace km::jerk {

//! Switches of a segment's joints closer than this fraction of its duration (or of 1 s,
//! if shorter) make one break: two joints' switches equal up to round-off would otherwise
//! leave a piece of 1e-17 s.
constexpr double PIECE_RTOL = 1e-13;

namespace detail {

//! A joint's profile: its phases' start times, durations, states (p, v, a) and jerks.
struct Phases {
    int count = 0;
    double start[MAX_PHASES + 1];
    double dur[MAX_PHASES], p[MAX_PHASES], v[MAX_PHASES], a[MAX_PHASES], j[MAX_PHASES];
};

}  // namespace detail

//! A move's exact pieces (cubic, or quintic where a joint's end was settled; lowest power
//! first) and the largest |v|, |a|, |j| of each joint on them. Kept by a caller from move to
//! move, its vectors keep their memory (a move's pieces fill some 100 kB: allocated afresh,
//! the pages cost more than the move).
struct Pieces {
    int n = 0;                   //!< joints
    int order = 4;               //!< coefficients of a piece: 4 (cubic) or 6 (quintic)
    std::vector<double> breaks;  //!< (p + 1) times (s)
    std::vector<double> coef;    //!< (p, order, n)
    std::vector<double> knots;   //!< (k) the waypoints' times
    std::vector<double> peak;    //!< (3, n) largest |velocity|, |acceleration|, |jerk|
    // scratch: each joint's phases, the switches, the segment's cuts, the still joints' state
    std::vector<detail::Phases> phases;
    std::vector<double> cuts, local, still;
};

namespace detail {

//! The phases of P from (p0, v0, 0), those of zero duration left out.
inline void walk(double p0, double v0, const Profile& P, Phases& out) {
    double t = 0.0, p = p0, v = v0, a = 0.0;
    out.count = 0;
    for (int k = 0; k < P.phases; ++k) {
        const double h = P.t[k], j = P.j[k];
        if (!(h > 0.0)) continue;
        const int c = out.count++;
        out.start[c] = t, out.dur[c] = h, out.p[c] = p, out.v[c] = v, out.a[c] = a, out.j[c] = j;
        p += h * (v + h * (a / 2.0 + h * j / 6.0));
        v += h * (a + h * j / 2.0);
        a += h * j;
        t += h;
    }
    out.start[out.count] = t;
}

//! Largest |v|, |a|, |j| of one cubic piece c (4 coefficients, stride n) over [0, h].
inline void piece_peaks(const double* c, int n, double h, double* peak) {
    const double c1 = c[n], c2 = c[2 * n], c3 = c[3 * n];
    const auto vel = [&](double x) { return std::fabs(c1 + x * (2.0 * c2 + x * 3.0 * c3)); };
    double v = std::max(vel(0.0), vel(h));
    if (c3 != 0.0) {
        const double x = -c2 / (3.0 * c3);  // where the acceleration 2c2 + 6c3 τ is zero
        if (x > 0.0 && x < h) v = std::max(v, vel(x));
    }
    peak[0] = std::max(peak[0], v);
    peak[n] = std::max({peak[n], std::fabs(2.0 * c2), std::fabs(2.0 * c2 + 6.0 * c3 * h)});
    peak[2 * n] = std::max(peak[2 * n], std::fabs(6.0 * c3));
}

}  // namespace detail

namespace detail {

//! The joints' phases out.phases (n of them, their starts in the local time of a span of
//! duration T from t0 to t1) cut into pieces appended to out; out.breaks holds t0 already.
//! A joint without a phase rests at (still_p, still_v) throughout.
inline void cut_pieces(int n, double t0, double t1, double T, const double* still_p, const double* still_v,
                       Pieces& out) {
    const std::vector<Phases>& ph = out.phases;
    std::vector<double>& cuts = out.cuts;
    std::vector<double>& local = out.local;
    cuts.clear();
    for (int j = 0; j < n; ++j) {
        const Phases& P = ph[static_cast<std::size_t>(j)];
        for (int c = 1; c < P.count; ++c) cuts.push_back(P.start[c]);
    }
    std::sort(cuts.begin(), cuts.end());
    const double tol = PIECE_RTOL * std::max(T, 1.0);
    local.assign(1, 0.0);
    for (const double c : cuts) {
        if (c - local.back() > tol && T - c > tol && t0 + c > t0 + local.back() && t0 + c < t1) local.push_back(c);
    }
    local.push_back(T);
    const std::size_t pieces = local.size() - 1, stride = 4 * static_cast<std::size_t>(n);
    const std::size_t base = out.coef.size();
    out.coef.resize(base + pieces * stride);
    for (std::size_t k = 0; k < pieces; ++k) {
        const double mid = 0.5 * (local[k] + local[k + 1]);
        double* c = out.coef.data() + base + k * stride;
        for (int j = 0; j < n; ++j) {
            const Phases& P = ph[static_cast<std::size_t>(j)];
            if (P.count == 0) {  // no phase: at rest (a move of zero duration)
                c[j] = still_p[j], c[n + j] = still_v[j], c[2 * n + j] = c[3 * n + j] = 0.0;
                continue;
            }
            // the phase holding the piece's midpoint: a switch merged into the piece's start
            // (PIECE_RTOL) may lie a hair after it, and the piece follows that phase
            int q = 0;
            while (q + 1 < P.count && P.start[q + 1] <= mid) ++q;
            const double tau = local[k] - P.start[q], a = P.a[q], jk = P.j[q];
            c[j] = P.p[q] + tau * (P.v[q] + tau * (a / 2.0 + tau * jk / 6.0));
            c[n + j] = P.v[q] + tau * (a + tau * jk / 2.0);
            c[2 * n + j] = (a + tau * jk) / 2.0;
            c[3 * n + j] = jk / 6.0;
        }
        for (int j = 0; j < n; ++j) piece_peaks(c + j, n, local[k + 1] - local[k], out.peak.data() + j);
        out.breaks.push_back(k + 1 == pieces ? t1 : t0 + local[k + 1]);
    }
}

}  // namespace detail

//! Segment i of n joints (from p0, v0 to p1, v1, duration T, starting at t0 = knots[i],
//! ending at t1 = knots[i+1]) appended to out as pieces; out.breaks holds t0 already.
inline void segment_pieces(int n, double t0, double t1, double T, const double* p0, const double* v0,
                           const double* p1, const double* v1, const Limits* L, Pieces& out) {
    out.phases.resize(static_cast<std::size_t>(n));
    Profile prof;
    for (int j = 0; j < n; ++j) {
        profile(T, p1[j] - p0[j], v0[j], v1[j], L[j], prof);
        detail::walk(p0[j], v0[j], prof, out.phases[static_cast<std::size_t>(j)]);
    }
    detail::cut_pieces(n, t0, t1, T, p0, v0, out);
}

//! The pieces of the move through the k waypoints w (k, n) at velocities vel (k, n), segment
//! i lasting time[i].
inline void move_pieces(int k, int n, const double* w, const double* vel, const double* time, const Limits* L,
                        Pieces& out) {
    out.n = n;
    out.order = 4;
    out.knots.assign(static_cast<std::size_t>(k), 0.0);
    for (int i = 0; i + 1 < k; ++i) out.knots[static_cast<std::size_t>(i) + 1] = out.knots[static_cast<std::size_t>(i)] + time[i];
    out.breaks.assign(1, 0.0);
    out.coef.clear();
    out.peak.assign(3 * static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i + 1 < k; ++i) {
        const double* p0 = w + static_cast<std::size_t>(i) * n;
        const double* v0 = vel + static_cast<std::size_t>(i) * n;
        segment_pieces(n, out.knots[static_cast<std::size_t>(i)], out.knots[static_cast<std::size_t>(i) + 1], time[i],
                       p0, v0, p0 + n, v0 + n, L, out);
    }
}

//! One joint's row of a state-to-state move's phase data (ruckig's profile, in this order):
//! the durations of the brake's 2 phases and the profile's 7, their jerks, the start
//! positions of the brake's 2 phases and the profile's 8 states (the last: its end), the
//! same of the velocities and the accelerations, then the target position.
constexpr int STATE_ROW = 49;
//! End-position errors up to this many units in the last place of the target are round-off
//! of the pieces' own arithmetic, and left as they are (settle).
constexpr double SETTLE_ULPS = 16.0;

namespace detail {

//! Offsets in a STATE_ROW row: phase k (0..8) at DURATION + k, JERK + k, and its start
//! state at POSITION + k, VELOCITY + k, ACCELERATION + k.
constexpr int DURATION = 0, JERK = 9, POSITION = 18, VELOCITY = 28, ACCELERATION = 38, TARGET = 48;

//! Peaks of the smoothstep 10s³ - 15s⁴ + 6s⁵ on [0, 1]: its first, second and third
//! derivatives (15/8, 10/√3, 60).
inline double step_peak(int order) {
    return order == 1 ? 15.0 / 8.0 : order == 2 ? 10.0 / std::sqrt(3.0) : 60.0;
}

//! The smoothstep's k-th derivative (k = 0..5) at s, over k!: Horner from the highest power.
inline double step_taylor(int k, double s) {
    static const double C[6][6] = {{0.0, 0.0, 0.0, 10.0, -15.0, 6.0}, {0.0, 0.0, 30.0, -60.0, 30.0},
                                   {0.0, 60.0, -180.0, 120.0},         {60.0, -360.0, 360.0},
                                   {-360.0, 720.0},                    {720.0}};
    static const int D[6] = {6, 5, 4, 3, 2, 1};
    double y = C[k][D[k] - 1];
    for (int i = D[k] - 2; i >= 0; --i) y = C[k][i] + y * s;
    return y;
}

//! Pieces of (p, 4, n) coefficients widened to (p, 6, n), the new ones zero.
inline void widen(Pieces& P) {
    if (P.order == 6) return;
    const std::size_t n = static_cast<std::size_t>(P.n), pieces = P.breaks.size() - 1;
    P.coef.resize(pieces * 6 * n, 0.0);
    for (std::size_t k = pieces; k-- > 0;) {
        for (std::size_t r = 6; r-- > 0;) {
            for (std::size_t j = 0; j < n; ++j) P.coef[(k * 6 + r) * n + j] = r < 4 ? P.coef[(k * 4 + r) * n + j] : 0.0;
        }
    }
    P.order = 6;
}

}  // namespace detail

//! Land each joint exactly on its target position pf (n) (round-off instead of ruckig's
//! 1e-8: measured up to 7.7e-9 for a joint re-timed to a long, slow cruise). An end error e
//! beyond SETTLE_ULPS units in the last place is taken out inside one zero-jerk phase of that
//! joint by adding -e times the smoothstep 10s³ - 15s⁴ + 6s⁵ of the phase's normalised time
//! (its velocity, acceleration and jerk change are zero at both of its ends) and -e after
//! it: the longest such phase whose velocity, acceleration and jerk stay within the limits
//! with the step's peaks added (over the phase's duration). A joint without one keeps
//! ruckig's end. The pieces become quintic where a step is added; the joint's peaks take the
//! phase's with the step's added (a bound of the exact ones, within the limits).
inline void settle(const double* pf, const Limits* L, Pieces& P) {
    const int n = P.n;
    const std::size_t pieces = P.breaks.size() - 1;
    for (int d = 0; d < n; ++d) {
        const detail::Phases& ph = P.phases[static_cast<std::size_t>(d)];
        if (ph.count == 0) continue;
        const std::size_t o = static_cast<std::size_t>(P.order), N = static_cast<std::size_t>(n);
        const double* last = P.coef.data() + (pieces - 1) * o * N + static_cast<std::size_t>(d);
        const double h = P.breaks[pieces] - P.breaks[pieces - 1];
        double end = last[(o - 1) * N];
        for (std::size_t r = o - 1; r-- > 0;) end = last[r * N] + h * end;
        const double e = end - pf[d], ae = std::fabs(e);
        const double ulp = std::nextafter(std::fabs(pf[d]), std::numeric_limits<double>::infinity()) - std::fabs(pf[d]);
        if (!(ae > SETTLE_ULPS * ulp)) continue;
        int rank[MAX_PHASES];  // the longest phase first, ties in their order
        for (int k = 0; k < ph.count; ++k) rank[k] = k;
        std::stable_sort(rank, rank + ph.count, [&ph](int a, int b) { return ph.dur[a] > ph.dur[b]; });
        for (int i = 0; i < ph.count; ++i) {
            const int k = rank[i];
            const double tau = ph.dur[k], t0 = ph.start[k];
            const double v_end = ph.v[k] + ph.a[k] * tau;
            const double vpk = std::max(std::fabs(ph.v[k]), std::fabs(v_end)) + detail::step_peak(1) * ae / tau;
            const double apk = std::fabs(ph.a[k]) + detail::step_peak(2) * ae / std::pow(tau, 2.0);
            const double jpk = detail::step_peak(3) * ae / std::pow(tau, 3.0);
            if (ph.j[k] != 0.0 || !(vpk <= L[d].v) || !(apk <= L[d].a) || !(jpk <= L[d].j)) continue;
            detail::widen(P);
            const double scale = 1.0 / tau;
            for (std::size_t p = 0; p < pieces; ++p) {
                const double mid = 0.5 * (P.breaks[p] + P.breaks[p + 1]);
                double* c = P.coef.data() + p * 6 * N + static_cast<std::size_t>(d);
                if (mid >= t0 && mid <= t0 + tau) {
                    const double s0 = (P.breaks[p] - t0) / tau;
                    double fact = 1.0;
                    for (int r = 0; r < 6; ++r) {
                        if (r > 1) fact *= r;
                        c[static_cast<std::size_t>(r) * N] -= e * (detail::step_taylor(r, s0) * std::pow(scale, r) / fact);
                    }
                } else if (mid > t0 + tau) {
                    c[0] -= e;
                }
            }
            double* peak = P.peak.data() + d;
            peak[0] = std::max(peak[0], vpk);
            peak[N] = std::max(peak[N], apk);
            peak[2 * N] = std::max(peak[2 * N], jpk);
            break;
        }
    }
}

//! The pieces of a state-to-state move of n joints and duration T from each joint's phase
//! data (rows: n STATE_ROW rows), settled on the targets; knots {0, T}.
inline void state_pieces(int n, double T, const double* rows, const Limits* L, Pieces& out) {
    using namespace detail;
    out.n = n;
    out.order = 4;
    out.knots.assign({0.0, T});
    out.breaks.assign(1, 0.0);
    out.coef.clear();
    out.peak.assign(3 * static_cast<std::size_t>(n), 0.0);
    out.phases.resize(static_cast<std::size_t>(n));
    out.still.assign(2 * static_cast<std::size_t>(n), 0.0);
    double* pf = out.still.data();  // the targets, then the still joints' velocity (zero)
    for (int j = 0; j < n; ++j) {
        const double* r = rows + static_cast<std::size_t>(j) * STATE_ROW;
        Phases& P = out.phases[static_cast<std::size_t>(j)];
        P.count = 0;
        double t = 0.0;
        for (int k = 0; k < 9; ++k) {
            const double h = r[DURATION + k];
            if (h > 0.0) {
                const int c = P.count++;
                P.start[c] = t, P.dur[c] = h, P.p[c] = r[POSITION + k], P.v[c] = r[VELOCITY + k];
                P.a[c] = r[ACCELERATION + k], P.j[c] = r[JERK + k];
            }
            t += h;
        }
        P.start[P.count] = t;
        pf[j] = r[TARGET];
    }
    detail::cut_pieces(n, 0.0, T, T, pf, pf + n, out);
    settle(pf, L, out);
}

//! Samples in each knot interval [a, b]: m = max(2, ⌈(b - a)/dt - 1e-9⌉ + 1) uniform ones,
//! the first being the previous interval's last. Their count in all (k - 1 intervals).
inline long sample_count(const std::vector<double>& knots, double dt) {
    long total = 1;
    if (!(knots.back() > 0.0)) return total;  // a move of zero duration: one sample
    for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
        const double span = knots[i + 1] - knots[i];
        total += std::max(2L, static_cast<long>(std::ceil(span / dt - 1e-9)) + 1) - 1;
    }
    return total;
}

namespace detail {

//! The d-th derivative (d = 0..3) at tau of a piece's polynomial c (order coefficients,
//! stride n; lowest power first): Horner from the highest power on the coefficients times
//! i!/(i - d)!.
inline double piece_value(const double* c, int n, int order, int d, double tau) {
    static const double FALL[4][6] = {
        {1, 1, 1, 1, 1, 1}, {0, 1, 2, 3, 4, 5}, {0, 0, 2, 6, 12, 20}, {0, 0, 0, 6, 24, 60}};
    double y = c[(order - 1) * n] * FALL[d][order - 1];
    for (int i = order - 2; i >= d; --i) y = y * tau + c[i * n] * FALL[d][i];
    return y;
}

}  // namespace detail

//! q, q̇, q̈ and the jerk (m, n each) at the m sorted times t within pieces [first, last) of
//! P (the right-hand piece at a break; past the last piece's end, the last piece).
inline void sample_pieces(const Pieces& P, std::size_t first, std::size_t last, const double* t, long m, double* q,
                          double* qd, double* qdd, double* qddd) {
    const int n = P.n, order = P.order;
    std::size_t p = first;
    for (long s = 0; s < m; ++s) {
        while (p + 1 < last && P.breaks[p + 1] <= t[s]) ++p;
        const double tau = t[s] - P.breaks[p];
        const double* c = P.coef.data() + p * static_cast<std::size_t>(order) * static_cast<std::size_t>(n);
        const std::size_t o = static_cast<std::size_t>(s) * n;
        if (order == 4) {
            for (int j = 0; j < n; ++j) {
                const double c0 = c[j], c1 = c[n + j], c2 = c[2 * n + j], c3 = c[3 * n + j];
                q[o + j] = c0 + tau * (c1 + tau * (c2 + tau * c3));
                qd[o + j] = c1 + tau * (2.0 * c2 + tau * 3.0 * c3);
                qdd[o + j] = 2.0 * c2 + tau * 6.0 * c3;
                qddd[o + j] = 6.0 * c3;
            }
            continue;
        }
        for (int j = 0; j < n; ++j) {
            q[o + j] = detail::piece_value(c + j, n, order, 0, tau);
            qd[o + j] = detail::piece_value(c + j, n, order, 1, tau);
            qdd[o + j] = detail::piece_value(c + j, n, order, 2, tau);
            qddd[o + j] = detail::piece_value(c + j, n, order, 3, tau);
        }
    }
}

//! The samples of the move (sample_count(P.knots, dt) of them: t (m), q, q̇, q̈, jerk (m, n)),
//! segment by segment; the last is the end state (w_end, v_end, a_end) exactly (a_end null:
//! zero), with the jerk that leads into it. A move of zero duration: one sample, the end.
inline void move_samples(const Pieces& P, double dt, const double* w_end, const double* v_end, const double* a_end,
                         double* t, double* q, double* qd, double* qdd, double* qddd) {
    const int n = P.n;
    const std::size_t k = P.knots.size(), pieces = P.breaks.size() - 1;
    t[0] = 0.0;
    long s = 1;
    std::size_t first = 0;
    sample_pieces(P, 0, 1, t, 1, q, qd, qdd, qddd);
    for (std::size_t i = 0; i + 1 < k && P.knots.back() > 0.0; ++i) {
        const double a = P.knots[i], b = P.knots[i + 1];
        const long m = std::max(2L, static_cast<long>(std::ceil((b - a) / dt - 1e-9)) + 1);
        const double step = (b - a) / static_cast<double>(m - 1);
        for (long j = 1; j < m; ++j) t[s + j - 1] = j + 1 == m ? b : a + static_cast<double>(j) * step;
        std::size_t last = first;
        while (last < pieces && P.breaks[last] < b) ++last;
        // the segment's pieces; its knot b, a sample, takes the next segment's first piece
        const std::size_t end = std::min(pieces, last + 1);
        const std::size_t o = static_cast<std::size_t>(s) * n;
        sample_pieces(P, first, end, t + s, m - 1, q + o, qd + o, qdd + o, qddd + o);
        s += m - 1;
        first = last;
    }
    const std::size_t o = static_cast<std::size_t>(s - 1) * n;
    const double* c = P.coef.data() + (pieces - 1) * static_cast<std::size_t>(P.order) * static_cast<std::size_t>(n);
    const double h = P.breaks[pieces] - P.breaks[pieces - 1];
    for (int j = 0; j < n; ++j) {
        q[o + j] = w_end[j], qd[o + j] = v_end[j], qdd[o + j] = a_end == nullptr ? 0.0 : a_end[j];
        qddd[o + j] = P.knots.back() > 0.0 ? detail::piece_value(c + j, n, P.order, 3, h) : 0.0;
    }
}

}  // namespace km::jerk
