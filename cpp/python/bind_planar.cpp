// The planar family (planar 2R/3R/PR/PRR arms and the SCARA): kinematica._core.planar.
#include "common.hpp"
#include "kinematica/solvers/planar.hpp"
#include "kinematica/solvers/planar_build.hpp"
#include "solver_binding.hpp"

namespace kmpy {

void bind_planar(nb::module_& m) {
    nb::module_ sub = m.def_submodule("planar", "Planar 2R/3R/PR/PRR arms and the SCARA.");
    bind_family<km::PlanarParams>(
        sub, "PlanarParams",
        "A planar arm or a SCARA as its closed form reads it (solvers/planar.hpp).",
        "kinematica/solvers/planar_build.hpp", "km::PlanarParams", "km::planar::build",
        [](const km::Chain& c) { return km::planar::build(c); });
    bind_position_build(sub, [](const km::Chain& c) { return km::planar::build(km::arm_axes(c), false); });
    sub.attr("SINGULAR_TOL") = km::triangle::SINGULAR_TOL;
    sub.attr("MERGE_TOL") = km::triangle::MERGE_TOL;
    sub.attr("FREE_SAMPLES") = km::planar::FREE_SAMPLES;
}

}  // namespace kmpy
