// The three-parallel family (UR type): kinematica._core.parallel.
//
// ParallelParams (built by the core: parallel_build.hpp) with its IK methods and mode, and
// the family's builder. Its tolerances and the scalar internals the tests pin are in the
// test-only module kinematica._core_testing (cpp/testing/).
#include "common.hpp"
#include "kinematica/solvers/parallel.hpp"
#include "kinematica/solvers/parallel_build.hpp"
#include "solver_binding.hpp"

namespace kmpy {

void bind_parallel(nb::module_& m) {
    nb::module_ sub = m.def_submodule(
        "parallel", "Three-parallel 6R arms (UR type): axes 5-6 meeting, parallel or apart.");

    nb::enum_<km::ParallelMode>(sub, "Mode", nb::is_arithmetic(), "How axes 5 and 6 lie.")
        .value("meet", km::ParallelMode::meet, "axes 5 and 6 meet")
        .value("parallel", km::ParallelMode::parallel, "axes 5 and 6 parallel")
        .value("general", km::ParallelMode::general, "apart (a5 != 0): the quartic");

    bind_family<km::ParallelParams>(
        sub, "ParallelParams",
        "A UR-type arm (axes 2, 3, 4 parallel) for its closed form, as the core builds it "
        "(solvers/parallel_build.hpp; parallel_params.hpp documents its fields).",
        "kinematica/solvers/parallel_build.hpp", "km::ParallelParams", "km::parallel::build",
        [](const km::Chain& c) { return km::parallel::build(c); })
        .def_prop_ro("mode", [](const km::ParallelParams& p) { return p.mode; },
                     "How axes 5 and 6 lie (the branch labels follow it).");
}

}  // namespace kmpy
