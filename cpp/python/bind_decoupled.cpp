// The arms decoupled at joint 3: joints 1-3 placing a point (ArmPoint), the spherical
// wrist's poses (and the spherical shoulder's, by the reversed chain) and the arm-position
// solver's position targets, bound into the submodule kinematica._core.decoupled (the
// family's tolerances and scalar internals: kinematica._core_testing.decoupled).
#include "casters.hpp"
#include "common.hpp"
#include "kinematica/solvers/arm_point.hpp"
#include "kinematica/solvers/arm_position.hpp"
#include "kinematica/solvers/arm_position_build.hpp"
#include "kinematica/solvers/arm_quartic.hpp"
#include "kinematica/solvers/spherical_shoulder.hpp"
#include "kinematica/solvers/spherical_wrist.hpp"
#include "kinematica/solvers/spherical_wrist_build.hpp"
#include "kinematica/solvers/spherical_shoulder_build.hpp"
#include "numpy_io.hpp"
#include "solver_binding.hpp"

namespace kmpy {

namespace kd = km::decoupled;

void bind_decoupled(nb::module_& m) {
    nb::module_ sub = m.def_submodule(
        "decoupled",
        "Arms decoupled at joint 3: spherical-wrist 6R and RRP arms, and position targets of "
        "longer arms (joints 1-3 place a point).");

    nb::enum_<kd::Shoulder>(sub, "Shoulder", "The geometry of axes 1 and 2.")
        .value("meet", kd::Shoulder::meet)
        .value("parallel", kd::Shoulder::parallel)
        .value("general", kd::Shoulder::general);

    nb::class_<kd::ArmPoint>(sub, "ArmPoint",
                             "Joints 1-3 placing a point fixed after joint 3 (arm_point.hpp), "
                             "filled by the family's builder: its values, read-only.")
        .def_ro("kind", &kd::ArmPoint::kind)
        .def_ro("prismatic", &kd::ArmPoint::prismatic, "joint 3 slides")
        .def_ro("parallel23", &kd::ArmPoint::parallel23, "axes 2 and 3 parallel")
        .def_ro("p1", &kd::ArmPoint::p1, "foot point of axis 1 (m, base frame)")
        .def_ro("h1", &kd::ArmPoint::h1, "axis 1 direction")
        .def_ro("h2", &kd::ArmPoint::h2, "axis 2 direction")
        .def_ro("h3", &kd::ArmPoint::h3, "axis 3 direction")
        .def_ro("a1", &kd::ArmPoint::a1, "a unit vector normal to h1")
        .def_ro("b1", &kd::ArmPoint::b1, "h1 x a1")
        .def_ro("a", &kd::ArmPoint::a, "distance of axes 1 and 2 along e1 (m, signed)")
        .def_ro("ca", &kd::ArmPoint::ca, "cos alpha = h1 . h2")
        .def_ro("g", &kd::ArmPoint::g, "h1 . e2")
        .def_ro("elbow", &kd::ArmPoint::elbow, "sign deciding elbow up (axes 2 and 3 parallel)")
        .def_ro("scale", &kd::ArmPoint::scale, "a length of the arm's size (m)")
        .def_ro("r_lo", &kd::ArmPoint::r_lo, "lower bound of |x - p1| (m)")
        .def_ro("r_hi", &kd::ArmPoint::r_hi, "upper bound of |x - p1| (m)")
        .def_ro("z_lo", &kd::ArmPoint::z_lo, "lower bound of h1 . (x - p1) (m)")
        .def_ro("z_hi", &kd::ArmPoint::z_hi, "upper bound of h1 . (x - p1) (m)")
        .def_ro("beta", &kd::ArmPoint::beta, "revolute joint 3: |u| is extreme at q3 = beta, beta + pi")
        .def_ro("dmin", &kd::ArmPoint::dmin, "revolute joint 3: min |u(q3)| (m)")
        .def_ro("dmax", &kd::ArmPoint::dmax, "revolute joint 3: max |u(q3)| (m)")
        .def_ro("b3", &kd::ArmPoint::b3, "slide: U0 . h3 (m)")
        .def_ro("m3", &kd::ArmPoint::m3, "slide: distance of axis 3 from p2 (m)")
        .def_ro("refine", &kd::ArmPoint::refine, "a second pass for nearly meeting or parallel axes");

    bind_family<kd::SphericalWristParams>(
        sub, "SphericalWristParams",
        "A 6R or RRP arm with a spherical wrist (spherical_wrist.hpp): 8 slots, 6 joints.",
        "kinematica/solvers/spherical_wrist_build.hpp", "km::decoupled::SphericalWristParams",
        "km::decoupled::build", [](const km::Chain& c) { return kd::build(c); },
        "build_spherical_wrist")
        .def_ro("arm", &kd::SphericalWristParams::arm, "joints 1-3 placing the wrist centre");
    bind_family<kd::SphericalShoulderParams>(
        sub, "SphericalShoulderParams",
        "A 6R or RRRPRR arm with a spherical shoulder (spherical_shoulder.hpp): the reversed "
        "chain's spherical wrist, 8 slots, 6 joints.",
        "kinematica/solvers/spherical_shoulder_build.hpp",
        "km::decoupled::SphericalShoulderParams", "km::decoupled::build_shoulder",
        [](const km::Chain& c) { return kd::build_shoulder(c); }, "build_spherical_shoulder")
        .def_ro("wrist", &kd::SphericalShoulderParams::wrist,
                "the reversed chain's SphericalWristParams (its joint j is -q_(7-j))");

    sub.attr("PLACE_RANK_TOL") = kd::PLACE_RANK_TOL;
    sub.attr("PLACE_PROBES") = nb::make_tuple(
        nb::make_tuple(kd::PLACE_PROBES[0][0], kd::PLACE_PROBES[0][1], kd::PLACE_PROBES[0][2]),
        nb::make_tuple(kd::PLACE_PROBES[1][0], kd::PLACE_PROBES[1][1], kd::PLACE_PROBES[1][2]),
        nb::make_tuple(kd::PLACE_PROBES[2][0], kd::PLACE_PROBES[2][1], kd::PLACE_PROBES[2][2]));

    bind_family<kd::ArmPositionParams>(
        sub, "ArmPositionParams",
        "Position targets of an arm of n > 3 joints (arm_position.hpp): 4 slots, n joints.",
        "kinematica/solvers/arm_position_build.hpp", "km::decoupled::ArmPositionParams",
        "km::decoupled::build_position", [](const km::Chain& c) { return kd::build_position(c); },
        "build_arm_position")
        .def_ro("arm", &kd::ArmPositionParams::arm, "joints 1-3 placing the tool origin");

    sub.attr("MAX_POSITION_DOF") = kd::MAX_POSITION_DOF;
}

}  // namespace kmpy
