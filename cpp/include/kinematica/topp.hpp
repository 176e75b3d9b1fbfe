// Time-optimal timing of a joint path by reachability analysis (TOPP-RA: Pham & Pham,
// "A new approach to time-optimal path parameterization based on reachability analysis",
// IEEE T-RO 2018): backward controllable sets, then a forward greedy pass.
//
// The path q(s) is a polynomial on each interval [s_i, s_i+1] of a grid. Within an
// interval the path acceleration u = s̈ is constant, so x = ṡ² is linear in s: from x
// (at s_i) to y (at s_i+1), u = (y - x) / (2h). The joint velocity and acceleration
//     q̇ = q'(s) ṡ,        q̈ = q'(s) u + q''(s) ṡ²
// are then, over the whole interval, polynomials in t = (s - s_i) / h whose coefficients
// are linear in (x, y):
//     q'(t)² ṡ² = x·q'²(1 - t) + y·q'²·t
//     q̈(t)     = x·(q''(1 - t) - q'/(2h)) + y·(q''·t + q'/(2h)).
// A polynomial on [0, 1] lies within the convex hull of its Bernstein coefficients, so
// asking every Bernstein coefficient to lie within the limits is a finite set of linear
// inequalities a·x + b·y <= c that holds the limits at every s of the interval, not only
// at the grid points (the collocation of the paper holds them at the grid points only).
// The coefficients differ from the polynomial's values by O(h²): the price in time is
// second order in the grid spacing.
//
// Every stage's feasible set of (x, y) is a convex polygon; the sets the passes need
// (the largest or smallest x given y in an interval, and the reverse) are found exactly
// by Newton's method on the concave piecewise-linear gap U(x) - L(x) between the
// tightest upper and lower bounds on y: from outside the feasible interval each Newton
// step lands on a new piece, never past the answer (a concave function lies below its
// tangents), so a few steps of O(rows) each give it, with no LP solver.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace km::topp {

//! Highest degree of the path's polynomial pieces (quintic).
constexpr int MAX_DEGREE = 5;
//! Rows of one joint at one stage: velocity (Bernstein degree 2·MAX_DEGREE - 1) and
//! acceleration (two sides of degree MAX_DEGREE - 1).
constexpr int MAX_JOINT_ROWS = 2 * MAX_DEGREE + 2 * MAX_DEGREE;
//! Relative shortfall of the gap U(x) - L(x) accepted as round-off.
constexpr double GAP_RTOL = 1e-12;
//! Newton steps allowed when locating a set's end (each lands on a new piece).
constexpr int MAX_NEWTON = 100;

//! What a row limits.
enum class Kind : int { velocity = 0, acceleration = 1, cap = 2, next_set = 3, none = 4 };

//! One inequality a·x + b·y <= c on the squared path speeds at both ends of a stage.
struct Row {
    double a, b, c;
    Kind kind;
    int joint;
};

//! How the timing ended.
//! Stages between two calls of the caller's stop() (a few µs to tens of µs of work).
constexpr int STOP_STAGES = 64;
//! interrupted: the caller's stop() said so; the outputs are then incomplete.
enum class Status : int { ok = 0, stuck = 1, start_outside = 2, empty = 3, interrupted = 4 };

//! A path and its limits, every array owned by the caller.
struct Problem {
    int n = 0;                      //!< joints
    int N = 0;                      //!< intervals (grid points N + 1)
    int degree = 3;                 //!< degree of the pieces, 1..MAX_DEGREE
    const double* s = nullptr;      //!< (N + 1) increasing grid
    const double* coef = nullptr;   //!< (N, degree + 1, n): Taylor coefficients of q at s_i
    const double* vlo = nullptr;    //!< (n) joint velocity limits, vlo <= 0 <= vhi (±inf: none)
    const double* vhi = nullptr;
    const double* alo = nullptr;    //!< (n) joint acceleration limits, alo <= 0 <= ahi
    const double* ahi = nullptr;
    const double* cap = nullptr;    //!< (N) largest x = ṡ² within each interval (inf: none)
    double x_start = 0.0;           //!< ṡ² at s_0
    double x_end = 0.0;             //!< ṡ² at s_N
    double x_max = 1e12;            //!< largest ṡ² anywhere (bounds a path that does not move)

    //! Why these values are not a problem time_optimal takes (nullptr: they are one): the
    //! grid finite and strictly increasing, the caps >= 0, the coefficients finite, each
    //! limit's low <= 0 <= high, the end speeds finite and >= 0, x_max finite and > 0.
    const char* invalid() const {
        for (int i = 0; i < N; ++i) {
            if (!(s[i + 1] > s[i]) || !std::isfinite(s[i + 1] - s[i])) {
                return "s must be finite and strictly increasing";
            }
            if (!(cap[i] >= 0.0)) return "cap must be >= 0 (inf for none)";
        }
        for (long k = 0; k < static_cast<long>(N) * (degree + 1) * n; ++k) {
            if (!std::isfinite(coef[k])) return "coef must be finite";
        }
        for (int j = 0; j < n; ++j) {
            if (!(vlo[j] <= 0.0 && vhi[j] >= 0.0 && alo[j] <= 0.0 && ahi[j] >= 0.0)) {
                return "limits must be lo <= 0 <= hi for every joint";
            }
        }
        if (!(x_start >= 0.0 && x_end >= 0.0 && std::isfinite(x_start) && std::isfinite(x_end))) {
            return "x_start and x_end must be finite squared speeds >= 0";
        }
        if (!(x_max > 0.0 && std::isfinite(x_max))) return "x_max must be a finite positive number";
        return nullptr;
    }
};

//! The outcome; the arrays (N + 1 each) are the caller's.
struct Output {
    double* x = nullptr;      //!< ṡ² along the grid (NaN past where the timing stops)
    double* k_lo = nullptr;   //!< controllable sets [k_lo, k_hi] (NaN where empty)
    double* k_hi = nullptr;
    double* r_lo = nullptr;   //!< reachable sets from x_start within the controllable ones
    double* r_hi = nullptr;
    double* mvc = nullptr;    //!< largest ṡ² each stage's own limits allow (the limit curve)
    Status status = Status::ok;
    int stage = -1;           //!< grid index where the timing stops (status != ok)
    Kind kind = Kind::none;   //!< the limit that stops it
    int joint = -1;           //!< its joint (velocity, acceleration), else -1
};

namespace detail {

//! Highest degree of a polynomial the rows are made of (q'² times a line, quintic path).
constexpr int MAX_BERNSTEIN = 2 * MAX_DEGREE - 1;

//! Power-to-Bernstein conversion on [0, 1]: b_k = Σ_{j<=k} C(k, j) / C(d, j) · a_j.
struct BernsteinTable {
    double w[MAX_BERNSTEIN + 1][MAX_BERNSTEIN + 1][MAX_BERNSTEIN + 1] = {};
    BernsteinTable() {
        double C[MAX_BERNSTEIN + 1][MAX_BERNSTEIN + 1] = {};
        for (int n = 0; n <= MAX_BERNSTEIN; ++n) {
            C[n][0] = 1.0;
            for (int k = 1; k <= n; ++k) C[n][k] = C[n - 1][k - 1] + (k <= n - 1 ? C[n - 1][k] : 0.0);
        }
        for (int d = 0; d <= MAX_BERNSTEIN; ++d)
            for (int k = 0; k <= d; ++k)
                for (int j = 0; j <= k; ++j) w[d][k][j] = C[k][j] / C[d][j];
    }
    void convert(const double* p, int d, double* out) const {
        for (int k = 0; k <= d; ++k) {
            double sum = 0.0;
            for (int j = 0; j <= k; ++j) sum += w[d][k][j] * p[j];
            out[k] = sum;
        }
    }
};

//! Each row of stage i, given to sink(a, b, c, kind, joint): every joint's velocity and
//! acceleration over the whole interval, then the cap. DEG: the degree of the pieces (a
//! template parameter, so that the short loops below unroll).
template <int DEG, class Sink>
inline void for_each_row(const Problem& P, const BernsteinTable& bt, int i, Sink&& sink) {
    constexpr int d1deg = DEG - 1;  // degree of q'
    constexpr int D = 2 * d1deg;    // degree of q'²
    const int n = P.n;
    const double h = P.s[i + 1] - P.s[i];
    const double half_inv_h = 0.5 / h;
    const double* c = P.coef + static_cast<std::ptrdiff_t>(i) * (DEG + 1) * n;
    for (int j = 0; j < n; ++j) {
        // q'(t) and q''(t) in t = τ/h, power basis.
        double d1[MAX_DEGREE + 1] = {0.0}, d2[MAX_DEGREE + 1] = {0.0};
        double hp = 1.0;  // h^(m-1)
        for (int m = 1; m <= DEG; ++m) {
            d1[m - 1] = m * c[m * n + j] * hp;
            if (m >= 2) d2[m - 2] = (m - 1) * d1[m - 1] / h;
            hp *= h;
        }
        const double vhi = P.vhi[j], vlo = P.vlo[j];
        if (std::isfinite(vhi) || std::isfinite(vlo)) {
            double b1[MAX_DEGREE + 1];
            bt.convert(d1, d1deg, b1);
            bool pos = true, neg = true, zero = true;
            for (int k = 0; k <= d1deg; ++k) {
                pos = pos && b1[k] >= 0.0;
                neg = neg && b1[k] <= 0.0;
                zero = zero && b1[k] == 0.0;
            }
            // The bound on |q̇| that holds for the sign(s) q' takes on the interval.
            const double v = pos ? vhi : neg ? -vlo : std::min(vhi, -vlo);
            if (!zero && std::isfinite(v)) {
                double sq[MAX_BERNSTEIN + 1] = {0.0};
                for (int a = 0; a <= d1deg; ++a)
                    for (int b = 0; b <= d1deg; ++b) sq[a + b] += d1[a] * d1[b];
                double B[MAX_BERNSTEIN + 1] = {0.0};
                bt.convert(sq, D, B);
                // x·(1 - t)·q'² + y·t·q'², degree D + 1.
                for (int k = 0; k <= D + 1; ++k) {
                    const double a = k <= D ? (D + 1 - k) * B[k] / (D + 1) : 0.0;
                    const double b = k >= 1 ? k * B[k - 1] / (D + 1) : 0.0;
                    sink(a, b, v * v, Kind::velocity, j);
                }
            }
        }
        const double ahi = P.ahi[j], alo = P.alo[j];
        if (std::isfinite(ahi) || std::isfinite(alo)) {
            // q̈ = x·A(t) + y·B(t), A = q''(1 - t) - q'/(2h), B = q''·t + q'/(2h).
            double A[MAX_DEGREE + 1] = {0.0}, Bp[MAX_DEGREE + 1] = {0.0};
            for (int k = 0; k <= d1deg; ++k) {
                A[k] = -d1[k] * half_inv_h;
                Bp[k] = d1[k] * half_inv_h;
            }
            for (int k = 0; k + 2 <= DEG; ++k) {
                A[k] += d2[k];
                A[k + 1] -= d2[k];
                Bp[k + 1] += d2[k];
            }
            double bA[MAX_DEGREE + 1], bB[MAX_DEGREE + 1];
            bt.convert(A, d1deg, bA);
            bt.convert(Bp, d1deg, bB);
            for (int k = 0; k <= d1deg; ++k) {
                if (std::isfinite(ahi)) sink(bA[k], bB[k], ahi, Kind::acceleration, j);
                if (std::isfinite(alo)) sink(-bA[k], -bB[k], -alo, Kind::acceleration, j);
            }
        }
    }
    const double cap = std::min(P.cap[i], P.x_max);
    sink(1.0, 0.0, cap, Kind::cap, -1);
    sink(0.0, 1.0, cap, Kind::cap, -1);
}

//! for_each_row at the problem's degree.
template <class Sink>
inline void each_row(const Problem& P, const BernsteinTable& bt, int i, Sink&& sink) {
    switch (P.degree) {
        case 1: for_each_row<1>(P, bt, i, sink); break;
        case 2: for_each_row<2>(P, bt, i, sink); break;
        case 3: for_each_row<3>(P, bt, i, sink); break;
        case 4: for_each_row<4>(P, bt, i, sink); break;
        default: for_each_row<5>(P, bt, i, sink); break;
    }
}

//! The rows of stage i as a list (for naming the limit that stops a path).
inline void stage_rows(const Problem& P, const BernsteinTable& bt, int i, std::vector<Row>& rows) {
    rows.clear();
    each_row(P, bt, i, [&](double a, double b, double c, Kind kind, int joint) {
        rows.push_back({a, b, c, kind, joint});
    });
}

//! A bound p + r·x on the second variable of a stage at its first one x.
struct Line {
    double p, r;
};

//! A stage's rows solved for one of its variables: upper and lower bounds on it as lines
//! in the other, and the bounds on the other alone.
struct Lines {
    std::vector<Line> up, lo;
    double first_lo = 0.0, first_hi = std::numeric_limits<double>::infinity();
    bool never = false;  //!< a row 0 <= c < 0: nothing satisfies it

    void clear() {
        up.clear();
        lo.clear();
        first_lo = 0.0;
        first_hi = std::numeric_limits<double>::infinity();
        never = false;
    }

    //! Add the row a·x + b·y <= c, solved for y.
    void add(double a, double b, double c) {
        if (b > 0.0) {
            const double inv = 1.0 / b;
            up.push_back({c * inv, -a * inv});
        } else if (b < 0.0) {
            const double inv = 1.0 / b;
            lo.push_back({c * inv, -a * inv});
        } else if (a > 0.0) {
            first_hi = std::min(first_hi, c / a);
        } else if (a < 0.0) {
            first_lo = std::max(first_lo, c / a);
        } else if (c < 0.0) {
            never = true;
        }
    }

    //! Stage i's rows, solved for y (swap: for x).
    void build(const Problem& P, const BernsteinTable& bt, int i, bool swap) {
        clear();
        each_row(P, bt, i, [&](double a, double b, double c, Kind, int) {
            if (swap) add(b, a, c);
            else add(a, b, c);
        });
    }
};

//! The tightest bounds on the second variable at the first one, with their slopes.
struct Bounds {
    double U, su, L, sl;
};

inline Bounds bounds_at(const Lines& L, double x, double ylo, double yhi) {
    Bounds r{yhi, 0.0, ylo, 0.0};
    for (const Line& l : L.up) {
        const double v = l.p + l.r * x;
        if (v < r.U) {
            r.U = v;
            r.su = l.r;
        }
    }
    for (const Line& l : L.lo) {
        const double v = l.p + l.r * x;
        if (v > r.L) {
            r.L = v;
            r.sl = l.r;
        }
    }
    return r;
}

inline double gap_tol(const Bounds& b) { return GAP_RTOL * (std::fabs(b.U) + std::fabs(b.L)) + 1e-300; }

//! The largest (or smallest) first variable of a feasible pair, the second in [ylo, yhi]
//! and the first in [xlo, xhi]; false when there is none.
inline bool extreme(const Lines& L, bool largest, double xlo, double xhi, double ylo, double yhi,
                    double& out) {
    if (L.never || !(ylo <= yhi)) return false;
    xlo = std::max(xlo, L.first_lo);
    xhi = std::min(xhi, L.first_hi);
    if (!(xlo <= xhi)) return false;
    double x = largest ? xhi : xlo;
    for (int it = 0; it < MAX_NEWTON; ++it) {
        const Bounds b = bounds_at(L, x, ylo, yhi);
        const double g = b.U - b.L;
        if (g >= -gap_tol(b)) {
            out = x;
            return true;
        }
        const double slope = b.su - b.sl;
        // Concave gap: from the right it must rise leftwards, from the left rightwards.
        if (largest ? !(slope < 0.0) : !(slope > 0.0)) return false;
        const double next = x - g / slope;
        if (largest ? next <= xlo : next >= xhi) {
            if (x == (largest ? xlo : xhi)) return false;
            x = largest ? xlo : xhi;
        } else {
            if (next == x) return false;
            x = next;
        }
    }
    return false;
}

//! The first row that forces y = 0 at x = 0 (the limit that stops the path); false if none.
inline bool name_stop(const std::vector<Row>& rows, Output& out) {
    for (const Row& w : rows) {
        if (w.b > 0.0 && w.c <= 0.0) {
            out.kind = w.kind;
            out.joint = w.joint;
            return true;
        }
    }
    return false;
}

}  // namespace detail

//! Scratch of one timing, reused across calls.
struct Workspace {
    std::vector<detail::Lines> stages;
    std::vector<Row> rows;
    detail::Lines swapped;
    detail::BernsteinTable bernstein;
};

//! Time-optimal ṡ² along the grid within every limit at every s (see the file comment).
//! sets: also the limit curve and the reachable sets (NaN otherwise). stop, when given, is
//! asked every STOP_STAGES stages of either pass; once it says true the call returns with
//! status interrupted (a long path in a thread the caller must be able to stop).
inline void time_optimal(const Problem& P, Output& out, Workspace& ws, bool sets = true,
                         const std::function<bool()>& stop = {}) {
    using detail::extreme;
    const int N = P.N;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    ws.stages.resize(N);
    for (int i = 0; i <= N; ++i) {
        out.x[i] = out.k_lo[i] = out.k_hi[i] = out.r_lo[i] = out.r_hi[i] = out.mvc[i] = nan;
    }
    // Backward: the controllable sets.
    out.k_lo[N] = out.k_hi[N] = P.x_end;
    out.status = Status::ok;
    const auto stopped = [&stop, &out](int i) {
        if (!stop || i % STOP_STAGES != 0 || !stop()) return false;
        out.status = Status::interrupted;
        out.stage = i;
        return true;
    };
    for (int i = N - 1; i >= 0; --i) {
        if (stopped(i)) return;
        ws.stages[i].build(P, ws.bernstein, i, false);
        if (sets) {
            double v;
            if (extreme(ws.stages[i], true, 0.0, inf, 0.0, inf, v)) out.mvc[i] = v;
            if (i == N - 1) {
                ws.swapped.build(P, ws.bernstein, i, true);
                if (extreme(ws.swapped, true, 0.0, inf, 0.0, inf, v)) out.mvc[N] = v;
            }
        }
        if (out.status != Status::ok) continue;  // the limit curve goes on
        double lo, hi;
        if (!extreme(ws.stages[i], false, 0.0, inf, out.k_lo[i + 1], out.k_hi[i + 1], lo) ||
            !extreme(ws.stages[i], true, 0.0, inf, out.k_lo[i + 1], out.k_hi[i + 1], hi)) {
            out.status = Status::empty;
            out.stage = i;
            continue;
        }
        out.k_lo[i] = lo;
        out.k_hi[i] = std::max(lo, hi);
    }
    if (out.status != Status::ok) return;
    const double x0 = P.x_start;
    if (x0 > out.k_hi[0] * (1.0 + GAP_RTOL) || x0 < out.k_lo[0] * (1.0 - GAP_RTOL)) {
        out.status = Status::start_outside;
        out.stage = 0;
        return;
    }
    // Forward: the fastest successor within the next controllable set.
    out.x[0] = out.r_lo[0] = out.r_hi[0] = x0;
    for (int i = 0; i < N; ++i) {
        if (stopped(i)) return;
        const detail::Lines& L = ws.stages[i];
        const double x = out.x[i];
        const detail::Bounds b = detail::bounds_at(L, x, out.k_lo[i + 1], out.k_hi[i + 1]);
        const double y = std::max(0.0, b.U);
        if (sets) {  // successors of the reachable x within the controllable sets
            ws.swapped.build(P, ws.bernstein, i, true);
            const double xa = std::max(out.r_lo[i], out.k_lo[i]), xb = std::min(out.r_hi[i], out.k_hi[i]);
            double rlo, rhi;
            if (extreme(ws.swapped, false, out.k_lo[i + 1], out.k_hi[i + 1], xa, xb, rlo) &&
                extreme(ws.swapped, true, out.k_lo[i + 1], out.k_hi[i + 1], xa, xb, rhi)) {
                out.r_lo[i + 1] = rlo;
                out.r_hi[i + 1] = std::max(rlo, rhi);
            }
        }
        if (x <= 0.0 && y <= 0.0) {  // at rest and held there: the path cannot go on
            out.status = Status::stuck;
            out.stage = i;
            for (int j = i; j < N; ++j) {  // the stage whose own limit holds it, not the sets'
                if (detail::bounds_at(ws.stages[j], 0.0, 0.0, inf).U <= 0.0) {
                    detail::stage_rows(P, ws.bernstein, j, ws.rows);
                    if (detail::name_stop(ws.rows, out)) break;
                }
            }
            return;
        }
        out.x[i + 1] = y;
    }
}

}  // namespace km::topp
