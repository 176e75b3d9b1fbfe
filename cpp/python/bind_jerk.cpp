// Jerk-limited segments at zero acceleration and moves through waypoints (jerk.hpp,
// jerk_via.hpp) for kinematica.motion.scurve_via: every array checked here before the core
// sees it.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common.hpp"
#include "kinematica/jerk.hpp"
#include "kinematica/jerk_pieces.hpp"
#include "kinematica/jerk_via.hpp"
#include "numpy_io.hpp"

namespace kmpy {

namespace {

namespace kj = km::jerk;

//! The limits vmax, amax, jmax (n,) of n joints, each finite and positive.
std::vector<kj::Limits> limits_of(F64 vmax, F64 amax, F64 jmax, npy_intp n) {
    const In V = in_f64(vmax, "vmax", 1, {n}), A = in_f64(amax, "amax", 1, {n}), J = in_f64(jmax, "jmax", 1, {n});
    std::vector<kj::Limits> L(static_cast<std::size_t>(n));
    for (npy_intp i = 0; i < n; ++i) {
        const double v = V.data[i], a = A.data[i], j = J.data[i];
        if (!(v > 0.0 && a > 0.0 && j > 0.0 && std::isfinite(v) && std::isfinite(a) && std::isfinite(j))) {
            fail_value("vmax, amax and jmax", "finite and positive");
        }
        L[static_cast<std::size_t>(i)] = kj::Limits{v, a, j};
    }
    return L;
}

//! Every value finite and each velocity within its joint's limit.
void check_states(const In& x, const char* name, const std::vector<kj::Limits>* L) {
    const npy_intp n = x.dim[x.ndim - 1];
    for (npy_intp k = 0; k < x.size(); ++k) {
        const double v = x.data[k];
        if (!std::isfinite(v)) fail_value(name, "finite");
        if (L != nullptr && std::fabs(v) > (*L)[static_cast<std::size_t>(k % n)].v) {
            fail_value(name, "within vmax");
        }
    }
}

nb::tuple jerk_segments(F64 p0, F64 v0, F64 p1, F64 v1, F64 vmax, F64 amax, F64 jmax) {
    const In P0 = in_f64(p0, "p0", 2);
    const npy_intp m = P0.dim[0], n = P0.dim[1];
    if (n < 1) fail_value("p0", "of at least one joint");
    const In V0 = in_f64(v0, "v0", 2, {m, n}), P1 = in_f64(p1, "p1", 2, {m, n}), V1 = in_f64(v1, "v1", 2, {m, n});
    const std::vector<kj::Limits> L = limits_of(vmax, amax, jmax, n);
    check_states(P0, "p0", nullptr);
    check_states(P1, "p1", nullptr);
    check_states(V0, "v0", &L);
    check_states(V1, "v1", &L);
    double *T, *t, *j;
    npy_int64* phases;
    nb::object To = new_f64({m}, T), to = new_f64({m, n, kj::MAX_PHASES}, t), jo = new_f64({m, n, kj::MAX_PHASES}, j);
    nb::object po = new_i64({m, n}, phases);
    {
        nb::gil_scoped_release release;
        std::vector<double> scratch(static_cast<std::size_t>(n));
        kj::Profile prof;
        for (npy_intp r = 0; r < m; ++r) {
            const npy_intp o = r * n;
            T[r] = kj::segment_time(static_cast<int>(n), P0.data + o, V0.data + o, P1.data + o, V1.data + o, L.data(),
                                    scratch.data());
            for (npy_intp i = 0; i < n; ++i) {
                kj::profile(T[r], P1.data[o + i] - P0.data[o + i], V0.data[o + i], V1.data[o + i],
                            L[static_cast<std::size_t>(i)], prof);
                phases[o + i] = prof.phases;
                for (int k = 0; k < kj::MAX_PHASES; ++k) {
                    t[(o + i) * kj::MAX_PHASES + k] = k < prof.phases ? prof.t[k] : 0.0;
                    j[(o + i) * kj::MAX_PHASES + k] = k < prof.phases ? prof.j[k] : 0.0;
                }
            }
        }
    }
    return nb::make_tuple(To, to, jo, po);
}

//! The checked problem of a move through waypoints: the arrays (held), the limits, the
//! core's structs.
struct ViaArgs {
    In W, VS, VE, Q;
    std::vector<kj::Limits> L;
    kj::Via P;
    kj::ViaParams prm;
};

void via_args(ViaArgs& A, F64 w, F64 v_start, F64 v_end, F64 vmax, F64 amax, F64 jmax, nb::object qlim,
              double qlim_atol, int sweeps, int golden_steps, int joint_sweeps) {
    A.W = in_f64(w, "w", 2);
    const npy_intp k = A.W.dim[0], n = A.W.dim[1];
    if (k < 2 || n < 1) fail_value("w", "of at least 2 waypoints of at least one joint");
    A.VS = in_f64(v_start, "v_start", 1, {n});
    A.VE = in_f64(v_end, "v_end", 1, {n});
    A.L = limits_of(vmax, amax, jmax, n);
    check_states(A.W, "w", nullptr);
    check_states(A.VS, "v_start", &A.L);
    check_states(A.VE, "v_end", &A.L);
    const double* W = A.W.data;
    for (npy_intp i = 0; i + 1 < k; ++i) {
        bool same = true;
        for (npy_intp j = 0; j < n; ++j) same = same && W[i * n + j] == W[(i + 1) * n + j];
        if (same) fail_value("w", "without two equal waypoints in a row");
    }
    if (!(qlim_atol >= 0.0 && std::isfinite(qlim_atol))) fail_value("qlim_atol", "finite and >= 0");
    if (sweeps < 0 || joint_sweeps < 0 || golden_steps < 2 || sweeps > 100 || joint_sweeps > 100 ||
        golden_steps > 100) {
        fail_value("sweeps, golden_steps, joint_sweeps", "0-100, 2-100, 0-100");
    }
    if (!qlim.is_none()) {
        A.Q = in_f64(qlim, "qlim", 2, {n, 2});
        for (npy_intp j = 0; j < n; ++j) {
            if (std::isnan(A.Q.data[2 * j]) || std::isnan(A.Q.data[2 * j + 1]) || A.Q.data[2 * j] > A.Q.data[2 * j + 1]) {
                fail_value("qlim", "low <= high, not NaN");
            }
        }
    }
    A.P = kj::Via{static_cast<int>(k), static_cast<int>(n), W, A.VS.data, A.VE.data, A.L.data(),
                  qlim.is_none() ? nullptr : A.Q.data, qlim_atol};
    A.prm = kj::ViaParams{sweeps, golden_steps, joint_sweeps};
}

//! A vector's values as a new array of the given shape.
F64 array_of(const std::vector<double>& x, std::initializer_list<npy_intp> dims) {
    double* d;
    F64 o = new_f64(dims, d);
    std::copy(x.begin(), x.end(), d);
    return o;
}

//! (pieces, samples) of the made pieces P: pieces (breaks, coef (p, order, n), knots, peak
//! (3, n)), samples every dt or closer (t, q, qd, qdd, jerk) ending on the state (q1, v1, a1;
//! a1 null: zero).
nb::tuple pieces_and_samples(const kj::Pieces& P, npy_intp n, double dt, const double* q1, const double* v1,
                             const double* a1) {
    const npy_intp pieces = static_cast<npy_intp>(P.breaks.size()) - 1;
    const nb::tuple exact = nb::make_tuple(array_of(P.breaks, {pieces + 1}),
                                           array_of(P.coef, {pieces, static_cast<npy_intp>(P.order), n}),
                                           array_of(P.knots, {static_cast<npy_intp>(P.knots.size())}),
                                           array_of(P.peak, {3, n}));
    const npy_intp m = kj::sample_count(P.knots, dt);
    double *t, *q, *qd, *qdd, *qddd;
    nb::object to = new_f64({m}, t), qo = new_f64({m, n}, q), qdo = new_f64({m, n}, qd);
    nb::object qddo = new_f64({m, n}, qdd), qdddo = new_f64({m, n}, qddd);
    {
        nb::gil_scoped_release release;
        kj::move_samples(P, dt, q1, v1, a1, t, q, qd, qdd, qddd);
    }
    return nb::make_tuple(exact, nb::make_tuple(to, qo, qdo, qddo, qdddo));
}

nb::tuple jerk_via_move(F64 w, F64 v_start, F64 v_end, F64 vmax, F64 amax, F64 jmax, nb::object qlim,
                        double qlim_atol, int sweeps, int golden_steps, int joint_sweeps, double dt,
                        double max_samples) {
    ViaArgs A;
    via_args(A, w, v_start, v_end, vmax, amax, jmax, qlim, qlim_atol, sweeps, golden_steps, joint_sweeps);
    if (!(dt > 0.0 && std::isfinite(dt))) fail_value("dt", "finite and positive");
    const npy_intp k = A.P.k, n = A.P.n;
    double *vel, *time, *stop;
    nb::object Vo = new_f64({k, n}, vel), To = new_f64({k - 1}, time), So = new_f64({k - 1}, stop);
    kj::ViaOutput out{vel, time, stop, 0};
    thread_local kj::Pieces P;  // its memory kept from call to call (jerk_pieces.hpp)
    bool made = false;
    {
        nb::gil_scoped_release release;
        kj::via(A.P, A.prm, out);
        double duration = 0.0;
        bool finite = true;
        for (npy_intp i = 0; i + 1 < k; ++i) {
            finite = finite && std::isfinite(stop[i]);
            duration += time[i];
        }
        // a segment that leaves qlim even with stops, or too many samples: the caller says so
        if (finite && duration / dt + static_cast<double>(k) <= max_samples) {
            kj::move_pieces(A.P.k, A.P.n, A.P.w, vel, time, A.L.data(), P);
            made = true;
        }
    }
    if (!made) return nb::make_tuple(Vo, To, So, out.evaluations, nb::none(), nb::none());
    const nb::tuple made_move = pieces_and_samples(P, n, dt, A.W.data + (k - 1) * n, A.VE.data, nullptr);
    return nb::make_tuple(Vo, To, So, out.evaluations, made_move[0], made_move[1]);
}

nb::tuple jerk_state_move(double T, F64 rows, F64 vmax, F64 amax, F64 jmax, F64 q1, F64 v1, F64 a1, double dt,
                          double max_samples) {
    const In R = in_f64(rows, "rows", 2);
    const npy_intp n = R.dim[0];
    if (n < 1 || R.dim[1] != kj::STATE_ROW) fail_value("rows", "(n, JERK_STATE_ROW) of at least one joint");
    const In Q1 = in_f64(q1, "q1", 1, {n}), V1 = in_f64(v1, "v1", 1, {n}), A1 = in_f64(a1, "a1", 1, {n});
    const std::vector<kj::Limits> L = limits_of(vmax, amax, jmax, n);
    check_states(R, "rows", nullptr);
    check_states(Q1, "q1", nullptr);
    check_states(V1, "v1", nullptr);
    check_states(A1, "a1", nullptr);
    for (npy_intp i = 0; i < n; ++i) {
        for (int k = 0; k < 9; ++k) {
            if (R.data[i * kj::STATE_ROW + k] < 0.0) fail_value("rows", "of phase durations >= 0");
        }
    }
    if (!(T >= 0.0 && std::isfinite(T))) fail_value("T", "finite and >= 0");
    if (!(dt > 0.0 && std::isfinite(dt))) fail_value("dt", "finite and positive");
    if (!(T / dt + 1.0 <= max_samples)) fail_value("T / dt", "at most max_samples - 1");
    thread_local kj::Pieces P;  // its memory kept from call to call (jerk_pieces.hpp)
    {
        nb::gil_scoped_release release;
        kj::state_pieces(static_cast<int>(n), T, R.data, L.data(), P);
    }
    return pieces_and_samples(P, n, dt, Q1.data, V1.data, A1.data);
}

}  // namespace

void bind_jerk(nb::module_& m) {
    m.def("jerk_segments", &jerk_segments, nb::arg("p0"), nb::arg("v0"), nb::arg("p1"), nb::arg("v1"),
          nb::arg("vmax"), nb::arg("amax"), nb::arg("jmax"),
          "Time-optimal synchronised jerk-limited segments from (p0, v0, 0) to (p1, v1, 0), each (m, n); "
          "limits (n,). Returns (T (m,), durations (m, n, P), jerks (m, n, P), phases (m, n)): each joint's "
          "phases of constant jerk, P = JERK_MAX_PHASES.");
    m.def("jerk_via_move", &jerk_via_move, nb::arg("w"), nb::arg("v_start"), nb::arg("v_end"), nb::arg("vmax"),
          nb::arg("amax"), nb::arg("jmax"), nb::arg("qlim").none(), nb::arg("qlim_atol"), nb::arg("sweeps"),
          nb::arg("golden_steps"), nb::arg("joint_sweeps"), nb::arg("dt"), nb::arg("max_samples"),
          "Velocities at the waypoints w (k, n) of a jerk-limited move through them (zero acceleration at "
          "each), chosen to shorten it, then the move's exact pieces and samples every dt or closer (every knot a "
          "sample). Returns (velocity, time, stop, evaluations, pieces, samples): pieces (breaks (p+1,), "
          "coef (p, 4, n), knots (k,), peak (3, n): largest |v|, |a|, |j|), samples (t (m,), q, qd, qdd, "
          "jerk (m, n)); both None where a segment leaves qlim with stops, or duration/dt + k > "
          "max_samples.");
    m.def("jerk_state_move", &jerk_state_move, nb::arg("T"), nb::arg("rows"), nb::arg("vmax"), nb::arg("amax"),
          nb::arg("jmax"), nb::arg("q1"), nb::arg("v1"), nb::arg("a1"), nb::arg("dt"), nb::arg("max_samples"),
          "The exact pieces and samples of a state-to-state move of duration T from each joint's phases "
          "(rows (n, JERK_STATE_ROW): ruckig's brake and profile, jerk_pieces.hpp), each joint's end settled "
          "on its target. Returns (pieces, samples): pieces (breaks (p+1,), coef (p, 4 or 6, n), knots (2,), "
          "peak (3, n)), samples (t (m,), q, qd, qdd, jerk (m, n)), every dt or closer, the last the end "
          "state (q1, v1, a1).");
    m.attr("JERK_MAX_PHASES") = kj::MAX_PHASES;
    m.attr("JERK_STATE_ROW") = kj::STATE_ROW;
    m.attr("JERK_SETTLE_ULPS") = kj::SETTLE_ULPS;
    m.attr("JERK_PIECE_RTOL") = kj::PIECE_RTOL;
}

}  // namespace kmpy
