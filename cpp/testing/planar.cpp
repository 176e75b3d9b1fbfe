// The planar and elbow families' subproblems for the tests that pin their tolerances:
// kinematica._core_testing.planar. The triangle (triangle.hpp) one call at a time: the
// turn between two plane directions, the 2R triangle and the slide-then-link.
#include <nanobind/nanobind.h>

#include "common.hpp"
#include "kinematica/solvers/planar.hpp"
#include "kinematica/solvers/triangle.hpp"
#include "numpy_io.hpp"

namespace kmpy {

namespace {

F64 pairs2(const double (&out)[2][2]) {
    double* d;
    F64 a = new_f64({2, 2}, d);
    for (int i = 0; i < 2; ++i) {
        d[2 * i] = out[i][0];
        d[2 * i + 1] = out[i][1];
    }
    return a;
}

nb::tuple two_link(double ax, double ay, double bx, double by, double tx, double ty,
                   double slack) {
    double out[2][2];
    const km::triangle::Code code = km::triangle::two_link(ax, ay, bx, by, tx, ty, out, slack);
    return nb::make_tuple(static_cast<int>(code), pairs2(out));
}

nb::tuple slide_link(double ux, double uy, double bx, double by, double tx, double ty) {
    double out[2][2];
    const bool merging = km::triangle::slide_link(ux, uy, bx, by, tx, ty, out);
    return nb::make_tuple(merging, pairs2(out));
}

}  // namespace

void bind_planar_testing(nb::module_& m) {
    nb::module_ sub = m.def_submodule("planar", "The triangle subproblems of the planar and elbow arms.");
    sub.attr("REGULAR") = static_cast<int>(km::triangle::Code::regular);
    sub.attr("NEAR") = static_cast<int>(km::triangle::Code::near);
    sub.attr("FOLD") = static_cast<int>(km::triangle::Code::fold);
    sub.attr("SINGULAR_TOL") = km::triangle::SINGULAR_TOL;
    sub.attr("MERGE_TOL") = km::triangle::MERGE_TOL;
    sub.attr("FREE_SAMPLES") = km::planar::FREE_SAMPLES;
    sub.def("turn", &km::triangle::turn, nb::arg("ax"), nb::arg("ay"), nb::arg("bx"),
            nb::arg("by"), "The rotation (rad) turning the direction of (ax, ay) onto (bx, by).");
    sub.def("two_link", &two_link, nb::arg("ax"), nb::arg("ay"), nb::arg("bx"), nb::arg("by"),
            nb::arg("tx"), nb::arg("ty"), nb::arg("slack") = 0.0,
            "The 2R triangle Rot(d1) (a + Rot(d2) b) = t: (code, (2, 2) rows psi <= 0 and "
            ">= 0, columns d1, d2 in rad); code REGULAR, NEAR or FOLD. slack (m): a nearby "
            "arm's triangle, its branches straddling the fold within it.");
    sub.def("slide_link", &slide_link, nb::arg("ux"), nb::arg("uy"), nb::arg("bx"),
            nb::arg("by"), nb::arg("tx"), nb::arg("ty"),
            "A slide then a link s u + Rot(d) b = t: (merging, (2, 2) rows link forward and "
            "backward, columns s in m, d in rad).");
}

}  // namespace kmpy
