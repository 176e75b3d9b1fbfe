// The cylindrical family (turn, lift, reach, and an optional roll): kinematica._core.cylindrical.
#include "common.hpp"
#include "kinematica/solvers/cylindrical.hpp"
#include "solver_binding.hpp"

namespace kmpy {

void bind_cylindrical(nb::module_& m) {
    using km::CylindricalParams;
    nb::module_ sub = m.def_submodule(
        "cylindrical", "Cylindrical arms: a turn, a lift along its axis, a reach across it, a roll.");
    auto cls = bind_closed_form<CylindricalParams>(
        sub, "CylindricalParams",
        "A cylindrical arm (RPP or RPPR) as its closed form reads it (solvers/cylindrical.hpp).",
        "km::CylindricalParams", "kinematica/solvers/cylindrical.hpp");
    cls.def_rw("n", &CylindricalParams::n, "joints: 3 (turn, lift, reach) or 4 (and the roll)")
        .def_rw("pose", &CylindricalParams::pose, "True: pose targets; False: position targets")
        .def_rw("turn", &CylindricalParams::turn, "joint index of the turn about k: 0 or 1")
        .def_rw("lift", &CylindricalParams::lift, "joint index of the lift along k: 1 or 0")
        .def_rw("lift_sign", &CylindricalParams::lift_sign, "k . (the lift's direction): +1 or -1")
        .def_rw("k", &CylindricalParams::k, "(3,) the turn's axis direction (unit, base frame)")
        .def_rw("o", &CylindricalParams::o, "(3,) a point on the turn's axis (m)")
        .def_rw("s", &CylindricalParams::s, "(3,) the reach's direction at q = 0 (unit)")
        .def_rw("sp", &CylindricalParams::sp, "(3,) its part across k")
        .def_rw("sk", &CylindricalParams::sk, "k . s")
        .def_rw("ss", &CylindricalParams::ss, "|sp|^2 (> 0)")
        .def_rw("nrm", &CylindricalParams::nrm, "(3,) unit k x sp")
        .def_rw("tool", &CylindricalParams::tool, "(3,) the tool origin at q = 0 (m)")
        .def_rw("h4", &CylindricalParams::h4, "(3,) the roll's axis direction (unit)")
        .def_rw("c4", &CylindricalParams::c4,
                "(3,) the foot of the tool origin on the roll's axis at q = 0 (m)")
        .def_rw("rho", &CylindricalParams::rho,
                "the tool origin's distance from the roll's axis (m)")
        .def_rw("w4", &CylindricalParams::w4, "(3,) a unit vector normal to h4")
        .def_rw("rh4", &CylindricalParams::rh4, "(3,) R_M^T h4 (M = fk(0))")
        .def_rw("rw4", &CylindricalParams::rw4, "(3,) R_M^T w4")
        .def_rw("e1", &CylindricalParams::e1, "(3,) a unit vector normal to k")
        .def_rw("re1", &CylindricalParams::re1, "(3,) R_M^T e1")
        .def_rw("offset", &CylindricalParams::offset,
                "how far the reach's line passes the turn's axis (m)")
        .def_rw("scale", &CylindricalParams::scale, "size of the arm (m): the scale of SINGULAR_TOL")
        .def_rw("slack", &CylindricalParams::slack,
                "how far the lift's tilt off k may put the tool from the ideal arm's (m)");
    sub.attr("SINGULAR_TOL") = km::triangle::SINGULAR_TOL;
    sub.attr("MERGE_TOL") = km::triangle::MERGE_TOL;
}

}  // namespace kmpy
