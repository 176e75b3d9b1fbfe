// What the core's check answers, as Python reads it: typed, read-only objects.
//
// Answer        one target: solutions (count, n), residuals (count, 2), the solutions
//               outside the limits (out, n), the branch label of each, and the check's
//               report (status, gap, nearest miss, near, free joints), by name.
// BatchAnswer   N targets: the check's arrays over the flat targets (q (N, m, n), slot,
//               res, status, count, out_count, gap, nearest, near, free), by name.
// Answer::result builds the ik layer's result object (kinematica.ik.IKResult) of one
// target in one step: its fields are the answer's attributes, by the same names, and
// the caller's (method, notes...). Every array is read-only.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/stl/optional.h>

#include <cstdint>
#include <optional>
#include <string>

#include "kinematica/ik_types.hpp"
#include "numpy_io.hpp"

namespace kmpy {

//! One target's answer.
struct Answer {
    F64 solutions;                     //!< (count, n) within the limits (all, limits ignored)
    F64 residuals;                     //!< (count, 2) position (m), rotation (rad) errors
    F64 out_of_limits;                 //!< (out, n) solutions outside the limits
    nb::tuple branches;                //!< (count,) the branch labels
    nb::tuple out_of_limits_branches;  //!< (out,)
    km::CheckReport report;
    int n = 0;

    //! The free joints (0-based), with the status singular only.
    nb::tuple free_joints() const {
        const bool singular = report.status == km::Status::singular;
        int nfree = 0;
        for (int j = 0; singular && j < n; ++j) nfree += static_cast<int>(km::free_bit(report.free, j));
        nb::object t = nb::steal(PyTuple_New(nfree));
        for (int j = 0, k = 0; singular && j < n; ++j) {
            if (km::free_bit(report.free, j)) PyTuple_SET_ITEM(t.ptr(), k++, PyLong_FromLong(j));
        }
        return nb::borrow<nb::tuple>(t);
    }
    //! The proven gap (m) of an unreachable target, else None.
    std::optional<double> gap() const {
        return report.gap == report.gap ? std::optional<double>(report.gap) : std::nullopt;
    }
    nb::tuple nearest_error() const {
        return nb::make_tuple(report.nearest_position, report.nearest_rotation);
    }
};

//! The names of the answer's attributes in a result's __dict__, interned once (the class's
//! attribute names are interned too: a look-up compares pointers).
enum Key { SOLUTIONS, STATUS, RESIDUALS, BRANCHES, OUT, OUT_BRANCHES, FREE, GAP, NEAREST, NEAR, KEYS };
inline PyObject* key(Key k) {
    static PyObject* const* keys = [] {
        static PyObject* made[KEYS];
        const char* names[KEYS] = {"solutions", "status", "residuals", "branches", "out_of_limits",
                                   "out_of_limits_branches", "free_joints", "gap",
                                   "nearest_error", "near_singular"};
        for (int i = 0; i < KEYS; ++i) made[i] = PyUnicode_InternFromString(names[i]);
        return made;
    }();
    return keys[k];
}

//! The (cls, fields, statuses) a result of one target is made with, checked: cls a class
//! whose instances have a __dict__, fields a dict, statuses a tuple of one object per
//! status code. Returns the fields with every attribute of an answer added (None), so
//! that each result's __dict__ is a copy of them, its values replaced.
inline nb::dict result_fields(nb::handle cls, nb::handle fields, nb::handle statuses) {
    if (!PyType_Check(cls.ptr()) ||
        reinterpret_cast<PyTypeObject*>(cls.ptr())->tp_dictoffset == 0) {
        throw nb::type_error("result must be a class whose instances have a __dict__");
    }
    if (!PyDict_Check(fields.ptr())) throw nb::type_error("fields must be a dict");
    if (!PyTuple_Check(statuses.ptr()) ||
        PyTuple_GET_SIZE(statuses.ptr()) <= static_cast<Py_ssize_t>(km::Status::invalid)) {
        throw nb::type_error("statuses must be a tuple of one object per status code");
    }
    nb::dict all = nb::steal<nb::dict>(PyDict_Copy(fields.ptr()));
    for (int k = 0; k < KEYS; ++k) PyDict_SetItem(all.ptr(), key(static_cast<Key>(k)), Py_None);
    return all;
}

//! The answer of an arm locked at its joint `joint`, as the whole arm's: its solutions
//! (count, n + 1) with that joint's column at `value` put back, its free joints shifted
//! past it (kinematica.ik.stack.widen_result's, for one target).
inline Answer widened(const Answer& a, int joint, double value) {
    Answer w = a;
    const int n = a.n, m = n + 1;
    const auto widen = [&](const F64& from) {
        auto* arr = reinterpret_cast<PyArrayObject*>(from.ptr());
        const npy_intp rows = PyArray_DIM(arr, 0);
        const double* src = static_cast<const double*>(PyArray_DATA(arr));
        double* dst;
        F64 out = new_f64({rows, m}, dst);
        for (npy_intp r = 0; r < rows; ++r) {
            for (int j = 0, s = 0; j < m; ++j) dst[r * m + j] = j == joint ? value : src[r * n + s++];
        }
        return read_only(out);
    };
    w.solutions = widen(a.solutions);
    w.out_of_limits = widen(a.out_of_limits);
    const std::uint32_t below = joint >= 32 ? ~std::uint32_t{0} : (std::uint32_t{1} << joint) - 1U;
    w.report.free = (a.report.free & below) | ((a.report.free & ~below) << 1U);
    w.n = m;
    return w;
}

//! A new instance of cls (no __init__ run) whose __dict__ is a copy of `fields` (made by
//! result_fields) holding the answer's attributes by their names, its status the object
//! statuses[code]; `parameter`, when given, its parameter (a joint held: (name, value)).
inline nb::object make_result(const Answer& a, nb::handle cls, nb::handle fields,
                              nb::handle statuses, nb::handle parameter = nb::handle()) {
    auto* type = reinterpret_cast<PyTypeObject*>(cls.ptr());
    nb::object obj = nb::steal(type->tp_alloc(type, 0));
    nb::object d = nb::steal(PyDict_Copy(fields.ptr()));
    if (!obj.is_valid() || !d.is_valid()) throw nb::python_error();
    const auto put = [&d](Key k, nb::handle v) { PyDict_SetItem(d.ptr(), key(k), v.ptr()); };
    put(SOLUTIONS, a.solutions);
    put(STATUS, PyTuple_GET_ITEM(statuses.ptr(), static_cast<int>(a.report.status)));
    put(RESIDUALS, a.residuals);
    put(BRANCHES, a.branches);
    put(OUT, a.out_of_limits);
    put(OUT_BRANCHES, a.out_of_limits_branches);
    put(FREE, a.free_joints());
    put(GAP, nb::cast(a.gap()));
    put(NEAREST, a.nearest_error());
    put(NEAR, a.report.near ? Py_True : Py_False);
    if (parameter.is_valid()) {
        static PyObject* const name = PyUnicode_InternFromString("parameter");
        PyDict_SetItem(d.ptr(), name, parameter.ptr());
    }
    if (PyObject_GenericSetDict(obj.ptr(), d.ptr(), nullptr) != 0) throw nb::python_error();
    return obj;
}

//! N targets' answers: the check's arrays over the flat targets.
struct BatchAnswer {
    F64 q;          //!< (N, m, n) solutions within the limits, then outside, NaN after
    I64 slot;       //!< (N, m) candidate slot (branch) of each row, -1 after
    F64 res;        //!< (N, m, 2) position, rotation residuals
    I64 status;     //!< (N,) status codes
    I64 count;      //!< (N,) solutions within the limits
    I64 out_count;  //!< (N,) solutions outside them
    F64 gap;        //!< (N,) the proven gap of unreachable targets (m), else NaN
    F64 nearest;    //!< (N, 2) the closest miss (m, rad)
    Bools near;     //!< (N,) the near flag
    Bools free;     //!< (N, n) free joints
};

//! a as a read-only array of dtype `type` and rank `ndim` whose first axis is N (N < 0:
//! any, then set), as BatchAnswer's constructor takes its arrays.
template <class A>
A batch_array(nb::handle a, const char* name, int type, int ndim, npy_intp& N) {
    PyObject* o = a.ptr();
    if (!PyArray_Check(o)) fail_type(name, "a numpy array");
    auto* arr = reinterpret_cast<PyArrayObject*>(o);
    if (PyArray_TYPE(arr) != type) fail_type(name, "of the dtype the core writes");
    if (PyArray_NDIM(arr) != ndim) fail_value(name, "of rank " + std::to_string(ndim));
    if (N < 0) N = PyArray_DIM(arr, 0);
    if (PyArray_DIM(arr, 0) != N) fail_value(name, "of " + std::to_string(N) + " rows");
    return read_only(nb::borrow<A>(a));
}

//! A BatchAnswer of arrays made in Python (a batch merged or stacked), checked.
inline BatchAnswer batch_answer(nb::handle q, nb::handle slot, nb::handle res, nb::handle status,
                                nb::handle count, nb::handle out_count, nb::handle gap,
                                nb::handle nearest, nb::handle near, nb::handle free) {
    npy_intp N = -1;
    BatchAnswer b;
    b.q = batch_array<F64>(q, "q", NPY_DOUBLE, 3, N);
    b.slot = batch_array<I64>(slot, "slot", NPY_INT64, 2, N);
    b.res = batch_array<F64>(res, "res", NPY_DOUBLE, 3, N);
    b.status = batch_array<I64>(status, "status", NPY_INT64, 1, N);
    b.count = batch_array<I64>(count, "count", NPY_INT64, 1, N);
    b.out_count = batch_array<I64>(out_count, "out_count", NPY_INT64, 1, N);
    b.gap = batch_array<F64>(gap, "gap", NPY_DOUBLE, 1, N);
    b.nearest = batch_array<F64>(nearest, "nearest", NPY_DOUBLE, 2, N);
    b.near = batch_array<Bools>(near, "near", NPY_BOOL, 1, N);
    b.free = batch_array<Bools>(free, "free", NPY_BOOL, 2, N);
    return b;
}

}  // namespace kmpy
