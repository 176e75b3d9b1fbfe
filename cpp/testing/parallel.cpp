// The three-parallel family's scalar internals for the tests that pin its tolerances:
// kinematica._core_testing.parallel. The roots of a cos θ + b sin θ = c, q5 of a meeting
// wrist and the elbow triangle take the few fields they read (the rest of the arm's
// Params left at its defaults); Newton on equations (1) and (2) and the values of a built
// arm take a chain (the core's builder fills its Params).
#include <nanobind/nanobind.h>

#include <cmath>

#include "casters.hpp"
#include "common.hpp"
#include "kinematica/solvers/parallel.hpp"
#include "kinematica/solvers/parallel_build.hpp"
#include "numpy_io.hpp"
#include "small_fields.hpp"

namespace kmpy {

namespace {

using km::ParallelParams;

void require_finite(double v, const char* name) {
    if (!std::isfinite(v)) fail_value(name, "finite");
}

//! (found, θ rising, θ falling, near) of a cos θ + b sin θ = c (parallel_pairs.hpp).
nb::tuple roots_of(double a, double b, double c, double size) {
    require_finite(a, "a");
    require_finite(b, "b");
    require_finite(c, "c");
    if (!(size > 0.0) || !std::isfinite(size)) fail_value("size", "positive and finite");
    double out[2] = {km::NaN, km::NaN};
    km::SolverInfo info;
    const bool found = km::parallel::roots(a, b, c, size, out, info);
    return nb::make_tuple(found, out[0], out[1], info.near);
}

//! (code, q5 no-flip, q5 flip) of a meeting wrist with k·R5 h6 = D1 cos q5 + E1 sin q5 +
//! F1 (wlo, whi its exact bounds), k·R5 h6 = d, m2 = |k1 × R_G h6|²; code -1 (none: q5
//! NaN), 0 (near), 1 (two roots).
nb::tuple wrist_of(double D1, double E1, double F1, double wlo, double whi, double d,
                   double m2) {
    for (const double v : {D1, E1, F1, wlo, whi, d, m2}) require_finite(v, "every argument");
    ParallelParams P;
    P.D1 = D1, P.E1 = E1, P.F1 = F1, P.wlo = wlo, P.whi = whi;
    km::parallel::Pair pair[2];
    const km::parallel::WristRoots code = km::parallel::wrist(P, d, m2, pair);
    return nb::make_tuple(static_cast<int>(code), pair[0].q5, pair[1].q5);
}

//! (flags, q2 up, ψ up, q2 down, ψ down) putting axis 4 at plane point (u, v) from axis 2,
//! the links (len_a, arg_a), (len_b, arg_b), the elbow-up side zup (2,), q2rep, slack.
nb::tuple triangle_of(double len_a, double len_b, double arg_a, double arg_b, F64 zup,
                      double q2rep, double slack, double u, double v) {
    for (const double x : {len_a, len_b, arg_a, arg_b, q2rep, slack, u, v}) {
        require_finite(x, "every argument");
    }
    ParallelParams P;
    P.len_a = len_a, P.len_b = len_b, P.arg_a = arg_a, P.arg_b = arg_b;
    small::set_vec(P.zup, zup, "zup");
    P.q2rep = q2rep, P.slack = slack;
    const km::parallel::Elbows e = km::parallel::triangle(P, {u, v});
    return nb::make_tuple(e.flags, e.q2_up, e.psi_up, e.q2_down, e.psi_down);
}

km::parallel::Sides sides_of(nb::handle h, const char* name) {
    double v[3];
    small::set_vec(v, h, name);
    for (const double x : v) require_finite(x, name);
    return {v[0], v[1], v[2]};
}

//! The core's closed form of a chain of the family (a ValueError where it declines).
ParallelParams built(const km::Chain& chain) {
    const std::optional<ParallelParams> P = km::parallel::build(chain);
    if (!P) throw nb::value_error("the three-parallel family declines this chain");
    return *P;
}

//! (q1, q5, res, evaluations, c1, s1, c5, s5) of Newton on (1) and (2) from (q1, q5).
nb::tuple newton_of(const km::Chain& chain, const km::Vec3& x6, F64 L1h, F64 L2h, double q1,
                    double q5) {
    require_finite(x6.x, "x6");
    require_finite(x6.y, "x6");
    require_finite(x6.z, "x6");
    require_finite(q1, "q1");
    require_finite(q5, "q5");
    const km::parallel::Sides L1 = sides_of(L1h, "L1");
    const km::parallel::Sides L2 = sides_of(L2h, "L2");
    const km::parallel::NewtonEnd e = km::parallel::newton(built(chain), x6, L1, L2, q1, q5);
    return nb::make_tuple(e.q1, e.q5, e.res, e.evaluations, e.c1, e.s1, e.c5, e.s5);
}

//! The values of a chain's built Params the tests read (parallel_params.hpp names them):
//! a dict, None where the family declines the chain.
nb::object values_of(const km::Chain& chain) {
    const std::optional<ParallelParams> found = km::parallel::build(chain);
    if (!found) return nb::none();
    const ParallelParams& P = *found;
    nb::dict d;
    const std::pair<const char*, km::Vec3> vectors[] = {
        {"k", P.k},       {"h1", P.h1},         {"p1", P.p1},   {"kpar", P.kpar},
        {"kperp", P.kperp}, {"hk", P.hk},       {"h5", P.h5},   {"p5", P.p5},
        {"h6", P.h6},     {"p6", P.p6},         {"p2", P.p2},   {"p4", P.p4},
        {"p1s", P.p1s},   {"a6", P.a6}};
    for (const auto& [name, v] : vectors) d[name] = v;
    const std::pair<const char*, double> scalars[] = {
        {"D1", P.D1},     {"E1", P.E1},     {"F1", P.F1},       {"D2", P.D2},
        {"E2", P.E2},     {"F2", P.F2},     {"wlo", P.wlo},     {"whi", P.whi},
        {"len_a", P.len_a}, {"len_b", P.len_b}, {"bound", P.bound}, {"scale", P.scale},
        {"slack", P.slack}, {"q1rep", P.q1rep}, {"q2rep", P.q2rep}};
    for (const auto& [name, v] : scalars) d[name] = v;
    d["home"] = P.home;
    d["mode"] = static_cast<int>(P.mode);
    return d;
}

}  // namespace

void bind_parallel_testing(nb::module_& m) {
    nb::module_ sub = m.def_submodule("parallel", "The three-parallel family's internals.");
    sub.attr("CONTINUUM_TOL") = km::parallel::CONTINUUM_TOL;
    sub.attr("NEAR_TOL") = km::parallel::NEAR_TOL;
    sub.attr("DOUBLE_ROOT_TOL") = km::parallel::DOUBLE_ROOT_TOL;
    sub.attr("NEWTON_STEPS") = km::parallel::NEWTON_STEPS;
    sub.attr("NEWTON_QUIET") = km::parallel::NEWTON_QUIET;
    sub.attr("FREE_Q1_SAMPLES") = km::parallel::FREE_Q1_SAMPLES;
    sub.def("roots", &roots_of, nb::arg("a"), nb::arg("b"), nb::arg("c"), nb::arg("size"),
            "(found, θ rising, θ falling, near) of a cos θ + b sin θ = c: a double root "
            "within DOUBLE_ROOT_TOL is one angle twice; a miss within NEAR_TOL · size the "
            "least-squares angle twice, near.");
    sub.def("wrist", &wrist_of, nb::arg("D1"), nb::arg("E1"), nb::arg("F1"), nb::arg("wlo"),
            nb::arg("whi"), nb::arg("d"), nb::arg("m2"),
            "(code, q5 no-flip, q5 flip) with k·R5 h6 = d, m2 = |k1 × R_G h6|² (axes 5 and 6 "
            "meeting): code -1 none, 0 near, 1 two roots.");
    sub.def("triangle", &triangle_of, nb::arg("len_a"), nb::arg("len_b"), nb::arg("arg_a"),
            nb::arg("arg_b"), nb::arg("zup"), nb::arg("q2rep"), nb::arg("slack"), nb::arg("u"),
            nb::arg("v"),
            "(flags, q2 up, ψ up, q2 down, ψ down) putting axis 4 at plane point (u, v) from "
            "axis 2: flags -1 none, else bit 1 folded (q2 free), bit 2 near.");
    sub.def("newton", &newton_of, nb::arg("chain"), nb::arg("x6"), nb::arg("L1"),
            nb::arg("L2"), nb::arg("q1"), nb::arg("q5"),
            "(q1, q5, res, evaluations, c1, s1, c5, s5) of Newton on equations (1) and (2) "
            "of the chain's built arm from (q1, q5); L1, L2 = (k⊥·y, (h1 × k)·y, k∥·y) of "
            "y = x6 = R_G h6 and y = w6 = G(p6) - p1.");
    sub.def("values", &values_of, nb::arg("chain"),
            "The built Params' values the tests read (a dict), or None where declined.");
}

}  // namespace kmpy
