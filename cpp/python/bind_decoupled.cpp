// (being ported: the decoupled family's binding)
#include "common.hpp"

namespace kmpy {

void bind_decoupled(nb::module_&) {}

}  // namespace kmpy
