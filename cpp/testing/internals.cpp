// The core's scalar internals, bound one value at a time for the tests that pin them
// (against the C library, their definitions, and each named tolerance from both sides).
// Submodule kinematica._core_testing.internals (the test-only module): not the library's API.
#include <nanobind/stl/array.h>
#include <nanobind/stl/complex.h>

#include <array>
#include <complex>
#include <vector>

#include "casters.hpp"
#include "common.hpp"
#include "interrupt.hpp"
#include "kinematica/chain.hpp"
#include "kinematica/check.hpp"
#include "kinematica/geometry.hpp"
#include "kinematica/linalg.hpp"
#include "kinematica/lm.hpp"
#include "kinematica/numeric.hpp"
#include "kinematica/point_rank.hpp"
#include "kinematica/polynomial.hpp"
#include "kinematica/reach_bounds.hpp"
#include "kinematica/so3.hpp"
#include "kinematica/trig.hpp"

namespace kmpy {

namespace {

//! The fields of a 6R arm's reach bounds (reach_bounds.hpp's Bounds): vectors and ranges
//! as tuples, circles as (c, u, v).
nb::dict reach_fields(const km::reach::Bounds& b) {
    const auto vec = [](const km::Vec3& v) { return nb::make_tuple(v.x, v.y, v.z); };
    const auto pair = [](const double* r) { return nb::make_tuple(r[0], r[1]); };
    const auto circle = [&](const km::reach::Circle& c) { return nb::make_tuple(vec(c.c), vec(c.u), vec(c.v)); };
    nb::dict d;
    d["a6"] = vec(b.a6), d["x"] = circle(b.x), d["shoulder"] = vec(b.shoulder), d["a1"] = vec(b.a1);
    d["reach"] = pair(b.reach), d["height"] = pair(b.height), d["x_radius"] = b.x_radius;
    d["arc6"] = pair(b.arc6), d["y"] = circle(b.y), d["arc1"] = pair(b.arc1), d["z"] = vec(b.z);
    d["reach2"] = pair(b.reach2), d["height2"] = pair(b.height2);
    return d;
}

nb::tuple sincos_of(double x) {
    double s, c;
    km::sincos(x, s, c);
    return nb::make_tuple(s, c);
}

nb::tuple sincos_reduced_of(double x) {
    double s, c;
    km::sincos_reduced(x, s, c);
    return nb::make_tuple(s, c);
}

nb::tuple sincos_many(F64 x) {
    const In in = in_f64(x, "x", 1);
    double *s, *c;
    nb::object S = new_f64({in.dim[0]}, s), C = new_f64({in.dim[0]}, c);
    km::sincos_block(in.data, s, c, static_cast<int>(in.dim[0]));
    return nb::make_tuple(S, C);
}

nb::tuple trig_linear_of(double a, double b, double c) {
    double out[2];
    const km::TrigRoots r = km::trig_linear(a, b, c, out);
    return nb::make_tuple(static_cast<int>(r), out[0], out[1]);
}

std::array<std::complex<double>, 4> quartic_of(const std::array<double, 5>& k) {
    std::array<std::complex<double>, 4> roots;
    km::quartic_roots(k.data(), roots.data());
    return roots;
}

//! The numeric search's model at q: counted errors e (r,) and rows J (r, n).
nb::tuple lm_rows(const km::Chain& chain, const std::array<double, 6>& w, F64 qh,
                  const km::Pose& T) {
    const int n = chain.dof();
    const In q = in_f64(qh, "q", 1, {n});
    const km::ChainView ch = chain.view();
    const km::lm::Rows rows(w.data());
    km::LMWork work(n);
    double err[6];
    km::lm::pose_errors(ch, q.data, T, rows, work, err);
    km::lm::jacobian_rows(ch, rows, work);
    double *e, *J;
    nb::object E = new_f64({rows.count}, e), Ja = new_f64({rows.count, n}, J);
    for (int r = 0; r < rows.count; ++r) {
        e[r] = err[r];
        for (int j = 0; j < n; ++j) J[r * n + j] = work.J[static_cast<size_t>(r * n + j)];
    }
    return nb::make_tuple(E, Ja);
}

//! The numeric search of each target T (N, 4, 4) from the default first guess, as
//! lm_solve counts it: (evaluations (N,), attempts (N,), converged (N,)).
nb::tuple lm_stats(const km::NumericSolver& s, const km::Chain& chain, F64 Th) {
    const In T = in_f64(Th, "T", 3, {-1, 4, 4});
    if (s.dof() != chain.dof()) throw nb::value_error("the solver and the chain differ in joints");
    const npy_intp N = T.dim[0];
    npy_int64 *evaluations, *attempts;
    npy_bool* converged;
    nb::object Ea = new_i64({N}, evaluations), Aa = new_i64({N}, attempts);
    nb::object Ca = new_array({N}, converged, NPY_BOOL);
    const km::ChainView ch = chain.view();
    run_rows(N, TARGET_BLOCK, 1, [&](long i0, long i1) {
        km::LMWork work(s.n);
        std::vector<double> q(static_cast<size_t>(s.n));
        for (long i = i0; i < i1; ++i) {
            const km::LMStats st =
                km::lm_solve(ch, s.bounds.data(), s.weights, s.settings, km::Pose::from_rows(T.data + 16 * i),
                             s.middle.data(), s.samples.data(), s.restarts(), q.data(), work);
            evaluations[i] = st.evaluations;
            attempts[i] = st.attempts;
            converged[i] = st.converged;
        }
    });
    return nb::make_tuple(Ea, Aa, Ca);
}

F64 dls(F64 Jh, F64 eh, double lam) {
    const In J = in_f64(Jh, "J", 2);
    const npy_intp r = J.dim[0], n = J.dim[1];
    if (r < 1 || r > 6 || n < 1) throw nb::value_error("J must have 1 to 6 rows and a column");
    const In e = in_f64(eh, "e", 1, {r});
    double* dq;
    F64 out = new_f64({n}, dq);
    km::damped_least_squares(J.data, static_cast<int>(r), static_cast<int>(n), e.data, lam, dq);
    return out;
}

bool backward_ok(const std::array<double, 5>& k, const std::array<std::complex<double>, 4>& r) {
    km::detail::Cx roots[4];
    for (int i = 0; i < 4; ++i) roots[i] = {r[static_cast<size_t>(i)].real(), r[static_cast<size_t>(i)].imag()};
    return km::detail::backward_ok(k.data(), roots);
}

//! The shared check of hand-made candidates Q (m, n) of one target.
nb::tuple check_given(const km::Chain& chain, F64 Th, F64 Qh, const km::CheckOptions& opts,
                      double gap, bool singular, bool near, nb::handle q0h) {
    const int n = chain.dof();
    const In Ti = in_f64(Th, "T", 2, {4, 4});
    const In Q = in_f64(Qh, "Q", 2, {-1, n});
    const int m = static_cast<int>(Q.dim[0]);
    if (m < 1) throw nb::value_error("Q must hold a candidate");
    const In q0in = q0h.is_none() ? In{} : in_f64(q0h, "q0", 1, {n});
    const double* q0 = q0in.data;
    km::SolverInfo info;
    info.gap = gap;
    info.singular = singular;
    info.near = near;
    km::CheckWork work(m, n);
    double *q, *res;
    F64 Qa = new_f64({m, n}, q), Ra = new_f64({m, 2}, res);
    std::vector<int> slot(static_cast<size_t>(m));
    const km::CheckReport r = km::check(chain.view(), km::Pose::from_rows(Ti.data), Q.data, m, info,
                                        opts, q0, work, km::CheckOut{q, slot.data(), res});
    nb::list slots;
    for (int i = 0; i < r.count + r.out_count; ++i) slots.append(slot[static_cast<size_t>(i)]);
    return nb::make_tuple(Qa, Ra, slots, static_cast<int>(r.status), r.count, r.out_count, r.gap);
}

//! The check's repair of one candidate q (n,) of target T: (q, position error, rotation
//! error) of the best point its Gauss-Newton steps reached.
nb::tuple repair_of(const km::Chain& chain, F64 Th, F64 qh, const km::CheckOptions& opts) {
    const int n = chain.dof();
    const In Ti = in_f64(Th, "T", 2, {4, 4});
    const In q = in_f64(qh, "q", 1, {n});
    const km::ChainView ch = chain.view();
    const km::Pose T = km::Pose::from_rows(Ti.data);
    km::CheckWork work(1, n);
    double* out;
    F64 Qa = new_f64({n}, out);
    for (int j = 0; j < n; ++j) out[j] = q.data[j];
    std::vector<double> c(static_cast<size_t>(n)), s(static_cast<size_t>(n));
    km::joint_trig(ch, out, c.data(), s.data());
    double p_err = km::INF, r_err = km::INF;
    km::detail::residual(ch, out, c.data(), s.data(), 1, T, opts.weights, p_err, r_err);
    km::detail::repair(ch, out, T, opts, work, p_err, r_err);
    return nb::make_tuple(Qa, p_err, r_err);
}

//! One Gauss-Newton step of the check's repair from q (n,) towards T: the new q.
F64 repair_step_of(const km::Chain& chain, F64 Th, F64 qh, const km::CheckOptions& opts) {
    const int n = chain.dof();
    const In Ti = in_f64(Th, "T", 2, {4, 4});
    const In q = in_f64(qh, "q", 1, {n});
    km::CheckWork work(1, n);
    double* out;
    F64 Qa = new_f64({n}, out);
    for (int j = 0; j < n; ++j) out[j] = q.data[j];
    km::detail::gauss_newton_step(chain.view(), out, km::Pose::from_rows(Ti.data), opts.weights,
                                  work, true);
    return Qa;
}

//! (B,): σmin / σmax of the Jacobian d(point)/d(q1, q2, q3) at each row of Q (B, n), the
//! point fixed in the tool frame at c_tool (point_rank.hpp, which places_point tests).
F64 point_rank_ratios(const km::Chain& chain, F64 Qh, const km::Vec3& c_tool, int workers) {
    const int n = chain.dof();
    if (n < 3) throw nb::value_error("the point's Jacobian needs joints 1-3: a chain of 3 joints or more");
    const In Q = in_f64(Qh, "Q", 2, {-1, n});
    const km::ChainView ch = chain.view();
    double* out;
    F64 R = new_f64({Q.dim[0]}, out);
    run_rows(Q.dim[0], 256, workers, [&](long b0, long b1) {
        std::vector<double> c(static_cast<size_t>(n)), s(c.size()), J(6 * c.size());
        for (long b = b0; b < b1; ++b) {
            out[b] = km::point_rank_ratio(ch, Q.data + b * n, c_tool, c.data(), s.data(), J.data());
        }
    });
    return R;
}

}  // namespace

void bind_testing(nb::module_& m) {
    nb::module_ t = m.def_submodule("internals", "The core's scalar internals, for tests.");
    t.def("reach_fields", &reach_fields, nb::arg("bounds"), "A ReachBounds' fields (reach_bounds.hpp).");
    t.def("sincos", &sincos_of, nb::arg("x"), "(sin x, cos x) as the core computes them.");
    t.def("point_rank_ratios", &point_rank_ratios, nb::arg("chain"), nb::arg("Q"),
          nb::arg("c_tool"), nb::arg("workers") = 1,
          "(B,): sigma_min / sigma_max of d(point)/d(q1, q2, q3) at each row of Q (B, n), the "
          "point fixed in the tool frame at c_tool (3,).");
    t.def("sincos_reduced", &sincos_reduced_of, nb::arg("x"), "The branch-free reduction alone.");
    t.def("sincos_block", &sincos_many, nb::arg("x"), "sincos of every angle of x (N,): (s, c).");
    t.def("wrap", [](double v) { return km::wrap(v); }, nb::arg("v"));
    t.def("floor_mod", [](double a, double b) { return km::floor_mod(a, b); }, nb::arg("a"), nb::arg("b"));
    t.def("angle_between", [](const km::Pose& T, const km::Pose& Tt) { return km::angle_between(T, Tt); },
          nb::arg("T"), nb::arg("Tt"), "The angle of Rtᵀ R.");
    t.def("rotate_about", [](const km::Vec3& k, double c, double s, const km::Vec3& v) {
              return km::rotate_about(k, c, s, v);
          }, nb::arg("k"), nb::arg("c"), nb::arg("s"), nb::arg("v"));
    t.def("subproblem1", [](const km::Vec3& p1, const km::Vec3& p2, const km::Vec3& k) {
              return km::subproblem1(p1, p2, k);
          }, nb::arg("p1"), nb::arg("p2"), nb::arg("k"));
    t.def("trig_linear", &trig_linear_of, nb::arg("a"), nb::arg("b"), nb::arg("c"),
          "(code, θ1, θ2) of a cos θ + b sin θ = c: code 1 two roots, 0 none, -1 a = b = 0.");
    t.def("quartic_roots", &quartic_of, nb::arg("k"), "The four roots of k[0] x⁴ + ... + k[4].");
    t.def("largest_cubic_root", &km::largest_cubic_root, nb::arg("A"), nb::arg("B"), nb::arg("C"));
    t.def("quartic_backward_ok", &backward_ok, nb::arg("k"), nb::arg("roots"),
          "True when every root's backward error is within QUARTIC_CHECK.");
    t.def("check", &check_given, nb::arg("chain"), nb::arg("T"), nb::arg("Q"), nb::arg("options"),
          nb::arg("gap"), nb::arg("singular"), nb::arg("near"), nb::arg("q0").none(),
          "The shared check of candidates Q (m, n): (q, res, slots, status, count, out_count, gap).");
    t.def("repair", &repair_of, nb::arg("chain"), nb::arg("T"), nb::arg("q"), nb::arg("options"),
          "The check's repair of one candidate q (n,): (q, position error, rotation error).");
    t.def("repair_step", &repair_step_of, nb::arg("chain"), nb::arg("T"), nb::arg("q"),
          nb::arg("options"), "One Gauss-Newton step of the repair from q (n,): the new q.");
    t.attr("REPAIR_DAMPING") = km::REPAIR_DAMPING;
    t.attr("REPAIR_DAMPING_FLOOR") = km::REPAIR_DAMPING_FLOOR;
    t.attr("REPAIR_PATIENCE") = km::REPAIR_PATIENCE;
    t.attr("REPAIR_STEPS") = km::REPAIR_STEPS;
    t.attr("REPAIR_QUIET") = km::REPAIR_QUIET;
    t.attr("POLISH_LIMIT") = km::POLISH_LIMIT;
    t.attr("DEDUP_TOL") = km::DEDUP_TOL;
    t.attr("LIMIT_TOL") = km::LIMIT_TOL;
    t.attr("MERGE_SPAN") = km::MERGE_SPAN;
    t.attr("LAMBDA_MIN") = km::LAMBDA_MIN;
    t.attr("STALL_WINDOW") = km::STALL_WINDOW;
    t.attr("SCALE_FLOOR") = km::SCALE_FLOOR;
    t.attr("ATAN_LINEAR") = km::ATAN_LINEAR;
    t.def("lm_rows", &lm_rows, nb::arg("chain"), nb::arg("weights"), nb::arg("q"), nb::arg("T"),
          "The search's model at q: (counted errors (r,), their weighted Jacobian rows (r, n)).");
    t.def("damped_least_squares", &dls, nb::arg("J"), nb::arg("e"), nb::arg("lam"));
    t.def("lm_stats", &lm_stats, nb::arg("solver"), nb::arg("chain"), nb::arg("T"),
          "The search of each target T (N, 4, 4) from the default first guess: (evaluations,\n"
          "attempts, converged), each (N,).");
    t.attr("REDUCTION_LIMIT") = km::REDUCTION_LIMIT;
    t.attr("TRIG_TOL") = km::TRIG_TOL;
    t.attr("QUARTIC_CHECK") = km::QUARTIC_CHECK;
    t.attr("ABERTH_STEPS") = km::ABERTH_STEPS;
    t.attr("SNAP_TOL") = km::SNAP_TOL;
}

}  // namespace kmpy
