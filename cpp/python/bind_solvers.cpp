// The closed-form solver families, each in a submodule of kinematica._core named after it. A
// family whose binding is its Params and builders alone is registered here, by one
// bind_family call (solver_binding.hpp); one with more has its own bind_<family>.cpp.
#include "common.hpp"
#include "kinematica/solvers/cylindrical_build.hpp"
#include "kinematica/solvers/elbow_build.hpp"
#include "kinematica/solvers/planar_build.hpp"
#include "solver_binding.hpp"

namespace kmpy {

void bind_decoupled(nb::module_& m);
void bind_parallel(nb::module_& m);
void bind_srs(nb::module_& m);
void bind_general6r(nb::module_& m);

void bind_solvers(nb::module_& m) {
    nb::module_ planar = m.def_submodule("planar", "Planar 2R/3R/PR/PRR arms and the SCARA.");
    bind_family<km::PlanarParams>(
        planar, "PlanarParams", "A planar arm or a SCARA as its closed form reads it (solvers/planar.hpp).",
        "kinematica/solvers/planar_build.hpp", "km::PlanarParams", "km::planar::build",
        [](const km::Chain& c) { return km::planar::build(c); }, "build",
        [](const km::Chain& c) { return km::planar::build(km::arm_axes(c), false); });

    nb::module_ elbow = m.def_submodule("elbow", "3R elbow arms, anthropomorphic or with a shoulder offset.");
    bind_family<km::ElbowParams>(
        elbow, "ElbowParams", "A 3R elbow arm as its closed form reads it (solvers/elbow.hpp).",
        "kinematica/solvers/elbow_build.hpp", "km::ElbowParams", "km::elbow::build",
        [](const km::Chain& c) { return km::elbow::build(c); }, "build",
        [](const km::Chain& c) { return km::elbow::build(km::arm_axes(c), false); });

    nb::module_ cylindrical = m.def_submodule(
        "cylindrical", "Cylindrical arms: a turn, a lift along its axis, a reach across it, a roll.");
    bind_family<km::CylindricalParams>(
        cylindrical, "CylindricalParams",
        "A cylindrical arm (RPP or RPPR) as its closed form reads it (solvers/cylindrical.hpp).",
        "kinematica/solvers/cylindrical_build.hpp", "km::CylindricalParams", "km::cylindrical::build",
        [](const km::Chain& c) { return km::cylindrical::build(c); }, "build",
        [](const km::Chain& c) { return km::cylindrical::build(km::arm_axes(c), false); });

    bind_decoupled(m);
    bind_parallel(m);
    bind_srs(m);
    bind_general6r(m);
}

}  // namespace kmpy
