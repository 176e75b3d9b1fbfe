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
// Samples: uniform within each segment (spacing <= dt), every knot among them; each
// sample from the piece that holds it (the right-hand one at a break), by one function
// per segment.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "kinematica/jerk.hpp"

namespace km::jerk {

//! Switches of a segment's joints closer than this fraction of its duration (or of 1 s,
//! if shorter) make one break: two joints' switches equal up to round-off would otherwise
//! leave a piece of 1e-17 s.
constexpr double PIECE_RTOL = 1e-13;

namespace detail {

//! A joint's profile: its phases' start times, states (p, v, a) and jerks.
struct Phases {
    int count = 0;
    double start[MAX_PHASES + 1];
    double p[MAX_PHASES], v[MAX_PHASES], a[MAX_PHASES], j[MAX_PHASES];
};

}  // namespace detail

//! A move's exact pieces (cubic, lowest power first) and the largest |v|, |a|, |j| of each
//! joint on them. Kept by a caller from move to move, its vectors keep their memory (a
//! move's pieces fill some 100 kB: allocated afresh, the pages cost more than the move).
struct Pieces {
    int n = 0;                   //!< joints
    std::vector<double> breaks;  //!< (p + 1) times (s)
    std::vector<double> coef;    //!< (p, 4, n)
    std::vector<double> knots;   //!< (k) the waypoints' times
    std::vector<double> peak;    //!< (3, n) largest |velocity|, |acceleration|, |jerk|
    // scratch of segment_pieces: each joint's phases, the switches, the segment's cuts
    std::vector<detail::Phases> phases;
    std::vector<double> cuts, local;
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
        out.start[c] = t, out.p[c] = p, out.v[c] = v, out.a[c] = a, out.j[c] = j;
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

//! Segment i of n joints (from p0, v0 to p1, v1, duration T, starting at t0 = knots[i],
//! ending at t1 = knots[i+1]) appended to out as pieces; out.breaks holds t0 already.
inline void segment_pieces(int n, double t0, double t1, double T, const double* p0, const double* v0,
                           const double* p1, const double* v1, const Limits* L, Pieces& out) {
    std::vector<detail::Phases>& ph = out.phases;
    std::vector<double>& cuts = out.cuts;
    std::vector<double>& local = out.local;
    ph.resize(static_cast<std::size_t>(n));
    cuts.clear();
    Profile prof;
    for (int j = 0; j < n; ++j) {
        profile(T, p1[j] - p0[j], v0[j], v1[j], L[j], prof);
        detail::walk(p0[j], v0[j], prof, ph[static_cast<std::size_t>(j)]);
        for (int c = 1; c < ph[static_cast<std::size_t>(j)].count; ++c) cuts.push_back(ph[static_cast<std::size_t>(j)].start[c]);
    }
    std::sort(cuts.begin(), cuts.end());
    const double tol = PIECE_RTOL * std::max(T, 1.0);
    local.assign(1, 0.0);
    for (const double c : cuts) {
        if (c - local.back() > tol && T - c > tol && t0 + c > t0 + local.back() && t0 + c < t1) local.push_back(c);
    }
    local.push_back(T);
    const std::size_t pieces = local.size() - 1;
    const std::size_t base = out.coef.size();
    out.coef.resize(base + pieces * 4 * static_cast<std::size_t>(n));
    for (std::size_t k = 0; k < pieces; ++k) {
        const double mid = 0.5 * (local[k] + local[k + 1]);
        double* c = out.coef.data() + base + k * 4 * static_cast<std::size_t>(n);
        for (int j = 0; j < n; ++j) {
            const detail::Phases& P = ph[static_cast<std::size_t>(j)];
            if (P.count == 0) {  // no phase: at rest where it is (a segment of zero duration)
                c[j] = p0[j], c[n + j] = v0[j], c[2 * n + j] = c[3 * n + j] = 0.0;
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
        for (int j = 0; j < n; ++j) detail::piece_peaks(c + j, n, local[k + 1] - local[k], out.peak.data() + j);
        out.breaks.push_back(k + 1 == pieces ? t1 : t0 + local[k + 1]);
    }
}

//! The pieces of the move through the k waypoints w (k, n) at velocities vel (k, n), segment
//! i lasting time[i].
inline void move_pieces(int k, int n, const double* w, const double* vel, const double* time, const Limits* L,
                        Pieces& out) {
    out.n = n;
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

//! Samples in each knot interval [a, b]: m = max(2, ⌈(b - a)/dt - 1e-9⌉ + 1) uniform ones,
//! the first being the previous interval's last. Their count in all (k - 1 intervals).
inline long sample_count(const std::vector<double>& knots, double dt) {
    long total = 1;
    for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
        const double span = knots[i + 1] - knots[i];
        total += std::max(2L, static_cast<long>(std::ceil(span / dt - 1e-9)) + 1) - 1;
    }
    return total;
}

//! q, q̇, q̈ and the jerk (m, n each) at the m sorted times t within pieces [first, last) of
//! P (the right-hand piece at a break; past the last piece's end, the last piece).
inline void sample_pieces(const Pieces& P, std::size_t first, std::size_t last, const double* t, long m, double* q,
                          double* qd, double* qdd, double* qddd) {
    const int n = P.n;
    std::size_t p = first;
    for (long s = 0; s < m; ++s) {
        while (p + 1 < last && P.breaks[p + 1] <= t[s]) ++p;
        const double tau = t[s] - P.breaks[p];
        const double* c = P.coef.data() + p * 4 * static_cast<std::size_t>(n);
        const std::size_t o = static_cast<std::size_t>(s) * n;
        for (int j = 0; j < n; ++j) {
            const double c0 = c[j], c1 = c[n + j], c2 = c[2 * n + j], c3 = c[3 * n + j];
            q[o + j] = c0 + tau * (c1 + tau * (c2 + tau * c3));
            qd[o + j] = c1 + tau * (2.0 * c2 + tau * 3.0 * c3);
            qdd[o + j] = 2.0 * c2 + tau * 6.0 * c3;
            qddd[o + j] = 6.0 * c3;
        }
    }
}

//! The samples of the move (sample_count(P.knots, dt) of them: t (m), q, q̇, q̈, jerk (m, n)),
//! segment by segment; the last is the end state (w_end, v_end, 0) exactly, with the jerk
//! that leads into it.
inline void move_samples(const Pieces& P, double dt, const double* w_end, const double* v_end, double* t, double* q,
                         double* qd, double* qdd, double* qddd) {
    const int n = P.n;
    const std::size_t k = P.knots.size(), pieces = P.breaks.size() - 1;
    t[0] = 0.0;
    long s = 1;
    std::size_t first = 0;
    sample_pieces(P, 0, 1, t, 1, q, qd, qdd, qddd);
    for (std::size_t i = 0; i + 1 < k; ++i) {
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
    const double* c = P.coef.data() + (pieces - 1) * 4 * static_cast<std::size_t>(n);
    for (int j = 0; j < n; ++j) {
        q[o + j] = w_end[j], qd[o + j] = v_end[j], qdd[o + j] = 0.0;
        qddd[o + j] = 6.0 * c[3 * n + j];
    }
}

}  // namespace km::jerk
