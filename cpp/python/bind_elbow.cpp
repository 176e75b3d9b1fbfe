// The elbow family (3R anthropomorphic and elbow arms): kinematica._core.elbow.
#include "common.hpp"
#include "kinematica/solvers/elbow.hpp"
#include "kinematica/solvers/elbow_build.hpp"
#include "solver_binding.hpp"

namespace kmpy {

void bind_elbow(nb::module_& m) {
    nb::module_ sub = m.def_submodule("elbow", "3R elbow arms, anthropomorphic or with a shoulder offset.");
    bind_family<km::ElbowParams>(
        sub, "ElbowParams", "A 3R elbow arm as its closed form reads it (solvers/elbow.hpp).",
        "kinematica/solvers/elbow_build.hpp", "km::ElbowParams", "km::elbow::build",
        [](const km::Chain& c) { return km::elbow::build(c); });
    bind_position_build(sub, [](const km::Chain& c) { return km::elbow::build(km::arm_axes(c), false); });
    sub.attr("SINGULAR_TOL") = km::triangle::SINGULAR_TOL;
    sub.attr("MERGE_TOL") = km::triangle::MERGE_TOL;
}

}  // namespace kmpy
