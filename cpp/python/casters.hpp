// Conversions of the core's small value types: Vec3 <-> a sequence of 3 numbers (out: a
// (3,) array), Pose <-> a (4, 4) (or 3 x 4) array or nested sequence (out: (4, 4)).
#pragma once

#include <nanobind/nanobind.h>

#include "kinematica/types.hpp"
#include "numpy_io.hpp"

namespace kmpy {

//! v into out[0 .. 3); returns out + 3.
inline double* put(const km::Vec3& v, double* out) {
    out[0] = v.x;
    out[1] = v.y;
    out[2] = v.z;
    return out + 3;
}

}  // namespace kmpy

namespace kmpy::detail {

//! Fill out[count] from a sequence of numbers; false (no Python error set) otherwise.
inline bool read_numbers(PyObject* src, double* out, Py_ssize_t count) {
    PyObject* seq = PySequence_Fast(src, "");
    if (seq == nullptr) {
        PyErr_Clear();
        return false;
    }
    bool ok = PySequence_Fast_GET_SIZE(seq) == count;
    for (Py_ssize_t i = 0; ok && i < count; ++i) {
        const double v = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(seq, i));
        if (v == -1.0 && PyErr_Occurred() != nullptr) {
            PyErr_Clear();
            ok = false;
        }
        out[i] = v;
    }
    Py_DECREF(seq);
    return ok;
}

}  // namespace kmpy::detail

namespace nanobind::detail {

template <>
struct type_caster<km::Vec3> {
    NB_TYPE_CASTER(km::Vec3, const_name("numpy.typing.NDArray[numpy.float64]"))

    bool from_python(handle src, uint8_t, cleanup_list*) noexcept {
        double v[3];
        if (!kmpy::detail::read_numbers(src.ptr(), v, 3)) return false;
        value = {v[0], v[1], v[2]};
        return true;
    }

    static handle from_cpp(const km::Vec3& v, rv_policy, cleanup_list*) noexcept {
        npy_intp d[1] = {3};
        PyObject* r = PyArray_SimpleNew(1, d, NPY_DOUBLE);
        if (r == nullptr) return handle();
        kmpy::put(v, static_cast<double*>(PyArray_DATA(reinterpret_cast<PyArrayObject*>(r))));
        return r;
    }
};

template <>
struct type_caster<km::Pose> {
    NB_TYPE_CASTER(km::Pose, const_name("numpy.typing.NDArray[numpy.float64]"))

    bool from_python(handle src, uint8_t, cleanup_list*) noexcept {
        PyObject* seq = PySequence_Fast(src.ptr(), "");
        if (seq == nullptr) {
            PyErr_Clear();
            return false;
        }
        const Py_ssize_t rows = PySequence_Fast_GET_SIZE(seq);
        double T[16] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
        bool ok = rows == 4 || rows == 3;
        for (Py_ssize_t i = 0; ok && i < 3; ++i) {
            ok = kmpy::detail::read_numbers(PySequence_Fast_GET_ITEM(seq, i), T + 4 * i, 4);
        }
        Py_DECREF(seq);
        if (ok) value = km::Pose::from_rows(T);
        return ok;
    }

    static handle from_cpp(const km::Pose& P, rv_policy, cleanup_list*) noexcept {
        npy_intp d[2] = {4, 4};
        PyObject* r = PyArray_SimpleNew(2, d, NPY_DOUBLE);
        if (r == nullptr) return handle();
        P.to_rows(static_cast<double*>(PyArray_DATA(reinterpret_cast<PyArrayObject*>(r))));
        return r;
    }
};

}  // namespace nanobind::detail
