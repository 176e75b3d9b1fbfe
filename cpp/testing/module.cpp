// kinematica._core_testing: the core's internals bound for the tests that pin them, one
// value at a time (against the C library, their definitions, and each named tolerance from
// both sides). Test-only: not the library's API, and nothing in the package imports it.
// Built by the same CMake project as kinematica._core (option KM_TESTING, on by default; a
// release build may leave it out), whose types (Chain, CheckOptions, NumericSolver) its
// functions take.
#define KM_NUMPY_IMPORT
#include "numpy_io.hpp"
// (the numpy C API is imported in this file only)

#include "common.hpp"

namespace kmpy {
void bind_testing(nb::module_& m);           // internals.cpp: kinematica._core_testing.internals
void bind_parallel_testing(nb::module_& m);  // parallel.cpp: kinematica._core_testing.parallel
void bind_decoupled_testing(nb::module_& m);  // decoupled.cpp: ..._core_testing.decoupled
void bind_planar_testing(nb::module_& m);  // planar.cpp: kinematica._core_testing.planar
void bind_general6r_testing(nb::module_& m);  // general6r.cpp: ..._core_testing.general6r
}  // namespace kmpy

namespace {
int import_numpy() {
    import_array1(-1);
    return 0;
}
}  // namespace

NB_MODULE(_core_testing, m) {
    if (import_numpy() < 0) throw nanobind::python_error();
    nanobind::module_::import_("kinematica._core");  // registers the types the hooks take
    m.doc() = "kinematica's compiled core: its internals, for the tests (not the library's API).";
    kmpy::bind_testing(m);
    kmpy::bind_parallel_testing(m);
    kmpy::bind_decoupled_testing(m);
    kmpy::bind_planar_testing(m);
    kmpy::bind_general6r_testing(m);
}
