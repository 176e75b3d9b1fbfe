// The arms decoupled at joint 3 (joints 1-3 placing a point: ArmPoint), the spherical wrist,
// the spherical shoulder and the arm-position solver: kinematica._core.decoupled (their
// tolerances and internals: kinematica._core_testing.decoupled).
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

    nb::class_<kd::ArmPoint>(sub, "ArmPoint",
                             "Joints 1-3 placing a point fixed after joint 3 (arm_point.hpp), "
                             "filled by the family's builder (opaque: arm_shape reads it).");
    sub.def(
        "arm_shape",
        [](const kd::ArmPoint& arm) {
            const char* kind = arm.kind == kd::Shoulder::meet       ? "meet"
                               : arm.kind == kd::Shoulder::parallel ? "parallel"
                                                                    : "general";
            return nb::make_tuple(kind, arm.prismatic, arm.parallel23);
        },
        nb::arg("arm"),
        "(kind, prismatic, parallel23): what names the arm's branches (ik.analytic.arm_point).");

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

    bind_family<kd::ArmPositionParams>(
        sub, "ArmPositionParams",
        "Position targets of an arm of n > 3 joints (arm_position.hpp): 4 slots, n joints.",
        "kinematica/solvers/arm_position_build.hpp", "km::decoupled::ArmPositionParams",
        "km::decoupled::build_position", [](const km::Chain& c) { return kd::build_position(c); },
        "build_arm_position")
        .def_ro("arm", &kd::ArmPositionParams::arm, "joints 1-3 placing the tool origin");
}

}  // namespace kmpy
