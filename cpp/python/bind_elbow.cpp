// The elbow family (3R anthropomorphic and elbow arms): kinematica._core.elbow.
#include "common.hpp"
#include "kinematica/solvers/elbow.hpp"
#include "small_fields.hpp"
#include "solver_binding.hpp"

namespace kmpy {

void bind_elbow(nb::module_& m) {
    using km::ElbowParams;
    nb::module_ sub = m.def_submodule("elbow", "3R elbow arms, anthropomorphic or with a shoulder offset.");
    auto cls = bind_closed_form<ElbowParams>(
        sub, "ElbowParams",
        "A 3R elbow arm as its closed form reads it (solvers/elbow.hpp); plane coordinates "
        "on e1, e2 = k x e1.",
        "km::ElbowParams", "kinematica/solvers/elbow.hpp");
    cls.def_rw("pose", &ElbowParams::pose, "True: pose targets; False: position targets")
        .def_rw("h1", &ElbowParams::h1, "(3,) axis 1 direction (unit, base frame)")
        .def_rw("p1", &ElbowParams::p1, "(3,) a point on axis 1 (m)")
        .def_rw("k", &ElbowParams::k, "(3,) axes 2 and 3 direction (unit)")
        .def_rw("e1", &ElbowParams::e1, "(3,) basis e1 of the plane normal to k")
        .def_rw("e2", &ElbowParams::e2, "(3,) e2 = k x e1")
        .def_rw("hk", &ElbowParams::hk, "(3,) h1 x k")
        .def_rw("p2", &ElbowParams::p2, "(3,) a point on axis 2 (m)")
        .def_rw("s2", &ElbowParams::s2, "k . (axis 2 direction): +1 or -1")
        .def_rw("s3", &ElbowParams::s3, "k . (axis 3 direction): +1 or -1")
        .def_rw("height", &ElbowParams::height, "k . (x - p1): the tool's height over axis 1 (m)")
        .def_rw("rk", &ElbowParams::rk, "(3,) R_M^T k (M = fk(0))")
        .def_rw("re1", &ElbowParams::re1, "(3,) R_M^T e1")
        .def_rw("foot", &ElbowParams::foot,
                "(3,) foot on axis 1 of the common normal of axes 1 and 2 (m)")
        .def_rw("offset", &ElbowParams::offset, "length of that common normal (m)")
        .def_rw("rmin", &ElbowParams::rmin,
                "least distance of the tool origin from the normal's foot on axis 2 (m)")
        .def_rw("rmax", &ElbowParams::rmax, "largest such distance (m)")
        .def_rw("scale", &ElbowParams::scale, "size of the arm (m): the scale of SINGULAR_TOL")
        .def_rw("slack", &ElbowParams::slack,
                "how far axis 3's tilt off k may put the tool from the ideal arm's (m)");
    KM_SMALL_VEC(cls, ElbowParams, a, "(2,) link 2, axis 2 to axis 3 at q = 0, plane (m)");
    KM_SMALL_VEC(cls, ElbowParams, b, "(2,) link 3, axis 3 to the tool origin at q = 0, plane (m)");
    KM_SMALL_VEC(cls, ElbowParams, up, "(2,) h1 x k in plane coordinates: the side of elbow up");
    sub.attr("SINGULAR_TOL") = km::triangle::SINGULAR_TOL;
    sub.attr("MERGE_TOL") = km::triangle::MERGE_TOL;
}

}  // namespace kmpy
