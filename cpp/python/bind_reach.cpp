// A 6R arm's reach bounds (reach_bounds_build.hpp) and their check (reach_bounds.hpp) of
// targets moved by a held end joint's values, for kinematica.ik.reach_bounds.
#include <nanobind/stl/optional.h>

#include "common.hpp"
#include "numpy_io.hpp"
#include "solver_binding.hpp"
#include "kinematica/moved.hpp"
#include "kinematica/reach_bounds.hpp"
#include "kinematica/reach_bounds_build.hpp"

namespace kmpy {

namespace {

//! (t, G): target i moved by values[j], checked against the bounds.
F64 reach_violation(const km::reach::Bounds& b, F64 T, F64 values, F64 A, bool after, bool slides, double P,
                    double R, bool limits) {
    const In in = in_f64(T, "T", 3, {-1, 4, 4});
    const In v = in_f64(values, "values", 1);
    const In parts = in_f64(A, "A", 3, {3, 4, 4});
    const npy_intp t = in.dim[0], G = v.dim[0];
    double* out;
    F64 result = new_f64({t, G}, out);
    for (npy_intp i = 0; i < t; ++i) {
        for (npy_intp j = 0; j < G; ++j) {
            double moved[16];
            km::moved_pose(parts.data, v.data[j], after, slides, in.data + 16 * i, moved);
            out[i * G + j] = km::reach::violation(b, km::Pose::from_rows(moved), P, R, limits);
        }
    }
    return result;
}

}  // namespace

void bind_reach(nb::module_& m) {
    nb::class_<km::reach::Bounds>(m, "ReachBounds",
                                  "A 6R arm's reach bounds (reach_bounds_build.hpp; opaque).");
    m.def(
        "reach_bounds", [](const km::Chain& c, bool limits) { return km::reach::build(c, limits); },
        nb::arg("chain"), nb::arg("limits"),
        "A 6R arm's ReachBounds, of solutions within the joint limits or anywhere; None for any "
        "other chain.");
    m.def("reach_violation", &reach_violation, nb::arg("bounds"), nb::arg("T"), nb::arg("values"),
          nb::arg("A"), nb::arg("after"), nb::arg("slides"), nb::arg("position"), nb::arg("rotation"), nb::arg("limits"),
          "(t, G) how far (m) each target T[i] (t, 4, 4), moved by values[j] (G,) as a held first "
          "or last (after) joint moves it (moved_poses: the move's parts A (3, 4, 4)), misses "
          "the arm's ReachBounds beyond the slack of "
          "the tolerance (position m, rotation rad), q1 and q6 within their limits with `limits`: "
          "positive where no solution reaches it; NaN for a target with a non-finite entry.");
}

}  // namespace kmpy
