// (being ported: the elbow family's binding)
#include "common.hpp"

namespace kmpy {

void bind_elbow(nb::module_&) {}

}  // namespace kmpy
