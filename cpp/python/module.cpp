// kinematica._core: the compiled core, bound to Python.
#define KM_NUMPY_IMPORT
#include "numpy_io.hpp"
// (the numpy C API is imported in this file only)

#include "common.hpp"
#include "pool.hpp"

namespace {
int import_numpy() {
    import_array1(-1);
    return 0;
}
}  // namespace

NB_MODULE(_core, m) {
    if (import_numpy() < 0) throw nanobind::python_error();
    m.doc() = "kinematica's compiled core: FK, Jacobians, IK solvers and the shared check.";
    m.def("hardware_threads", &kmpy::hardware_threads, "Threads the machine offers.");
    kmpy::bind_chain(m);
    kmpy::bind_ik(m);
    kmpy::bind_solvers(m);
    kmpy::bind_spatial(m);
    kmpy::bind_lines(m);
    kmpy::bind_topp(m);
    kmpy::bind_jerk(m);
    kmpy::bind_reach(m);
}
