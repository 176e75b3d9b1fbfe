// The shared check's tolerance, options and statuses, its typed answers (answer.hpp), the
// numeric solver, target defects, and the named tolerances of the check and the search.
#include <nanobind/stl/array.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "casters.hpp"
#include "common.hpp"
#include "interrupt.hpp"
#include "kinematica/check.hpp"
#include "kinematica/lm.hpp"
#include "kinematica/numeric.hpp"
#include "kinematica/pose_check.hpp"
#include "solver_binding.hpp"

namespace kmpy {

namespace {

km::NumericSolver make_numeric(F64 bounds, const km::Tolerance& tol, int max_steps, double reach, const km::Vec3& base,
                               const std::array<double, 6>& weights, F64 samples,
                               F64 middle) {
    const In b = in_f64(bounds, "bounds", 2, {-1, 3});
    const npy_intp n = b.dim[0];
    if (n < 1) throw nb::value_error("bounds must have a row per joint");
    const In s = in_f64(samples, "samples", 2, {-1, n});
    const In mid = in_f64(middle, "middle", 1, {n});
    if (max_steps < 0) throw nb::value_error("max_steps must be >= 0");
    km::NumericSolver solver;
    solver.n = static_cast<int>(n);
    for (npy_intp i = 0; i < n; ++i) {
        solver.bounds.push_back({b.data[3 * i], b.data[3 * i + 1], b.data[3 * i + 2]});
    }
    solver.settings = km::LMSettings{tol, max_steps, reach, base};
    for (int k = 0; k < 6; ++k) solver.weights[k] = weights[static_cast<size_t>(k)];
    solver.samples.assign(s.data, s.data + s.size());
    solver.middle.assign(mid.data, mid.data + n);
    return solver;
}

nb::tuple defects_one(F64 T) {
    const In in = in_f64(T, "T", 2, {4, 4});
    const km::PoseDefects d = km::pose_defects(in.data);
    return nb::make_tuple(d.finite, d.last_row, d.ortho, d.det);
}

nb::tuple defects_many(F64 T, int workers) {
    const In in = in_f64(T, "T", 3, {-1, 4, 4});
    const npy_intp N = in.dim[0];
    npy_bool* finite;
    double *last, *ortho, *det;
    nb::object F = new_array({N}, finite, NPY_BOOL);
    nb::object L = new_f64({N}, last), O = new_f64({N}, ortho), D = new_f64({N}, det);
    run_rows(N, FK_BLOCK, workers, [&](long i0, long i1) {
        for (long i = i0; i < i1; ++i) {
            const km::PoseDefects d = km::pose_defects(in.data + 16 * i);
            finite[i] = d.finite;
            last[i] = d.last_row;
            ortho[i] = d.ortho;
            det[i] = d.det;
        }
    });
    return nb::make_tuple(F, L, O, D);
}

//! Each row of Q (m, n) carried by the check's repair (check.hpp) towards its own target
//! T[i] (m, 4, 4), whatever its residual: (the rows reached (m, n), their residuals (m, 2));
//! a row with a non-finite entry is left as it is, its residuals inf.
nb::tuple repair_candidates(const km::Chain& chain, F64 Th, F64 Qh, const km::CheckOptions& opts) {
    const int n = chain.dof();
    const In Q = in_f64(Qh, "Q", 2, {-1, n});
    const npy_intp m = Q.dim[0];
    const In T = in_f64(Th, "T", 3, {m, 4, 4});
    const km::ChainView ch = chain.view();
    double *q, *res;
    F64 Qa = new_f64({m, n}, q), Ra = new_f64({m, 2}, res);
    std::copy(Q.data, Q.data + m * n, q);
    km::CheckWork work(1, n);
    for (npy_intp i = 0; i < m; ++i) {
        double* qi = q + i * n;
        double p_err = km::INF, r_err = km::INF;
        bool finite = true;
        for (int k = 0; k < n; ++k) finite = finite && std::isfinite(qi[k]);
        if (finite) {
            const km::Pose P = km::Pose::from_rows(T.data + 16 * i);
            km::joint_trig(ch, qi, work.c1.data(), work.s1.data());
            km::detail::residual(ch, qi, work.c1.data(), work.s1.data(), 1, P, opts.weights,
                                 p_err, r_err);
            km::detail::repair(ch, qi, P, opts, work, p_err, r_err);
        }
        res[2 * i] = p_err;
        res[2 * i + 1] = r_err;
    }
    return nb::make_tuple(Qa, Ra);
}

}  // namespace

//! The answers' classes: read-only, each attribute by name.
void bind_answers(nb::module_& m) {
    nb::class_<Answer>(m, "Answer", "The check's answer to one target (read-only).")
        .def_ro("solutions", &Answer::solutions, "(count, n) the solutions (within the limits)")
        .def_ro("residuals", &Answer::residuals, "(count, 2) position (m), rotation (rad)")
        .def_ro("out_of_limits", &Answer::out_of_limits, "(out, n) solutions outside the limits")
        .def_ro("branches", &Answer::branches, "(count,) branch labels")
        .def_ro("out_of_limits_branches", &Answer::out_of_limits_branches, "(out,) labels")
        .def_prop_ro("status", [](const Answer& a) { return static_cast<int>(a.report.status); })
        .def_prop_ro("gap", &Answer::gap, "the proven gap of an unreachable target (m), or None")
        .def_prop_ro("nearest_error", &Answer::nearest_error, "(m, rad) of the closest miss")
        .def_prop_ro("near_singular", [](const Answer& a) { return a.report.near; })
        .def_prop_ro("free_joints", &Answer::free_joints, "free joints (status singular only)")
        .def(
            "result",
            [](const Answer& a, nb::handle cls, nb::handle fields, nb::handle statuses) {
                return make_result(a, cls, result_fields(cls, fields, statuses), statuses);
            },
            nb::arg("cls"), nb::arg("fields"), nb::arg("statuses"),
            "A new cls (no __init__) holding fields and these attributes (make_result).");

    nb::class_<BatchAnswer>(m, "BatchAnswer", "The check's answers to N targets (read-only).")
        .def(nb::new_(&batch_answer), nb::arg("q"), nb::arg("slot"), nb::arg("res"),
             nb::arg("status"), nb::arg("count"), nb::arg("out_count"), nb::arg("gap"),
             nb::arg("nearest"), nb::arg("near"), nb::arg("free"),
             "Arrays made elsewhere (a batch merged or stacked), checked and made read-only.")
        .def_ro("q", &BatchAnswer::q, "(N, m, n) solutions, then those outside the limits")
        .def_ro("slot", &BatchAnswer::slot, "(N, m) the slot (branch) of each row, -1 after")
        .def_ro("res", &BatchAnswer::res, "(N, m, 2) position (m), rotation (rad) residuals")
        .def_ro("status", &BatchAnswer::status, "(N,) status codes")
        .def_ro("count", &BatchAnswer::count, "(N,) solutions within the limits")
        .def_ro("out_count", &BatchAnswer::out_count, "(N,) solutions outside them")
        .def_ro("gap", &BatchAnswer::gap, "(N,) the proven gap of unreachable targets, else NaN")
        .def_ro("nearest", &BatchAnswer::nearest, "(N, 2) the closest miss (m, rad)")
        .def_ro("near", &BatchAnswer::near, "(N,) the near flag")
        .def_ro("free", &BatchAnswer::free, "(N, n) the free joints");

    nb::class_<Prepared>(m, "Prepared", "A solver made ready for one target (Params.prepare).")
        .def("__call__", &Prepared::operator(), nb::arg("T").none(), nb::arg("q0").none() = nb::none(),
             "The result (or Answer) of T (4, 4), sorted by q0 (n,); None for either to read otherwise.")
        .def("held", &Prepared::held, nb::arg("joint"), nb::arg("A"), nb::arg("after"),
             nb::arg("slides"), nb::arg("name"),
             "This Prepared of the arm locked at 0 at the whole arm's end joint `joint` (ik.moved).")
        .def("at", &Prepared::at, nb::arg("T").none(), nb::arg("value"), nb::arg("q0").none() = nb::none(),
             "The whole arm's result of T (4, 4) with the held joint at `value` (or None).")
        .def("sweep", &Prepared::sweep, nb::arg("T"), nb::arg("start"), nb::arg("grid"),
             nb::arg("skip"), nb::arg("bounds").none(), nb::arg("position"), nb::arg("rotation"),
             nb::arg("limits"), nb::arg("slack"), nb::arg("workers"),
             "(index (N,), answers): each T[i] at the first value of grid nearest start[i] with a "
             "solution (nearest_value.swept).");
}

void bind_ik(nb::module_& m) {
    bind_answers(m);
    m.def(
        "moved_poses",
        [](nb::handle A, nb::handle T, nb::handle v, bool after, bool slides) {
            const In parts = in_f64(A, "A", 3, {3, 4, 4});
            const In poses = in_f64(T, "T", 3, {-1, 4, 4});
            const npy_intp N = poses.dim[0];
            const In values = in_f64(v, "v", 1, {N});
            double* out;
            F64 moved = new_f64({N, 4, 4}, out);
            for (npy_intp i = 0; i < N; ++i) {
                km::moved_pose(parts.data, values.data[i], after, slides, poses.data + 16 * i,
                           out + 16 * i);
            }
            return moved;
        },
        nb::arg("A"), nb::arg("T"), nb::arg("v"), nb::arg("after"), nb::arg("slides"),
        "(N, 4, 4) the poses T of a whole arm as targets of the arm locked at 0 (ik.moved).");
    const km::Tolerance defaults;  // the defaults, as ik_types.hpp writes them
    nb::class_<km::Tolerance>(m, "Tolerance", "Acceptance tolerances of a solution.")
        .def(nb::init<double, double>(), nb::arg("position") = defaults.position,
             nb::arg("rotation") = defaults.rotation)
        .def_rw("position", &km::Tolerance::position, "m")
        .def_rw("rotation", &km::Tolerance::rotation, "rad");
    nb::class_<km::CheckOptions>(m, "CheckOptions", "How the shared check judges candidates.")
        .def(nb::init<>())
        .def_rw("tol", &km::CheckOptions::tol, "a solution is within it of the target")
        .def_rw("respect_limits", &km::CheckOptions::respect_limits)
        .def_rw("complete", &km::CheckOptions::complete, "the solver gives every solution")
        .def_rw("gap_slack", &km::CheckOptions::gap_slack, "m: unreachable needs a gap beyond tol + this")
        .def_rw("repair", &km::CheckOptions::repair, "carry each candidate to this arm's solution")
        .def_prop_rw(
            "weights",
            [](const km::CheckOptions& o) {
                return std::array<double, 6>{o.weights[0], o.weights[1], o.weights[2],
                                             o.weights[3], o.weights[4], o.weights[5]};
            },
            [](km::CheckOptions& o, const std::array<double, 6>& w) {
                for (int k = 0; k < 6; ++k) o.weights[k] = w[static_cast<size_t>(k)];
            },
            "of x, y, z, rx, ry, rz (0: not counted)");

    nb::class_<km::NumericSolver> numeric(m, "NumericSolver", "Levenberg-Marquardt with restarts (lm.hpp).");
    numeric.def(nb::new_(&make_numeric), nb::arg("bounds"), nb::arg("tol"), nb::arg("max_steps"), nb::arg("reach"), nb::arg("base"),
                nb::arg("weights"), nb::arg("samples"), nb::arg("middle"));
    numeric.def_prop_ro("restarts", &km::NumericSolver::restarts);
    numeric.def_rw("skip_first", &km::NumericSolver::skip_first,
                   "True: the attempts start at the first restart (the first guess searched)");
    add_ik_methods(numeric, [](const km::NumericSolver& s) -> const km::NumericSolver& { return s; });

    m.def("repair_candidates", &repair_candidates, nb::arg("chain"), nb::arg("T"), nb::arg("Q"),
          nb::arg("options"), "Each row of Q (m, n) repaired towards its target T[i] (m, 4, 4).");
    m.def("pose_defects", &defects_one, nb::arg("T"),
          "(finite, max |last row - [0,0,0,1]|, max |RᵀR - I|, det R) of T (4, 4).");
    m.def("pose_defects_batch", &defects_many, nb::arg("T"), nb::arg("workers") = 1, "pose_defects, batched.");

    nb::dict status;  // name: code, the codes 0, 1, ... of km::Status in order
    const char* names[] = {"ok", "singular", "out_of_limits", "unreachable", "not_found", "invalid"};
    static_assert(static_cast<int>(km::Status::invalid) == 5, "a name for each status");
    for (int code = 0; code < 6; ++code) status[names[code]] = code;
    m.attr("STATUS") = status;
}

}  // namespace kmpy
