// The cylindrical family (turn, lift, reach, and an optional roll): kinematica._core.cylindrical.
#include "common.hpp"
#include "kinematica/solvers/cylindrical.hpp"
#include "kinematica/solvers/cylindrical_build.hpp"
#include "solver_binding.hpp"

namespace kmpy {

void bind_cylindrical(nb::module_& m) {
    nb::module_ sub = m.def_submodule(
        "cylindrical", "Cylindrical arms: a turn, a lift along its axis, a reach across it, a roll.");
    bind_family<km::CylindricalParams>(
        sub, "CylindricalParams",
        "A cylindrical arm (RPP or RPPR) as its closed form reads it (solvers/cylindrical.hpp).",
        "kinematica/solvers/cylindrical_build.hpp", "km::CylindricalParams",
        "km::cylindrical::build", [](const km::Chain& c) { return km::cylindrical::build(c); });
    bind_position_build(
        sub, [](const km::Chain& c) { return km::cylindrical::build(km::arm_axes(c), false); });
    sub.attr("SINGULAR_TOL") = km::triangle::SINGULAR_TOL;
    sub.attr("MERGE_TOL") = km::triangle::MERGE_TOL;
}

}  // namespace kmpy
