// The closed-form solver families, each bound in its own file (bind_<family>.cpp) into a
// submodule of kinematica._core named after it.
#include "common.hpp"

namespace kmpy {

void bind_planar(nb::module_& m);
void bind_elbow(nb::module_& m);
void bind_cylindrical(nb::module_& m);
void bind_decoupled(nb::module_& m);
void bind_parallel(nb::module_& m);
void bind_srs(nb::module_& m);
void bind_general6r(nb::module_& m);

void bind_solvers(nb::module_& m) {
    bind_planar(m);
    bind_elbow(m);
    bind_cylindrical(m);
    bind_decoupled(m);
    bind_parallel(m);
    bind_srs(m);
    bind_general6r(m);
}

}  // namespace kmpy
