// (being ported: the planar family's binding)
#include "common.hpp"

namespace kmpy {

void bind_planar(nb::module_&) {}

}  // namespace kmpy
