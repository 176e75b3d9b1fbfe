// The three-parallel family (UR type): kinematica._core.parallel.
//
// ParallelParams with a read-write attribute per field, the family's tolerances, and the
// scalar internals the tolerance tests pin (roots of a cos θ + b sin θ = c, q5 of a
// meeting wrist, the elbow triangle, Newton on equations (1) and (2)).
#include <nanobind/nanobind.h>

#include <cmath>
#include <string>

#include "casters.hpp"
#include "common.hpp"
#include "kinematica/solvers/parallel.hpp"
#include "numpy_io.hpp"
#include "small_fields.hpp"
#include "solver_binding.hpp"

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

//! (code, q5 no-flip, q5 flip) of a meeting wrist, k·R5 h6 = d, m2 = |k1 × R_G h6|²;
//! code -1 (none: q5 NaN), 0 (near), 1 (two roots).
nb::tuple wrist_of(const ParallelParams& P, double d, double m2) {
    require_finite(d, "d");
    require_finite(m2, "m2");
    km::parallel::Pair pair[2];
    const km::parallel::WristRoots code = km::parallel::wrist(P, d, m2, pair);
    return nb::make_tuple(static_cast<int>(code), pair[0].q5, pair[1].q5);
}

//! (flags, q2 up, ψ up, q2 down, ψ down) putting axis 4 at plane point (u, v).
nb::tuple triangle_of(const ParallelParams& P, double u, double v) {
    require_finite(u, "u");
    require_finite(v, "v");
    const km::parallel::Elbows e = km::parallel::triangle(P, {u, v});
    return nb::make_tuple(e.flags, e.q2_up, e.psi_up, e.q2_down, e.psi_down);
}

km::parallel::Sides sides_of(nb::handle h, const char* name) {
    double v[3];
    small::set_vec(v, h, name);
    for (const double x : v) require_finite(x, name);
    return {v[0], v[1], v[2]};
}

//! (q1, q5, res, evaluations, c1, s1, c5, s5) of Newton on (1) and (2) from (q1, q5).
nb::tuple newton_of(const ParallelParams& P, const km::Vec3& x6, F64 L1h, F64 L2h,
                    double q1, double q5) {
    require_finite(x6.x, "x6");
    require_finite(x6.y, "x6");
    require_finite(x6.z, "x6");
    require_finite(q1, "q1");
    require_finite(q5, "q5");
    const km::parallel::Sides L1 = sides_of(L1h, "L1");
    const km::parallel::Sides L2 = sides_of(L2h, "L2");
    const km::parallel::NewtonEnd e = km::parallel::newton(P, x6, L1, L2, q1, q5);
    return nb::make_tuple(e.q1, e.q5, e.res, e.evaluations, e.c1, e.s1, e.c5, e.s5);
}

}  // namespace

void bind_parallel(nb::module_& m) {
    nb::module_ sub = m.def_submodule(
        "parallel", "Three-parallel 6R arms (UR type): axes 5-6 meeting, parallel or apart.");

    nb::enum_<km::ParallelMode>(sub, "Mode", nb::is_arithmetic(), "How axes 5 and 6 lie.")
        .value("meet", km::ParallelMode::meet, "axes 5 and 6 meet")
        .value("parallel", km::ParallelMode::parallel, "axes 5 and 6 parallel")
        .value("general", km::ParallelMode::general, "apart (a5 != 0): the quartic");

    auto cls = bind_closed_form<ParallelParams>(
        sub, "ParallelParams",
        "A UR-type arm (axes 2, 3, 4 parallel) for its closed form: vectors in the base "
        "frame at q = 0 (m), scalars as solvers/parallel_params.hpp documents them.",
        "km::ParallelParams", "kinematica/solvers/parallel.hpp");
    cls.def_rw("k", &ParallelParams::k, "direction of axes 2, 3, 4")
        .def_rw("h1", &ParallelParams::h1, "axis 1 direction")
        .def_rw("p1", &ParallelParams::p1, "a point on axis 1")
        .def_rw("kpar", &ParallelParams::kpar, "(h1·k) h1")
        .def_rw("kperp", &ParallelParams::kperp, "k - kpar")
        .def_rw("hk", &ParallelParams::hk, "h1 × k")
        .def_rw("h5", &ParallelParams::h5, "axis 5 direction")
        .def_rw("p5", &ParallelParams::p5, "on axis 5: foot of the common normal with axis 6")
        .def_rw("h6", &ParallelParams::h6, "axis 6 direction")
        .def_rw("p6", &ParallelParams::p6, "on axis 6: foot of the common normal with axis 5")
        .def_rw("h6par", &ParallelParams::h6par, "(h5·h6) h5")
        .def_rw("h6perp", &ParallelParams::h6perp, "h6 - h6par")
        .def_rw("h5xh6", &ParallelParams::h5xh6, "h5 × h6")
        .def_rw("p2", &ParallelParams::p2, "a point on axis 2")
        .def_rw("p4", &ParallelParams::p4, "a point on axis 4")
        .def_rw("e1", &ParallelParams::e1, "unit vector across k")
        .def_rw("e2", &ParallelParams::e2, "k × e1")
        .def_rw("home", &ParallelParams::home, "(4, 4) M, the tool pose at q = 0")
        .def_rw("p1s", &ParallelParams::p1s, "on axis 1: foot of the common normal with axis 2")
        .def_rw("a6", &ParallelParams::a6, "on axis 6: the point the reach bound is about")
        .def_rw("mode", &ParallelParams::mode)
        .def_rw("D1", &ParallelParams::D1)
        .def_rw("E1", &ParallelParams::E1)
        .def_rw("F1", &ParallelParams::F1, "k·R5 h6 = D1 cos q5 + E1 sin q5 + F1")
        .def_rw("D2", &ParallelParams::D2)
        .def_rw("E2", &ParallelParams::E2)
        .def_rw("F2", &ParallelParams::F2, "equation (2)'s right side, F2 with k·(p5 - p1)")
        .def_rw("wlo", &ParallelParams::wlo, "1 - |D1, E1| - F1, exactly")
        .def_rw("whi", &ParallelParams::whi, "1 - |D1, E1| + F1, exactly")
        .def_rw("len_a", &ParallelParams::len_a, "|A| (m), A = p3 - p2 across k")
        .def_rw("len_b", &ParallelParams::len_b, "|B| (m), B = p4 - p3 across k")
        .def_rw("arg_a", &ParallelParams::arg_a, "arg A (rad)")
        .def_rw("arg_b", &ParallelParams::arg_b, "arg B (rad)")
        .def_rw("sign3", &ParallelParams::sign3, "h3·k = ±1")
        .def_rw("sign4", &ParallelParams::sign4, "h4·k = ±1")
        .def_rw("bound", &ParallelParams::bound, "reach bound about p1s (m)")
        .def_rw("lip", &ParallelParams::lip, "|h1·k| + |kperp|")
        .def_rw("scale", &ParallelParams::scale, "size of the arm (m)")
        .def_rw("slack", &ParallelParams::slack,
                "how far the real arm may put axis 4 from this one's (m; 0: exact)")
        .def_rw("q1rep", &ParallelParams::q1rep, "q1 given when q1 is free (rad)")
        .def_rw("q2rep", &ParallelParams::q2rep, "q2 given when q2 is free (rad)");
    KM_SMALL_VEC(cls, ParallelParams, minv,
                 "(4,) row-major inverse of [[D1, E1], [D2, E2]] (Mode.general)");
    KM_SMALL_VEC(cls, ParallelParams, zup, "(2,) plane coordinates of h1 × k (the elbow-up side)");

    sub.attr("SLOTS") = ParallelParams{}.slots();
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
    sub.def("wrist", &wrist_of, nb::arg("params"), nb::arg("d"), nb::arg("m2"),
            "(code, q5 no-flip, q5 flip) with k·R5 h6 = d, m2 = |k1 × R_G h6|² (axes 5 and 6 "
            "meeting): code -1 none, 0 near, 1 two roots.");
    sub.def("triangle", &triangle_of, nb::arg("params"), nb::arg("u"), nb::arg("v"),
            "(flags, q2 up, ψ up, q2 down, ψ down) putting axis 4 at plane point (u, v) from "
            "axis 2: flags -1 none, else bit 1 folded (q2 free), bit 2 near.");
    sub.def("newton", &newton_of, nb::arg("params"), nb::arg("x6"), nb::arg("L1"),
            nb::arg("L2"), nb::arg("q1"), nb::arg("q5"),
            "(q1, q5, res, evaluations, c1, s1, c5, s5) of Newton on equations (1) and (2) "
            "from (q1, q5); L1, L2 = (k⊥·y, (h1 × k)·y, k∥·y) of y = x6 = R_G h6 and "
            "y = w6 = G(p6) - p1.");
}

}  // namespace kmpy
