// SRS 7R arms (iiwa type) at a given arm angle: kinematica._core.srs.
#include "common.hpp"
#include "kinematica/solvers/srs.hpp"
#include "solver_binding.hpp"

namespace kmpy {

void bind_srs(nb::module_& m) {
    using km::srs::SRSParams;
    nb::module_ sub = m.def_submodule(
        "srs", "SRS 7R arms (axes 1-3 meet, axes 5-7 meet): all 8 solutions at an arm angle.");
    auto cls = bind_closed_form<SRSParams>(
        sub, "SRSParams",
        "An SRS 7R arm as its closed form reads it (solvers/srs.hpp): 8 slots, 7 joints; "
        "vectors at q = 0 in the base frame.",
        "km::srs::SRSParams", "kinematica/solvers/srs.hpp");
    cls.def_rw("shoulder", &SRSParams::shoulder,
               "axes 1, 2, 3 as a three-axis decomposition (its h4, h5, h6 fields)")
        .def_rw("wrist", &SRSParams::wrist, "axes 5, 6, 7 as a three-axis decomposition")
        .def_rw("s", &SRSParams::s, "(3,) the shoulder centre S (m)")
        .def_rw("w_tool", &SRSParams::w_tool, "(3,) the wrist centre in the tool frame (m)")
        .def_rw("se", &SRSParams::se, "(3,) shoulder to elbow point at q = 0 (m)")
        .def_rw("ew", &SRSParams::ew, "(3,) elbow point to wrist centre at q = 0 (m)")
        .def_rw("h4", &SRSParams::h4, "(3,) the elbow axis (unit)")
        .def_rw("ref", &SRSParams::ref, "(3,) the arm angle's reference direction (axis 1)")
        .def_rw("ref_alt", &SRSParams::ref_alt, "(3,) a unit vector normal to ref")
        .def_rw("stretched", &SRSParams::stretched, "q4 (rad) where |W - S| is largest")
        .def_rw("d_max", &SRSParams::d_max, "largest |W - S| (m)")
        .def_rw("d_min", &SRSParams::d_min, "least |W - S| (m)")
        .def_rw("scale", &SRSParams::scale, "the arm's size (m), for tolerances")
        .def_rw("psi", &SRSParams::psi, "the arm angle to solve at (rad)");
    cls.def(
        "at",
        [](const SRSParams& p, double psi) {
            SRSParams out = p;
            out.psi = psi;
            return out;
        },
        nb::arg("psi"), "A copy solving at the arm angle psi (rad).");
    sub.attr("COLLINEAR_TOL") = km::srs::COLLINEAR_TOL;
    sub.attr("REFERENCE_TOL") = km::srs::REFERENCE_TOL;
}

}  // namespace kmpy
