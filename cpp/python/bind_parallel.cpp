// (being ported: the parallel family's binding)
#include "common.hpp"

namespace kmpy {

void bind_parallel(nb::module_&) {}

}  // namespace kmpy
