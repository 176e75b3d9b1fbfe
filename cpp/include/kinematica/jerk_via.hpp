// Jerk-limited moves through waypoints (jerk.hpp's segments), the velocities at the
// waypoints chosen to make the whole move short; the acceleration at every waypoint is zero.
//
// 1. A direction per waypoint from its neighbours: a joint that moves the same way before
//    and after the waypoint keeps moving through it, along the chord w[i+1] - w[i-1]; a
//    joint that turns back (or does not move on one side) passes it at rest. The chord is
//    scaled to the highest speed the joints' limits allow along it: vhat[i].
// 2. The velocity at waypoint i is λ_i·vhat[i], λ_i in [0, 1]: one common λ for every
//    waypoint is tried on a grid (a stop at each included), then each λ_i in turn by a
//    golden-section search on the sum of its two segments' durations; then, optionally,
//    each joint's own speed at each waypoint. A value is kept only when it shortens the
//    move, so the result is never longer than a stop at every waypoint.
// 3. With position limits a segment whose exact extremes leave them counts as infinitely
//    long, so the search keeps only velocities whose segments stay inside.
// A heuristic over one number per waypoint (and per joint), not a global optimum: its
// duration is an upper bound of the best jerk-limited move through the same waypoints.
//
// What makes it cheap (the choices are those of searching on the durations themselves):
// - A segment's duration is the smallest one its slowest joint can take that no joint's
//   blocked durations hold (jerk.hpp), so only a *binding* joint (the slowest alone, or one
//   that moved the duration past its blocked ones) can shorten it: the per-joint search
//   skips every joint that binds neither segment next to its waypoint, and times the one
//   it searches against the other joints' duration, kept once (one joint planned, not n).
// - The other joints' duration bounds a joint's search from below (a joint added to a
//   segment only lengthens it): the search is skipped where that bound is no shorter than
//   the two segments today, and ends once a candidate reaches it (no later candidate could
//   replace it): the result is the full search's, to the bit, in 8 % fewer evaluations.
// - The joints whose velocity a candidate does not change keep their shortest durations.
// - A golden section compares each new point with the one it keeps, and drops the worse: a
//   point whose lower bound is already above the kept one's value needs no more work. A
//   segment lasts at least its slowest joint's shortest duration (the λ search times each
//   segment's slowest joint of the chosen move first, then the others, and stops once the
//   bound passes), and, in the per-joint search, at least the other joints' duration: the
//   search goes as with every point timed in full, to the bit (a fifth of the λ search's
//   points are dropped so). The best point's timing is kept, not timed again once chosen;
//   a common λ on the grid stops timing its segments once their sum passes the best.
// - With position limits, each golden section runs on the durations without them (no
//   profile built) and its best point is then checked; only where that leaves qlim is the
//   section run again with every point checked.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

#include "kinematica/jerk.hpp"

namespace km::jerk {

//! Common speed fractions of the first search (0: a stop at every waypoint).
constexpr double VIA_GRID[] = {0.0, 0.5, 1.0};
//! (√5 - 1)/2.
constexpr double GOLD = 0.6180339887498949;

//! How hard the search looks.
struct ViaParams {
    int sweeps = 1;        //!< sweeps over the waypoints with one speed fraction each
    int golden_steps = 8;  //!< evaluations of each golden-section search (0.618^8 ~ 2 %)
    int joint_sweeps = 0;  //!< then sweeps over each joint's own speed at each waypoint
};

//! The waypoints and limits, every array the caller's.
struct Via {
    int k = 0;                       //!< waypoints (>= 2)
    int n = 0;                       //!< joints
    const double* w = nullptr;       //!< (k, n) waypoints, no two in a row equal
    const double* v_start = nullptr; //!< (n) velocity at the first waypoint
    const double* v_end = nullptr;   //!< (n) velocity at the last
    const Limits* limits = nullptr;  //!< (n)
    const double* qlim = nullptr;    //!< (n, 2) position limits (low, high), or nullptr
    double qlim_atol = 0.0;          //!< how far an extreme may pass a position limit
};

//! What the search chose; the arrays are the caller's.
struct ViaOutput {
    double* velocity = nullptr;  //!< (k, n) at the waypoints
    double* time = nullptr;      //!< (k - 1) each segment's duration
    double* stop = nullptr;      //!< (k - 1) each segment's duration with a stop at every waypoint
    long evaluations = 0;        //!< segments planned by the search
};

//! Lowest and highest position of a joint's profile from (p0, v0, 0): its ends, and where
//! its velocity (quadratic in each phase) is zero inside a phase.
inline void extremes(double p0, double v0, const Profile& P, double& lo, double& hi) {
    double p = p0, v = v0, a = 0.0;
    lo = hi = p0;
    for (int k = 0; k < P.phases; ++k) {
        const double h = P.t[k], j = P.j[k];
        // v + a τ + j τ²/2 = 0 for τ in (0, h)
        double roots[2];
        int nr = 0;
        if (j == 0.0) {
            if (a != 0.0) roots[nr++] = -v / a;
        } else {
            const double disc = a * a - 2.0 * j * v;
            if (disc >= 0.0) {
                const double sq = std::sqrt(disc);
                roots[nr++] = (-a + sq) / j;
                roots[nr++] = (-a - sq) / j;
            }
        }
        for (int r = 0; r < nr; ++r) {
            const double tau = roots[r];
            if (tau > 0.0 && tau < h) {
                const double x = p + tau * (v + tau * (a / 2.0 + tau * j / 6.0));
                lo = std::min(lo, x);
                hi = std::max(hi, x);
            }
        }
        p += h * (v + h * (a / 2.0 + h * j / 6.0));
        v += h * (a + h * j / 2.0);
        a += h * j;
        lo = std::min(lo, p);
        hi = std::max(hi, p);
    }
}

//! Whether every profile of duration T from (p0, v0, 0) to (p1, v1, 0) that profile() can
//! return surely stays within [low, high], without building it (false: not known). Its
//! velocity lies between the lowest and the highest peak of the extreme shapes of T (a
//! shape with one cruise between them, or their convex combination), each at most vmax:
//! from either end the position moves at most that fast. A bound, with room for the
//! round-off of extremes(): where it says inside, extremes() does too.
inline bool inside(double p0, double p1, double v0, double v1, double T, const Limits& L, double low,
                   double high) {
    // the highest of min(p0 + vh·t, p1 - vl·(T - t)) over t in [0, T]: at an end or where
    // the two lines cross (and the lowest of the mirror image)
    const auto reach = [T](double a, double b, double up, double down) {
        double best = std::max(std::min(a, b - down * T), std::min(a + up * T, b));
        if (up > down) {
            const double t = (b - a - down * T) / (up - down);
            if (t > 0.0 && t < T) best = std::max(best, a + up * t);
        }
        return best;
    };
    const auto fits = [&](double vh, double vl) {
        const double guard = 1e-12 * (1.0 + std::fabs(p0) + std::fabs(p1) + (vh - vl) * T);
        return reach(p0, p1, vh, vl) + guard <= high && -reach(-p0, -p1, -vl, -vh) - guard >= low;
    };
    if (fits(L.v, -L.v)) return true;
    const double Tm = std::max(T, detail::ramp_time(v1 - v0, L));
    const double vh = detail::extreme(Tm, v0, v1, true, L).vp, vl = detail::extreme(Tm, v0, v1, false, L).vp;
    return fits(std::max({vh, v0, v1}), std::min({vl, v0, v1}));
}

namespace detail {

//! The search's state: the problem, the chosen velocities and durations, scratch.
class ViaSearch {
public:
    ViaSearch(const Via& P, ViaOutput& out)
        : P_(P),
          out_(out),
          t_(P.n),
          shortest_((P.k - 1) * P.n),
          vhat_(P.k * P.n),
          trial_(P.n),
          grid_t_((P.k - 1) * P.n),
          b_(P.n),
          binding_((P.k - 1) * P.n),
          grid_b_((P.k - 1) * P.n),
          changed_(P.k - 1, 0),
          pair_t_(2 * P.n),
          seen_t_(2 * P.n),
          pair_b_(2 * P.n),
          seen_b_(2 * P.n) {}

    void run(const ViaParams& prm) {
        const int k = P_.k, n = P_.n;
        directions();
        double* vel = out_.velocity;
        for (int i = 0; i < k * n; ++i) vel[i] = 0.0;
        for (int j = 0; j < n; ++j) {
            vel[j] = P_.v_start[j];
            vel[(k - 1) * n + j] = P_.v_end[j];
        }
        // each total() keeps its segments' shortest durations and binding joints in
        // grid_t_, grid_b_: the best's are the chosen segments'
        double best = total(vel, out_.stop);
        std::vector<double> trial_vel(vel, vel + k * n), trial_time(k - 1);
        for (int i = 0; i < k - 1; ++i) out_.time[i] = out_.stop[i];
        if (!std::isfinite(best)) return;  // the caller names the segment
        shortest_.swap(grid_t_);
        binding_.swap(grid_b_);
        for (const double x : VIA_GRID) {
            if (x == 0.0) continue;
            for (int i = 1; i < k - 1; ++i) {
                for (int j = 0; j < n; ++j) trial_vel[i * n + j] = x * vhat_[i * n + j];
            }
            const double d = total(trial_vel.data(), trial_time.data(), best);
            if (d < best) {
                best = d;
                std::copy(trial_vel.begin(), trial_vel.end(), vel);
                std::copy(trial_time.begin(), trial_time.end(), out_.time);
                shortest_.swap(grid_t_);
                binding_.swap(grid_b_);
            }
        }
        kept_ = true;
        for (int s = 0; s < prm.sweeps; ++s) {
            for (int i = 1; i < k - 1; ++i) {
                bool moving = false;
                for (int j = 0; j < n; ++j) moving = moving || vhat_[i * n + j] != 0.0;
                if (!moving) continue;
                improve(i, prm.golden_steps, -1, [&](double x, double* v) {
                    for (int j = 0; j < n; ++j) v[j] = x * vhat_[i * n + j];
                });
            }
        }
        // a waypoint whose two segments have not changed since its last search began would
        // be searched to the same end: skipped
        std::vector<long> searched(k, -1);
        for (int s = 0; s < prm.joint_sweeps; ++s) {
            for (int i = 1; i < k - 1; ++i) {
                if (searched[i] >= std::max(changed_[i - 1], changed_[i])) continue;
                searched[i] = accepted_;
                for (int j = 0; j < n; ++j) {
                    // an onward joint in its direction; one that turns back may pass its
                    // waypoint moving either way (overshooting it on one side)
                    const double before = P_.w[i * n + j] - P_.w[(i - 1) * n + j];
                    const double after = P_.w[(i + 1) * n + j] - P_.w[i * n + j];
                    const double vh = vhat_[i * n + j];
                    const double signs[2] = {vh != 0.0 ? vh : before, vh != 0.0 ? 0.0 : after};
                    for (const double sign : signs) {
                        if (sign == 0.0) continue;
                        const double top = (sign > 0.0 ? 1.0 : -1.0) * P_.limits[j].v;
                        improve(i, prm.golden_steps, j, [&](double x, double* v) {
                            std::copy(vel + i * n, vel + (i + 1) * n, v);
                            v[j] = x * top;
                        });
                    }
                }
            }
        }
    }

private:
    //! Duration of segment i (waypoint i to i+1) from velocity vi to vj; inf if it leaves
    //! qlim. Each joint's shortest duration is left in t_, the binding joints in b_.
    double time(int i, const double* vi, const double* vj, bool qlim = true) {
        const int n = P_.n;
        const double* p0 = P_.w + i * n;
        const double* p1 = p0 + n;
        ++out_.evaluations;
        for (int j = 0; j < n; ++j) t_[j] = joint_time(i, vi, vj, j);
        const double T = synchronised(n, p0, vi, p1, vj, P_.limits, t_.data(), -1, b_.data());
        return !qlim || within_qlim(i, T, vi, vj, -1) ? T : std::numeric_limits<double>::infinity();
    }

    //! Joint j's shortest duration in segment i from vi to vj: the chosen segment's where
    //! its velocities are the chosen ones (kept).
    double joint_time(int i, const double* vi, const double* vj, int j) const {
        const int n = P_.n;
        const double* ci = out_.velocity + i * n;
        const double* p0 = P_.w + i * n;
        return kept_ && vi[j] == ci[j] && vj[j] == ci[n + j] ? shortest_[i * n + j]
                                                            : shortest(p0[n + j] - p0[j], vi[j], vj[j], P_.limits[j]);
    }

    //! The two segments next to waypoint i, its velocity v: their durations' sum (time()),
    //! or, once the longest of each segment's joints' shortest durations timed so far (the
    //! chosen segment's slowest joint first) sum above cutoff, that sum (a lower bound:
    //! synchronised() only lengthens the longest). Timed in full, each segment's duration,
    //! its joints' shortest durations and binding joints are left in pair_T_, pair_t_, pair_b_.
    double pair(int i, const double* v, bool qlim, double cutoff) {
        const int n = P_.n;
        const double* vel = out_.velocity;
        const double* from[2] = {vel + (i - 1) * n, v};
        const double* to[2] = {v, vel + (i + 1) * n};
        double top[2];
        int first[2];
        for (int s = 0; s < 2; ++s) {
            const double* c = shortest_.data() + (i - 1 + s) * n;
            first[s] = static_cast<int>(std::max_element(c, c + n) - c);
            top[s] = pair_t_[s * n + first[s]] = joint_time(i - 1 + s, from[s], to[s], first[s]);
        }
        if (top[0] + top[1] > cutoff) return top[0] + top[1];
        for (int s = 0; s < 2; ++s) {
            for (int j = 0; j < n; ++j) {
                if (j == first[s]) continue;
                const double t = pair_t_[s * n + j] = joint_time(i - 1 + s, from[s], to[s], j);
                top[s] = std::max(top[s], t);
            }
            if (top[0] + top[1] > cutoff) return top[0] + top[1];
        }
        for (int s = 0; s < 2; ++s) {
            const int seg = i - 1 + s;
            const double* p0 = P_.w + seg * n;
            ++out_.evaluations;
            const double T = synchronised(n, p0, from[s], p0 + n, to[s], P_.limits, pair_t_.data() + s * n, -1,
                                          pair_b_.data() + s * n);
            pair_T_[s] = !qlim || within_qlim(seg, T, from[s], to[s], -1) ? T : std::numeric_limits<double>::infinity();
        }
        return pair_T_[0] + pair_T_[1];
    }

    //! time(i, vi, vj) when only `joint`'s velocities differ from the chosen ones. tw: the
    //! segment's duration without that joint; bind: whether the joint binds the chosen
    //! segment (else tw is its duration, whose other joints are known to keep qlim); tj: the
    //! joint's shortest duration. The other joints' shortest durations are the chosen
    //! segment's (not computed again).
    double time_joint(int i, const double* vi, const double* vj, int joint, double tj, double tw, bool bind,
                      bool qlim) {
        const int n = P_.n;
        const double* p0 = P_.w + i * n;
        const double* p1 = p0 + n;
        ++out_.evaluations;
        const double d = p1[joint] - p0[joint];
        const Limits& L = P_.limits[joint];
        double T;
        bool others_kept = !bind;
        if (tj <= tw && unblocked(tw, d, vi[joint], vj[joint], L) == tw) {
            T = tw;  // the other joints' duration, which this joint can take
        } else {
            std::copy(shortest_.begin() + i * n, shortest_.begin() + (i + 1) * n, t_.begin());
            t_[joint] = tj;
            T = synchronised(n, p0, vi, p1, vj, P_.limits, t_.data());
            others_kept = false;
        }
        if (!qlim) return T;
        return within_qlim(i, T, vi, vj, others_kept ? joint : -1) ? T : std::numeric_limits<double>::infinity();
    }

    //! t_ and b_ (of segment i at the chosen velocities) kept.
    void keep(int i) {
        const int n = P_.n;
        std::copy(t_.begin(), t_.end(), shortest_.begin() + i * n);
        std::copy(b_.begin(), b_.end(), binding_.begin() + i * n);
    }

    //! Whether every joint of segment i (only `joint` if >= 0), of duration T, stays within
    //! qlim.
    bool within_qlim(int i, double T, const double* vi, const double* vj, int joint) const {
        const int n = P_.n;
        const double* p0 = P_.w + i * n;
        const double* p1 = p0 + n;
        if (P_.qlim == nullptr || !std::isfinite(T)) return true;
        Profile prof;
        for (int j = joint < 0 ? 0 : joint; j < (joint < 0 ? n : joint + 1); ++j) {
            const double low = P_.qlim[2 * j] - P_.qlim_atol, high = P_.qlim[2 * j + 1] + P_.qlim_atol;
            if (inside(p0[j], p1[j], vi[j], vj[j], T, P_.limits[j], low, high)) continue;
            profile(T, p1[j] - p0[j], vi[j], vj[j], P_.limits[j], prof);
            double lo, hi;
            extremes(p0[j], vi[j], prof, lo, hi);
            if (lo < low || hi > high) return false;
        }
        return true;
    }

    //! The move's duration at the velocities vel (k, n) (no kept values used), each segment's
    //! in times; its joints' shortest durations and binding joints in grid_t_, grid_b_. Once
    //! the segments timed reach `above`, their sum (the rest left untimed).
    double total(const double* vel, double* times, double above = std::numeric_limits<double>::infinity()) {
        const int n = P_.n;
        double sum = 0.0;
        for (int i = 0; i < P_.k - 1; ++i) {
            times[i] = time(i, vel + i * n, vel + (i + 1) * n);
            std::copy(t_.begin(), t_.end(), grid_t_.begin() + i * n);
            std::copy(b_.begin(), b_.end(), grid_b_.begin() + i * n);
            sum += times[i];
            if (sum >= above) break;
        }
        return sum;
    }

    //! The best of `steps` evaluations of f on [0, 1] by golden section: (x, f(x)).
    //! floor: a value no f(x) is below; once the best reaches it, the rest of the search
    //! could not replace it (only a strictly lower value does), so it ends there.
    //! f(x, cutoff) may return, instead of f(x), any lower bound of it above cutoff: each
    //! new point is compared with the one the section keeps (its cutoff), and a point above
    //! that one is dropped whatever its value, so the search goes as with every f(x) exact.
    template <class F>
    static std::pair<double, double> golden(const F& f, int steps, double floor) {
        constexpr double all = std::numeric_limits<double>::infinity();
        double lo = 0.0, hi = 1.0;
        double x1 = hi - GOLD, x2 = lo + GOLD;
        double f1 = f(x1, all);
        if (f1 <= floor) return {x1, f1};
        double f2 = f(x2, f1);
        double xb = f1 <= f2 ? x1 : x2, fb = std::min(f1, f2);
        for (int s = 2; s < steps && fb > floor; ++s) {
            if (f1 <= f2) {
                hi = x2, x2 = x1, f2 = f1;
                x1 = hi - GOLD * (hi - lo);
                f1 = f(x1, f2);
                if (f1 < fb) fb = f1, xb = x1;
            } else {
                lo = x1, x1 = x2, f1 = f2;
                x2 = lo + GOLD * (hi - lo);
                f2 = f(x2, f1);
                if (f2 < fb) fb = f2, xb = x2;
            }
        }
        return {xb, fb};
    }

    //! Waypoint i's velocity: the best candidate(x, v), x in [0, 1], if it shortens the move.
    //! joint >= 0: the candidates differ from the chosen velocity in that joint only, which
    //! is searched only where it binds a segment next to the waypoint (elsewhere no velocity
    //! of it shortens them).
    template <class Candidate>
    void improve(int i, int steps, int joint, const Candidate& candidate) {
        const int n = P_.n;
        double* vel = out_.velocity;
        double tw[2] = {out_.time[i - 1], out_.time[i]};
        bool bind[2] = {false, false};
        double floor = -std::numeric_limits<double>::infinity();
        if (joint >= 0) {
            for (int s = 0; s < 2; ++s) {
                const int seg = i - 1 + s;
                bind[s] = binding_[seg * n + joint] != 0;
                if (bind[s]) {
                    const double* p0 = P_.w + seg * n;
                    tw[s] = synchronised(n, p0, vel + seg * n, p0 + n, vel + (seg + 1) * n, P_.limits,
                                         shortest_.data() + seg * n, joint);
                }
            }
            if (!bind[0] && !bind[1]) return;
            // no velocity of the joint makes a segment shorter than the other joints allow
            // (a joint added to a segment only lengthens it): tw[0] + tw[1] bounds the search
            // from below, and where it is no shorter than today's, there is nothing to gain
            floor = tw[0] + tw[1];
            if (floor >= out_.time[i - 1] + out_.time[i]) return;
        }
        // the two segments' duration, with qlim or without (a lower bound: no profile built),
        // or a lower bound of it above cutoff (golden())
        const auto around = [&](double x, bool qlim, double cutoff) {
            candidate(x, trial_.data());
            if (joint < 0) return pair(i, trial_.data(), qlim, cutoff);
            const Limits& lim = P_.limits[joint];
            const double* p0 = P_.w + (i - 1) * n;
            const double v = trial_[joint];
            const double t0 = shortest(p0[n + joint] - p0[joint], vel[(i - 1) * n + joint], v, lim);
            const double t1 = shortest(p0[2 * n + joint] - p0[n + joint], v, vel[(i + 1) * n + joint], lim);
            // each segment lasts at least its joint's shortest and the other joints' duration
            const double low = std::max(t0, tw[0]) + std::max(t1, tw[1]);
            if (low > cutoff) return low;
            return time_joint(i - 1, vel + (i - 1) * n, trial_.data(), joint, t0, tw[0], bind[0], qlim) +
                   time_joint(i, trial_.data(), vel + (i + 1) * n, joint, t1, tw[1], bind[1], qlim);
        };
        // the λ search without qlim keeps its best point's timing (pair()'s), not timed again
        double seen = std::numeric_limits<double>::infinity(), x_seen = -1.0;
        const auto f = [&](double x, double cutoff) {
            const double d = around(x, P_.qlim == nullptr, cutoff);
            if (joint < 0 && P_.qlim == nullptr && d < seen) {
                seen = d, x_seen = x;
                std::copy(pair_t_.begin(), pair_t_.end(), seen_t_.begin());
                std::copy(pair_b_.begin(), pair_b_.end(), seen_b_.begin());
                seen_T_[0] = pair_T_[0], seen_T_[1] = pair_T_[1];
            }
            return d;
        };
        // with qlim, the search without it, whose best point is then checked: where it keeps
        // qlim, that is the result; else the search again with qlim (every point checked)
        constexpr double all = std::numeric_limits<double>::infinity();
        auto [xb, fb] = golden(f, steps, floor);
        if (P_.qlim != nullptr && around(xb, true, all) != fb) {
            std::tie(xb, fb) = golden([&](double x, double cutoff) { return around(x, true, cutoff); }, steps, floor);
        }
        if (fb < out_.time[i - 1] + out_.time[i]) {
            candidate(xb, trial_.data());
            if (joint < 0 && P_.qlim == nullptr && x_seen == xb) {
                for (int s = 0; s < 2; ++s) {
                    out_.time[i - 1 + s] = seen_T_[s];
                    std::copy(seen_t_.begin() + s * n, seen_t_.begin() + (s + 1) * n, shortest_.begin() + (i - 1 + s) * n);
                    std::copy(seen_b_.begin() + s * n, seen_b_.begin() + (s + 1) * n, binding_.begin() + (i - 1 + s) * n);
                }
            } else {
                // timed before the velocities are changed: the joints whose velocity is the
                // same keep their shortest durations (each segment's own, kept by keep())
                out_.time[i - 1] = time(i - 1, vel + (i - 1) * n, trial_.data());
                keep(i - 1);
                out_.time[i] = time(i, trial_.data(), vel + (i + 1) * n);
                keep(i);
            }
            std::copy(trial_.begin(), trial_.end(), vel + i * n);
            changed_[i - 1] = changed_[i] = ++accepted_;
        }
    }

    //! vhat (module comment, 1).
    void directions() {
        const int k = P_.k, n = P_.n;
        std::fill(vhat_.begin(), vhat_.end(), 0.0);
        for (int i = 1; i < k - 1; ++i) {
            double scale = std::numeric_limits<double>::infinity();
            for (int j = 0; j < n; ++j) {
                const double before = P_.w[i * n + j] - P_.w[(i - 1) * n + j];
                const double after = P_.w[(i + 1) * n + j] - P_.w[i * n + j];
                const bool same = before != 0.0 && (before > 0.0) == (after > 0.0) && after != 0.0;
                const double u = same ? P_.w[(i + 1) * n + j] - P_.w[(i - 1) * n + j] : 0.0;
                vhat_[i * n + j] = u;
                if (u != 0.0) scale = std::min(scale, P_.limits[j].v / std::fabs(u));
            }
            if (!std::isfinite(scale)) continue;
            for (int j = 0; j < n; ++j) {
                // the joint that sets the scale: its limit, not one ulp over
                const double v = vhat_[i * n + j] * scale, V = P_.limits[j].v;
                vhat_[i * n + j] = std::min(V, std::max(-V, v));
            }
        }
    }

    const Via& P_;
    ViaOutput& out_;
    std::vector<double> t_, shortest_, vhat_, trial_, grid_t_;
    std::vector<unsigned char> b_, binding_, grid_b_;  //!< binding joints of a segment; of the chosen ones
    std::vector<long> changed_;  //!< each segment's last change: the value of accepted_ then
    long accepted_ = 0;          //!< velocities accepted so far
    // pair()'s timing of the two segments at a waypoint, and that of the best point seen
    std::vector<double> pair_t_, seen_t_;
    std::vector<unsigned char> pair_b_, seen_b_;
    double pair_T_[2] = {}, seen_T_[2] = {};
    bool kept_ = false;                       //!< shortest_ and binding_ hold the chosen segments'
};

}  // namespace detail

//! Velocities at the waypoints and the segments' durations (file comment). out.time holds
//! out.stop's values (and the velocities are the stops') when a stop at every waypoint
//! already leaves qlim: some entry of out.stop is then inf.
inline void via(const Via& P, const ViaParams& prm, ViaOutput& out) {
    out.evaluations = 0;
    detail::ViaSearch search(P, out);
    search.run(prm);
}

}  // namespace km::jerk
