// The general 6R family: kinematica._core.general6r.
//
// General6RParams registered by one bind_family line (its builder, general_6r_build.hpp,
// fills it from the chain), the slot counts its branch labels are made of, and the one
// question the package asks of a solution found by other means: the joints free along
// the continuum through it. The near-6R three-parallel solver beside it. The family's
// tolerances and internals are bound for the tests in kinematica._core_testing.general6r
// (cpp/testing/general6r.cpp). The only product translation unit that includes Eigen
// (through general_6r.hpp): compile time counts.
#include <nanobind/nanobind.h>

#include <cstdint>
#include <optional>

#include "casters.hpp"
#include "common.hpp"
#include "kinematica/solvers/general_6r.hpp"
#include "kinematica/solvers/general_6r_build.hpp"
#include "kinematica/solvers/near_6r.hpp"
#include "kinematica/solvers/near_6r_build.hpp"
#include "numpy_io.hpp"
#include "solver_binding.hpp"

namespace kmpy {

namespace {

namespace kg = km::general6r;
using kg::General6RParams;

//! The labelling the continuum test of a bare chain uses: (start 5, not reversed), the
//! target on the left side (no constant Q asked of the arm).
constexpr int CONTINUUM_LABELLING = 9;
static_assert(kg::LABELLING_START[CONTINUUM_LABELLING] == 5 &&
              !kg::LABELLING_REVERSE[CONTINUUM_LABELLING]);

//! The joints (0-based) free along the continuum of the pose T's solutions through q,
//! the one that moved most first; () where q is regular, at a fold, or does not close
//! the loop to CLOSURE_TOL.
nb::tuple free_joints(const General6RParams& p, const km::Pose& T_in, F64 qh) {
    if (const char* why = p.invalid()) throw nb::value_error(why);
    const In qa = in_f64(qh, "q", 1, {6});  // held: it may own a copy
    const std::optional<kg::SelfMotion> at = p.self_motion_at(T_in, qa.data);
    if (!at || at->verdict != kg::Degeneracy::continuum) return nb::tuple();
    const kg::SelfMotion& sm = *at;
    double moved[6];
    bool free[6];
    for (int k = 0; k < 6; ++k) {
        moved[p.order[k]] = sm.moved[k];
        free[p.order[k]] = ((sm.free >> k) & 1U) != 0;
    }
    int joints[6], count = 0;
    for (int j = 0; j < 6; ++j) {  // by how far each moved, most first (ties: ascending)
        if (!free[j]) continue;
        int at = count++;
        for (; at > 0 && moved[joints[at - 1]] < moved[j]; --at) joints[at] = joints[at - 1];
        joints[at] = j;
    }
    nb::object out = nb::steal(PyTuple_New(count));
    for (int i = 0; i < count; ++i) PyTuple_SET_ITEM(out.ptr(), i, PyLong_FromLong(joints[i]));
    return nb::borrow<nb::tuple>(out);
}

//! free_joints on the loop of a 6R chain (CONTINUUM_LABELLING); () for any other chain.
nb::tuple free_joints_of_chain(const km::Chain& chain, const km::Pose& T, F64 q) {
    kg::Loop loop;
    General6RParams p;
    if (!kg::loop_of(chain, loop) || !kg::labelling(loop, CONTINUUM_LABELLING, p)) {
        return nb::tuple();
    }
    return free_joints(p, T, q);
}

}  // namespace

void bind_general6r(nb::module_& m) {
    nb::module_ sub = m.def_submodule(
        "general6r",
        "Any 6R arm: Raghavan-Roth elimination to a 12 x 12 quadratic eigenproblem "
        "(Manocha-Canny), computed numerically from the arm's loop.");
    sub.attr("CLASSES") = kg::CLASSES;
    sub.attr("PER_CLASS") = kg::PER_CLASS;
    sub.attr("FURTHER") = kg::FURTHER;
    bind_family<General6RParams>(
        sub, "General6RParams",
        "A 6R arm as the loop I = Rz(q'1) L1 ... Rz(q'6) L6 of one labelling of its joints, "
        "and the elimination's constants (general_6r.hpp).",
        "kinematica/solvers/general_6r_build.hpp", "km::general6r::General6RParams",
        "km::general6r::build", [](const km::Chain& c) { return kg::build(c); });
    const char* free_doc =
        "The joints (0-based) free along the continuum of the pose T's (4, 4) solutions "
        "through q (6,), the one that moved most first (the self-motion test of "
        "general_6r.hpp); () where q is regular, at a fold or not a solution of T.";
    sub.def("free_joints", &free_joints, nb::arg("params"), nb::arg("T"), nb::arg("q"), free_doc);
    sub.def("free_joints", &free_joints_of_chain, nb::arg("chain"), nb::arg("T"), nb::arg("q"),
            free_doc);

    using NearParallel = km::Near6RParams<km::ParallelParams>;
    bind_params<NearParallel>(
        sub, "NearParallelParams",
        "A three-parallel 6R arm whose axes hold that structure only within the line "
        "geometry's tolerance: the family's candidates and the general 6R's, checked "
        "together (solvers/near_6r.hpp; built by near_6r_build.hpp).",
        "km::Near6RParams<km::ParallelParams>", "kinematica/solvers/near_6r_build.hpp")
        .attr("cpp_build") = "km::build_near_parallel";
    sub.def("near_parallel", [](const km::Chain& c) { return km::build_near_parallel(c); },
            nb::arg("chain"),
            "The solver of a three-parallel arm near-degenerate (slack > 0): the family's "
            "closed form and the general 6R's, or None (an exact arm, or either declines).");
}

}  // namespace kmpy
