// Binding an IK solver: single targets, batches, and its raw candidates (for tests).
//
// bind_solver<Solver>(cls) adds to a solver's nanobind class:
//   ik(chain, T, options, q0, labels)           one target: an Answer (answer.hpp)
//   ik_batch(chain, T, options, q0, invalid, workers)   N targets: a BatchAnswer
//   prepare(chain, options, roundoff, labels, result, fields, statuses, final)
//                                               a Prepared: one rigid target -> its result
//   candidates(chain, T, q0)                    the solver's raw candidates and info
// where Solver satisfies ik.hpp's solver interface (ClosedForm<Params> for closed forms).
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "answer.hpp"
#include "casters.hpp"
#include "common.hpp"
#include "interrupt.hpp"
#include "kinematica/chain.hpp"
#include "kinematica/ik.hpp"
#include "kinematica/held_sweep.hpp"
#include "kinematica/moved.hpp"
#include "kinematica/pose_check.hpp"
#include "numpy_io.hpp"

namespace kmpy {

//! The work arrays of single calls with one solver type: made once per thread (and again
//! only when an arm of other dimensions comes).
template <class Solver>
km::IKWork<Solver>& thread_work(const Solver& s, int n) {
    thread_local std::unique_ptr<km::IKWork<Solver>> work;
    if (!work || work->check.m != s.slots() || work->check.n != n) {
        work = std::make_unique<km::IKWork<Solver>>(s, n);
    }
    return *work;
}

//! The labels of slots[first, last) as a tuple of the label objects themselves.
inline nb::tuple branch_tuple(nb::handle labels, const int* slots, int first, int last) {
    nb::object t = nb::steal(PyTuple_New(last - first));
    for (int r = first; r < last; ++r) {
        PyObject* label = PyTuple_GET_ITEM(labels.ptr(), slots[r]);
        Py_INCREF(label);
        PyTuple_SET_ITEM(t.ptr(), r - first, label);
    }
    return nb::borrow<nb::tuple>(t);
}

//! The branch labels of a solver of m slots: a tuple of at least m.
inline nb::handle checked_labels(nb::handle labels, int m) {
    if (!PyTuple_Check(labels.ptr()) || PyTuple_GET_SIZE(labels.ptr()) < m) {
        throw nb::value_error(("labels must be a tuple of the solver's " + std::to_string(m) +
                               " branch names")
                                  .c_str());
    }
    return labels;
}

inline km::Pose target_pose(F64 T) {
    const In in = in_f64(T, "T", 2, {4, 4});
    return km::Pose::from_rows(in.data);
}

//! q0 (n,) checked, or an In without data for None (read .data while the In lives).
inline In optional_q0(nb::handle q0, int n) {
    if (q0.is_none()) return In{};
    return in_f64(q0, "q0", 1, {n});
}

//! A solver built for n joints takes chains of n joints only.
template <class Solver>
void check_dims(const Solver& s, const km::Chain& chain) {
    if (s.dof() != chain.dof()) {
        throw nb::value_error(("this solver takes a chain of " + std::to_string(s.dof()) +
                               " joints, got " + std::to_string(chain.dof()))
                                  .c_str());
    }
}

//! One target solved and checked, compiled for AVX-512, AVX2 and the baseline (the
//! check's trigonometry of every candidate runs as SIMD on the first two).
template <class Solver>
KM_CLONES km::CheckReport solve_checked(const Solver& s, const km::ChainView& ch, const km::Pose& P,
                                        const km::CheckOptions& opts, const double* q0,
                                        km::IKWork<Solver>& work, const km::CheckOut& out) {
    return km::solve_ik(s, ch, P, opts, q0, work, out);
}

//! Where one target's checked rows land before they are copied out: per thread.
struct OneOut {
    std::vector<double> q, res;
    std::vector<int> slot;
    void fit(int m, int n) {
        if (static_cast<int>(slot.size()) < m || static_cast<int>(q.size()) < m * n) {
            q.resize(static_cast<size_t>(m * n));
            res.resize(static_cast<size_t>(2 * m));
            slot.resize(static_cast<size_t>(m));
        }
    }
};

//! One target P solved and checked into buf (its rows: solutions, then those outside the
//! limits), on this thread's work arrays: its report.
template <class Solver>
km::CheckReport ik_rows(const Solver& s, const km::ChainView& ch, const km::Pose& P,
                        const km::CheckOptions& opts, const double* q0p, OneOut& buf) {
    buf.fit(s.slots(), ch.n);
    km::IKWork<Solver>& work = thread_work(s, ch.n);
    return solve_checked(s, ch, P, opts, q0p, work,
                         km::CheckOut{buf.q.data(), buf.slot.data(), buf.res.data()});
}

//! The Answer of one target's rows in buf (ik_rows, its report rep; n joints): its
//! solutions, residuals, solutions outside the limits, the branch label of each (labels:
//! one per slot) and the report.
inline Answer answer_of(const OneOut& buf, const km::CheckReport& rep, int n, nb::handle labels) {
    const int count = rep.count, out = rep.out_count;
    double *q, *res, *qo;
    Answer a;
    a.solutions = read_only(new_f64({count, n}, q));
    a.residuals = read_only(new_f64({count, 2}, res));
    a.out_of_limits = read_only(new_f64({out, n}, qo));
    std::copy(buf.q.data(), buf.q.data() + count * n, q);
    std::copy(buf.res.data(), buf.res.data() + 2 * count, res);
    std::copy(buf.q.data() + count * n, buf.q.data() + (count + out) * n, qo);
    const int* slot = buf.slot.data();
    a.branches = branch_tuple(labels, slot, 0, count);
    a.out_of_limits_branches = branch_tuple(labels, slot, count, count + out);
    a.report = rep;
    a.n = n;
    return a;
}

//! The Answer of one target P (read by the caller): ik_rows, then answer_of.
template <class Solver>
Answer ik_pose(const Solver& s, const km::Chain& chain, const km::Pose& P,
               const km::CheckOptions& opts, const double* q0p, nb::handle labels) {
    const km::ChainView ch = chain.view();
    thread_local OneOut buf;
    const km::CheckReport rep = ik_rows(s, ch, P, opts, q0p, buf);
    return answer_of(buf, rep, ch.n, labels);
}

//! ik_pose of one target T (4, 4), q0 (n,) or None.
template <class Solver>
Answer ik_one(const Solver& s, const km::Chain& chain, F64 T,
                 const km::CheckOptions& opts, nb::handle q0, nb::handle labels) {
    check_dims(s, chain);
    checked_labels(labels, s.slots());
    const km::Pose P = target_pose(T);
    const In q0in = optional_q0(q0, chain.dof());
    return ik_pose(s, chain, P, opts, q0in.data, labels);
}

//! A solver made ready for one kind of call: the chain, the check's options, the branch
//! labels and what a final answer's result is made of (make_result), held; called with
//! one target T (4, 4) and q0 (n,) or None. A target the core does not read in place or
//! that is not rigid to round-off, or a q0 not of n finite float64 values, gives None (the
//! caller's general path reads and explains it); an answer whose status is final (bit
//! `status` of final_codes) gives its result, any other its Answer (the caller completes it).
//!
//! Made for the arm an end joint's lock leaves (held()), it is called with the held value
//! beside the target (at()): the target moved by the value (kinematica.ik.moved), solved,
//! and the whole arm's result given, the joint's column put back and its parameter named.
struct Prepared {
    std::function<Answer(const km::Pose&, const double* q0)> solve;
    //! solve's rows alone (ik_rows), no Python object made: callable without the GIL
    std::function<km::CheckReport(const km::Pose&, OneOut&)> rows;
    nb::object keep;  //!< the solver, the chain and the labels the solve reads
    const km::Chain* chain = nullptr;  //!< the chain solved (kept alive by keep)
    nb::object labels;
    int n = 0;  //!< the locked arm's joints
    nb::object result, fields, statuses;
    double roundoff = 0.0;
    std::uint32_t final_codes = 0;
    // the held end joint (held()): its index in the whole arm (-1: none), its name, the
    // move's parts A0, A1, A2 (4x4 rows each) and whether it comes after the target
    int held_joint = -1;
    bool held_after = false, held_slides = false;
    double held_move[48] = {};
    nb::object held_name;

    //! T's 16 values (rows) where the core reads T in place and it is rigid, else nullptr.
    const double* rigid_rows(nb::handle T) const {
        PyObject* o = T.ptr();
        if (!PyArray_Check(o)) return nullptr;
        auto* a = reinterpret_cast<PyArrayObject*>(o);
        if (PyArray_TYPE(a) != NPY_DOUBLE || PyArray_NDIM(a) != 2 || PyArray_DIM(a, 0) != 4 ||
            PyArray_DIM(a, 1) != 4 || !PyArray_IS_C_CONTIGUOUS(a) || !PyArray_ISALIGNED(a) ||
            !PyArray_ISNOTSWAPPED(a)) {
            return nullptr;
        }
        const double* t = static_cast<const double*>(PyArray_DATA(a));
        return rigid(t) ? t : nullptr;
    }
    //! Whether the 16 values (rows) t are a rigid pose to round-off, as the core reads one.
    bool rigid(const double* t) const {
        const km::PoseDefects d = km::pose_defects(t);
        return d.finite && d.last_row == 0.0 && d.ortho <= roundoff && d.det > 0.0;
    }
    bool final(const Answer& ans) const {
        return ((final_codes >> static_cast<unsigned>(ans.report.status)) & 1U) != 0U;
    }

    //! q0 (None, or a float64 array of `size` values, at most FREE_JOINTS) into q (room for
    //! `size`), leaving out entry `skip` (-1: none): false where a value is not finite or
    //! there are too many (the caller's general path explains it). with_q0: q0 is not None.
    static bool read_q0(nb::handle q0, int size, int skip, double* q, bool& with_q0) {
        with_q0 = !q0.is_none();
        if (!with_q0) return true;
        if (size > km::FREE_JOINTS) return false;
        const In in = in_f64(q0, "q0", 1, {size});
        for (int i = 0, k = 0; i < size; ++i) {
            if (!std::isfinite(in.data[i])) return false;
            if (i != skip) q[k++] = in.data[i];
        }
        return true;
    }

    //! The result (or Answer) of T sorted by q0; None where T is not read in place or not
    //! rigid, or q0 (n,) is not within the chain's own limits and a turn (q_state not ok:
    //! the caller warns of it and its general path solves).
    nb::object operator()(nb::handle T, nb::handle q0) const {
        const double* t = rigid_rows(T);
        double q[km::FREE_JOINTS];
        bool with_q0 = false;
        if (t == nullptr || !read_q0(q0, n, -1, q, with_q0)) return nb::none();
        if (with_q0 && (chain == nullptr || km::q_state(chain->view(), q) != km::QState::ok)) return nb::none();
        const Answer ans = solve(km::Pose::from_rows(t), with_q0 ? q : nullptr);
        if (final(ans)) return make_result(ans, result, fields, statuses);
        return nb::cast(ans);
    }

    //! The whole arm's result of T with the held joint at `value` where the answer is
    //! final, else the locked arm's Answer of the moved T (the caller completes it); None
    //! where T is not read in place or not rigid, or q0 (the whole arm's, or None) not
    //! finite float64 values (the caller's general path).
    nb::object at(nb::handle T, double value, nb::handle q0) const {
        if (held_joint < 0) throw nb::value_error("at(): this Prepared holds no joint (held())");
        const double* t = rigid_rows(T);
        double q[km::FREE_JOINTS];
        bool with_q0 = false;
        if (t == nullptr || !read_q0(q0, n + 1, held_joint, q, with_q0)) return nb::none();
        return given(solved_at(t, value, with_q0 ? q : nullptr), value);
    }

    //! For each target T[i] (N, 4, 4), at(T[i], v) at the first value v of grid (G,) whose
    //! answer has a solution (within the limits where they are kept), tried in its own order:
    //! nearest start[i] first (of two as near, the lower), leaving out a value equal to
    //! skip[i] (NaN: none) and the values the reach bounds prove out of reach (bounds: the
    //! ReachBounds of the arm locked at 0, or None: violation above `slack`
    //! with the tolerance P m, R rad, q1 and q6 within their limits with `limits`). The rows
    //! are solved on up to `workers` threads, the GIL released, and one Python object made
    //! per row answered. Returns (index (N,) of the value answered in grid, -1 where none
    //! has a solution, -2 where T[i] is not rigid; [at(T[i], grid[index[i]]) or None]).
    nb::tuple sweep(F64 T, F64 start, F64 grid, F64 skip, const km::reach::Bounds* bounds, double P, double R,
                    bool limits, double slack, int workers) const {
        if (held_joint < 0) throw nb::value_error("sweep(): this Prepared holds no joint (held())");
        const In in = in_f64(T, "T", 3, {-1, 4, 4});
        const npy_intp N = in.dim[0];
        const In s0 = in_f64(start, "start", 1, {N});
        const In sk = in_f64(skip, "skip", 1, {N});
        const In g = in_f64(grid, "grid", 1);
        const npy_intp G = g.dim[0];
        std::vector<OneOut> bufs(static_cast<size_t>(N));
        std::vector<km::CheckReport> reps(static_cast<size_t>(N));
        npy_int64* index;
        nb::object found = new_i64({N}, index);
        const km::HeldMove move{held_move, held_after, held_slides};
        const km::ReachScreen screen{bounds, P, R, slack, limits};
        run_rows(static_cast<long>(N), 1L, workers, [&](long begin, long end) {
            std::vector<long> order;
            for (long i = begin; i < end; ++i) {
                const double* t = in.data + 16 * i;
                if (!rigid(t)) {
                    index[i] = -2;
                    continue;
                }
                OneOut& buf = bufs[static_cast<size_t>(i)];
                km::CheckReport& rep = reps[static_cast<size_t>(i)];
                index[i] = km::first_held_value(g.data, G, s0.data[i], sk.data[i], t, move, screen, order,
                                                [&](const km::Pose& pose) {
                                                    rep = rows(pose, buf);
                                                    return rep.count > 0;
                                                });
            }
        });
        nb::list answers;
        for (npy_intp i = 0; i < N; ++i) {
            if (index[i] < 0) {
                answers.append(nb::none());
                continue;
            }
            const size_t r = static_cast<size_t>(i);
            answers.append(given(answer_of(bufs[r], reps[r], n, labels), g.data[index[i]]));
        }
        return nb::make_tuple(read_only(found), answers);
    }

    //! The locked arm's answer of the target T (rows) moved by the held joint at `value`.
    Answer solved_at(const double* T, double value, const double* q0) const {
        double moved[16];
        km::moved_pose(held_move, value, held_after, held_slides, T, moved);
        return solve(km::Pose::from_rows(moved), q0);
    }
    //! The whole arm's result of a final answer, the joint at `value` put back and named;
    //! else the locked arm's Answer (the caller completes it).
    nb::object given(Answer ans, double value) const {
        if (!final(ans)) return nb::cast(std::move(ans));
        const nb::object parameter = nb::make_tuple(held_name, value);
        return make_result(widened(ans, held_joint, value), result, fields, statuses, parameter);
    }

    //! This Prepared for the arm locked at 0 at joint `joint` of the whole arm (its first
    //! or last), the move's parts A (3, 4, 4) before the target (first) or after (last).
    Prepared held(int joint, nb::handle A, bool after, bool slides, nb::str name) const {
        if (joint < 0 || joint >= km::FREE_JOINTS) throw nb::value_error("held(): joint out of range");
        const In parts = in_f64(A, "A", 3, {3, 4, 4});
        Prepared p = *this;
        std::copy(parts.data, parts.data + 48, p.held_move);
        p.held_joint = joint;
        p.held_after = after;
        p.held_slides = slides;
        p.held_name = name;
        return p;
    }
};

//! A batch of N targets: a BatchAnswer (answer.hpp) of arrays q (N, m, n), slot (N, m),
//! res (N, m, 2), status (N,), count (N,), out_count (N,), gap (N,), nearest (N, 2),
//! near (N,), free (N, n), written in place by the core. Target i is solved and checked by solve_row(i, chain, P, q0 of i, work, out)
//! (a solver with a value per target); s gives the work arrays' dimensions.
template <class Solver, class SolveRow>
BatchAnswer ik_many_rows(const Solver& s, const km::Chain& chain, F64 Th, nb::handle q0h,
                      nb::handle invalidh, int workers, const SolveRow& solve_row) {
    check_dims(s, chain);
    const km::ChainView ch = chain.view();
    const int n = ch.n, m = s.slots();
    const In T = in_f64(Th, "T", 3, {-1, 4, 4});
    const npy_intp N = T.dim[0];
    const In q0in = q0h.is_none() ? In{} : in_f64(q0h, "q0", 2, {N, n});
    const double* q0 = q0in.data;
    const npy_bool* invalid = in_flags(invalidh, "invalid", N);
    double *q, *res, *gap, *nearest;
    npy_int64 *slot, *status, *count, *out_count;
    npy_bool *near, *freeb;
    // read-only to Python from the start: the core writes them through the pointers
    BatchAnswer out{read_only(new_f64({N, m, n}, q)),  read_only(new_i64({N, m}, slot)),
                    read_only(new_f64({N, m, 2}, res)), read_only(new_i64({N}, status)),
                    read_only(new_i64({N}, count)),     read_only(new_i64({N}, out_count)),
                    read_only(new_f64({N}, gap)),       read_only(new_f64({N, 2}, nearest)),
                    read_only(new_bools({N}, near)),    read_only(new_bools({N, n}, freeb))};
    const int blocks = static_cast<int>((N + TARGET_BLOCK - 1) / TARGET_BLOCK);
    run_blocks(blocks, workers, [&](int blk) {
        km::IKWork<Solver> work(s, n);  // once per block
        std::vector<int> slots(static_cast<size_t>(m));
        const npy_intp i1 = std::min<npy_intp>((blk + 1) * static_cast<npy_intp>(TARGET_BLOCK), N);
        for (npy_intp i = blk * static_cast<npy_intp>(TARGET_BLOCK); i < i1; ++i) {
            const km::CheckOut o{q + i * m * n, slots.data(), res + i * m * 2};
            km::CheckReport rep;
            if (invalid != nullptr && invalid[i]) {
                rep = km::invalid_target(m, n, o);
            } else {
                const km::Pose P = km::Pose::from_rows(T.data + 16 * i);
                rep = solve_row(i, ch, P, q0 != nullptr ? q0 + i * n : nullptr, work, o);
            }
            for (int r = 0; r < m; ++r) slot[i * m + r] = slots[static_cast<size_t>(r)];
            status[i] = static_cast<npy_int64>(rep.status);
            count[i] = rep.count;
            out_count[i] = rep.out_count;
            gap[i] = rep.gap;
            nearest[2 * i] = rep.nearest_position;
            nearest[2 * i + 1] = rep.nearest_rotation;
            near[i] = rep.near;
            for (int j = 0; j < n; ++j) freeb[i * n + j] = km::free_bit(rep.free, j);
        }
    });
    return out;
}

//! ik_many_rows with one solver for every target.
template <class Solver>
BatchAnswer ik_many(const Solver& s, const km::Chain& chain, F64 Th,
                 const km::CheckOptions& opts, nb::handle q0h, nb::handle invalidh, int workers) {
    return ik_many_rows(s, chain, Th, q0h, invalidh, workers,
                        [&s, &opts](npy_intp, const km::ChainView& ch, const km::Pose& P,
                                    const double* q0, km::IKWork<Solver>& work,
                                    const km::CheckOut& o) {
                            return solve_checked(s, ch, P, opts, q0, work, o);
                        });
}

//! (Q (m, n), singular, near, gap, free mask): the solver's raw candidates of one target.
template <class Solver>
nb::tuple candidates(const Solver& s, const km::Chain& chain, F64 T, nb::handle q0) {
    check_dims(s, chain);
    const km::ChainView ch = chain.view();
    const int n = ch.n, m = s.slots();
    const km::Pose P = target_pose(T);
    const In q0in = optional_q0(q0, n);
    const double* q0p = q0in.data;
    double* Q;
    nb::object Qa = new_f64({m, n}, Q);
    km::IKWork<Solver>& work = thread_work(s, n);
    km::SolverInfo info;
    s.solve(ch, P, q0p, Q, info, work.solver);
    return nb::make_tuple(Qa, info.singular, info.near, info.gap, static_cast<unsigned long>(info.free));
}

//! ik, ik_batch and candidates on a solver class; `get` turns the bound object into a
//! Solver (a closed form's Params into ClosedForm<Params>).
template <class Bound, class Get>
void add_ik_methods(nb::class_<Bound>& cls, Get get) {
    cls.def("ik",
            [get](const Bound& b, const km::Chain& chain, F64 T, const km::CheckOptions& o,
                  nb::handle q0, nb::handle labels) { return ik_one(get(b), chain, T, o, q0, labels); },
            nb::arg("chain"), nb::arg("T"), nb::arg("options"), nb::arg("q0").none(),
            nb::arg("labels"),
            "Every solution of one target T (4, 4): an Answer.");
    cls.def("ik_batch",
            [get](const Bound& b, const km::Chain& chain, F64 T, const km::CheckOptions& o,
                  nb::handle q0, nb::handle invalid, int workers) {
                return ik_many(get(b), chain, T, o, q0, invalid, workers);
            },
            nb::arg("chain"), nb::arg("T"), nb::arg("options"), nb::arg("q0").none(),
            nb::arg("invalid").none(), nb::arg("workers"),
            "Every solution of each target T (N, 4, 4): a BatchAnswer.");
    cls.def(
        "prepare",
        [get](nb::handle_t<Bound> self, nb::handle_t<km::Chain> chain, const km::CheckOptions& o,
              double roundoff, nb::handle labels, nb::handle result, nb::handle fields,
              nb::handle statuses, std::uint32_t final_codes) {
            const Bound* b = &nb::cast<const Bound&>(self);
            const km::Chain* c = &nb::cast<const km::Chain&>(chain);
            check_dims(get(*b), *c);
            checked_labels(labels, get(*b).slots());
            Prepared p;
            p.fields = result_fields(result, fields, statuses);
            p.solve = [get, b, c, o, labels](const km::Pose& P, const double* q0) {
                return ik_pose(get(*b), *c, P, o, q0, labels);
            };
            p.rows = [get, b, c, o](const km::Pose& P, OneOut& buf) {
                return ik_rows(get(*b), c->view(), P, o, nullptr, buf);
            };
            p.labels = nb::borrow(labels);
            p.n = c->dof();
            p.chain = c;
            p.keep = nb::make_tuple(self, chain, labels);
            p.result = nb::borrow(result);
            p.statuses = nb::borrow(statuses);
            p.roundoff = roundoff;
            p.final_codes = final_codes;
            return p;
        },
        nb::arg("chain"), nb::arg("options"), nb::arg("roundoff"), nb::arg("labels"),
        nb::arg("result"), nb::arg("fields"), nb::arg("statuses"), nb::arg("final_codes"),
        "This solver made ready for one target at a time (a Prepared): the chain, options\n"
        "and labels held; an answer whose status s has bit s of final_codes set is given as\n"
        "`result` (a class) with `fields` (a dict) and the answer's attributes in its\n"
        "__dict__, its status statuses[code].");
    cls.def("candidates",
            [get](const Bound& b, const km::Chain& chain, F64 T, nb::handle q0) {
                return candidates(get(b), chain, T, q0);
            },
            nb::arg("chain"), nb::arg("T"), nb::arg("q0").none() = nb::none(),
            "The raw candidates (m, n) of one target and what the solver says of it.");
    cls.def_prop_ro("slots", [get](const Bound& b) { return get(b).slots(); });
}

//! Params with `const char* invalid() const` (nullptr when fine) say so before each call.
template <class P, class = void>
struct has_invalid : std::false_type {};
template <class P>
struct has_invalid<P, std::void_t<decltype(std::declval<const P&>().invalid())>>
    : std::true_type {};

//! p, after its own check (if it has one): a ValueError, not a bad index in the core.
template <class Params>
const Params& checked(const Params& p) {
    if constexpr (has_invalid<Params>::value) {
        if (const char* why = p.invalid()) throw nb::value_error(why);
    }
    return p;
}

//! A closed form's Params class with its IK methods, opaque to Python (no constructor, no
//! fields): its values come from the core's builder.
template <class Params>
nb::class_<Params> bind_params(nb::module_& m, const char* name, const char* doc,
                               const char* cpp_type, const char* cpp_header) {
    nb::class_<Params> cls(m, name, doc);
    // for code that builds the same struct in C++ (kinematica convert ROBOT --to cpp)
    cls.attr("cpp_type") = cpp_type;
    cls.attr("cpp_header") = cpp_header;
    add_ik_methods(cls, [](const Params& p) { return km::ClosedForm<Params>{checked(p)}; });
    return cls;
}

//! A closed-form family built in C++, registered by one call: its opaque Params class
//! (bind_params) and `<build_name>(chain) -> Params | None` in module m, where `build` is
//! the family's builder (`std::optional<Params>(const km::Chain&)`, named cpp_build in C++:
//! the C++ export calls it); with `position`, its builder for position targets of the tool
//! origin too, as `build_position(chain) -> Params | None`.
template <class Params, class Build, class Position = std::nullptr_t>
nb::class_<Params> bind_family(nb::module_& m, const char* name, const char* doc,
                               const char* cpp_header, const char* cpp_type,
                               const char* cpp_build, Build build,
                               const char* build_name = "build", Position position = nullptr) {
    nb::class_<Params> cls = bind_params<Params>(m, name, doc, cpp_type, cpp_header);
    cls.attr("cpp_build") = cpp_build;
    m.def(
        build_name,
        [build](const km::Chain& chain) -> std::optional<Params> { return build(chain); },
        nb::arg("chain"),
        "The family's closed form of a chain (the C++ builder its Params' cpp_build names), "
        "or None where the family declines the arm.");
    if constexpr (!std::is_same_v<Position, std::nullptr_t>) {
        m.def("build_position", [position](const km::Chain& chain) { return position(chain); },
              nb::arg("chain"), "The same for position targets (the tool origin), or None.");
    }
    return cls;
}

}  // namespace kmpy
