// The planar family (planar 2R/3R/PR/PRR arms and the SCARA): kinematica._core.planar.
//
// PlanarParams with its fields and IK methods, the triangle's tolerances, and its
// subproblems (turn, two_link, slide_link) as plain functions for the tolerance tests.
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include <optional>
#include <string>

#include "common.hpp"
#include "kinematica/solvers/planar.hpp"
#include "small_fields.hpp"
#include "solver_binding.hpp"

namespace kmpy {

namespace {

using km::PlanarParams;

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

//! An int field limited to [lo, hi] (the joint indices and counts; invalid() checks how
//! they fit together before each solve).
template <int PlanarParams::*F>
void int_field(nb::class_<PlanarParams>& cls, const char* name, int lo, int hi, const char* doc) {
    cls.def_prop_rw(
        name, [](const PlanarParams& p) { return p.*F; },
        [name, lo, hi](PlanarParams& p, int v) {
            if (v < lo || v > hi) {
                throw nb::value_error((std::string(name) + " must be in [" + std::to_string(lo) +
                                       ", " + std::to_string(hi) + "]")
                                          .c_str());
            }
            p.*F = v;
        },
        doc);
}

}  // namespace

void bind_planar(nb::module_& m) {
    nb::module_ sub = m.def_submodule("planar", "Planar 2R/3R/PR/PRR arms and the SCARA.");
    auto cls = bind_closed_form<PlanarParams>(
        sub, "PlanarParams",
        "A planar arm or a SCARA as its closed form reads it (solvers/planar.hpp); "
        "plane coordinates on e1, e2 = k x e1 relative to origin.",
        "km::PlanarParams", "kinematica/solvers/planar.hpp");
    constexpr int J = PlanarParams::MAX_JOINTS;
    int_field<&PlanarParams::n>(cls, "n", 1, J, "joints of the arm (2 to 4)");
    int_field<&PlanarParams::slide>(cls, "slide", -1, J - 1,
                                    "joint index of the slide across k, or -1");
    int_field<&PlanarParams::lift>(cls, "lift", -1, J - 1,
                                   "joint index of the slide along k (SCARA), or -1");
    int_field<&PlanarParams::nrev>(cls, "nrev", 1, PlanarParams::MAX_REV,
                                   "number of revolute joints, 1 to 3");
    cls.def_rw("pose", &PlanarParams::pose, "True: pose targets; False: position targets")
        .def_rw("swap", &PlanarParams::swap,
                "the triangle's branch psi >= 0 takes slot 0 (SCARA), else psi <= 0 does")
        .def_rw("lift_sign", &PlanarParams::lift_sign, "k . (the lift's direction): +1 or -1")
        .def_rw("k", &PlanarParams::k, "(3,) the common axis direction (unit, base frame)")
        .def_rw("e1", &PlanarParams::e1, "(3,) plane basis e1 (unit, normal to k)")
        .def_rw("e2", &PlanarParams::e2, "(3,) plane basis e2 = k x e1")
        .def_rw("origin", &PlanarParams::origin,
                "(3,) origin of the plane coordinates, on the first revolute axis (m)")
        .def_rw("tool", &PlanarParams::tool, "(3,) tool origin at q = 0 (base frame, m)")
        .def_rw("re1", &PlanarParams::re1, "(3,) R_M^T e1 (M = fk(0))")
        .def_rw("wrist", &PlanarParams::wrist,
                "(3,) the last revolute axis point in the tool frame at q = 0 (m)")
        .def_rw("reach", &PlanarParams::reach, "sum of the in-plane link lengths (m)")
        .def_rw("rmin", &PlanarParams::rmin,
                "least distance of the tool origin from the first revolute axis (m)")
        .def_rw("rmax", &PlanarParams::rmax,
                "largest distance from that axis (or across the slide's line) (m)")
        .def_rw("slack", &PlanarParams::slack,
                "how far the revolute axes' tilts may put the tool from the ideal arm's (m)")
        .def_rw("slide_tilt", &PlanarParams::slide_tilt, "|k . slide direction| (sine)")
        .def_rw("lift_tilt", &PlanarParams::lift_tilt, "|k x lift direction| (sine)")
        .def_rw("length", &PlanarParams::length,
                "sum of the distances between consecutive axes and to the tool (m)");
    cls.def_prop_rw(
        "rev", [](const PlanarParams& p) { return small::get_ints(p.rev); },
        [](PlanarParams& p, I64 v) { small::set_ints(p.rev, v, "rev", 0, J - 1); },
        "(3,) the revolute joints' indices, base to tip (unused entries 0)");
    KM_SMALL_VEC(cls, PlanarParams, sign, "(3,) k . (each revolute axis direction): +1 or -1");
    KM_SMALL_PAIRS(cls, PlanarParams, axis, "(3, 2) the revolute axis points at q = 0, plane (m)");
    KM_SMALL_VEC(cls, PlanarParams, tip, "(2,) the tool origin at q = 0, plane coordinates (m)");
    KM_SMALL_VEC(cls, PlanarParams, u, "(2,) the slide direction across k, plane (unit)");
    KM_SMALL_PAIRS(cls, PlanarParams, qlim, "(4, 2) joint limits (rad or m; +-inf: none)");

    sub.attr("SINGULAR_TOL") = km::triangle::SINGULAR_TOL;
    sub.attr("MERGE_TOL") = km::triangle::MERGE_TOL;
    sub.attr("FREE_SAMPLES") = km::planar::FREE_SAMPLES;
    sub.attr("REGULAR") = static_cast<int>(km::triangle::Code::regular);
    sub.attr("NEAR") = static_cast<int>(km::triangle::Code::near);
    sub.attr("FOLD") = static_cast<int>(km::triangle::Code::fold);
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
