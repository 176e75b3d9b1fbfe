// Fixed-size array fields of the families' Params as the test hooks read and write them
// (cpp/testing/):
// read as a new numpy array, written from any array or nested sequence of exactly that
// shape (a ValueError otherwise: a wrong size never reaches the core).
#pragma once

#include <nanobind/nanobind.h>

#include <string>

#include "common.hpp"
#include "numpy_io.hpp"

namespace kmpy::small {

//! src as a C-contiguous array of typenum with exactly `rows` x `cols` entries
//! (cols 0: a vector of `rows`); the caller owns the reference.
inline PyArrayObject* exact_array(nb::handle src, const char* name, int typenum, npy_intp rows,
                                  npy_intp cols) {
    PyObject* a = PyArray_FromAny(src.ptr(), PyArray_DescrFromType(typenum), 0, 0,
                                  NPY_ARRAY_CARRAY, nullptr);
    if (a == nullptr) throw nb::python_error();
    auto* arr = reinterpret_cast<PyArrayObject*>(a);
    const int nd = cols == 0 ? 1 : 2;
    bool ok = PyArray_NDIM(arr) == nd && PyArray_DIM(arr, 0) == rows;
    if (ok && nd == 2) ok = PyArray_DIM(arr, 1) == cols;
    if (!ok) {
        Py_DECREF(a);
        const std::string shape = cols == 0 ? "(" + std::to_string(rows) + ",)"
                                            : "(" + std::to_string(rows) + ", " +
                                                  std::to_string(cols) + ")";
        throw nb::value_error((std::string(name) + " must have shape " + shape).c_str());
    }
    return arr;
}

//! A (k,) float field.
template <int K>
F64 get_vec(const double (&v)[K]) {
    double* out;
    F64 a = new_f64({K}, out);
    for (int i = 0; i < K; ++i) out[i] = v[i];
    return a;
}

template <int K>
void set_vec(double (&v)[K], nb::handle src, const char* name) {
    PyArrayObject* a = exact_array(src, name, NPY_DOUBLE, K, 0);
    const auto* d = static_cast<const double*>(PyArray_DATA(a));
    for (int i = 0; i < K; ++i) v[i] = d[i];
    Py_DECREF(a);
}

//! A (k, 2) float field.
template <int K>
F64 get_pairs(const double (&v)[K][2]) {
    double* out;
    F64 a = new_f64({K, 2}, out);
    for (int i = 0; i < K; ++i) {
        out[2 * i] = v[i][0];
        out[2 * i + 1] = v[i][1];
    }
    return a;
}

template <int K>
void set_pairs(double (&v)[K][2], nb::handle src, const char* name) {
    PyArrayObject* a = exact_array(src, name, NPY_DOUBLE, K, 2);
    const auto* d = static_cast<const double*>(PyArray_DATA(a));
    for (int i = 0; i < K; ++i) {
        v[i][0] = d[2 * i];
        v[i][1] = d[2 * i + 1];
    }
    Py_DECREF(a);
}

//! A (k,) int field (int64 on the Python side).
template <int K>
I64 get_ints(const int (&v)[K]) {
    npy_int64* out;
    I64 a = new_i64({K}, out);
    for (int i = 0; i < K; ++i) out[i] = v[i];
    return a;
}

template <int K>
void set_ints(int (&v)[K], nb::handle src, const char* name, int lo, int hi) {
    PyArrayObject* a = exact_array(src, name, NPY_INT64, K, 0);
    const auto* d = static_cast<const npy_int64*>(PyArray_DATA(a));
    for (int i = 0; i < K; ++i) {
        if (d[i] < lo || d[i] > hi) {
            Py_DECREF(a);
            throw nb::value_error((std::string(name) + " entries must be in [" +
                                   std::to_string(lo) + ", " + std::to_string(hi) + "]")
                                      .c_str());
        }
    }
    for (int i = 0; i < K; ++i) v[i] = static_cast<int>(d[i]);
    Py_DECREF(a);
}

}  // namespace kmpy::small

//! .def_prop_rw of a fixed float array field F of class C: (k,) or (k, 2).
#define KM_SMALL_VEC(cls, C, F, doc)                                                           \
    cls.def_prop_rw(                                                                          \
        #F, [](const C& p) { return ::kmpy::small::get_vec(p.F); },                           \
        [](C& p, ::kmpy::F64 v) { ::kmpy::small::set_vec(p.F, v, #F); }, doc)
#define KM_SMALL_PAIRS(cls, C, F, doc)                                                         \
    cls.def_prop_rw(                                                                          \
        #F, [](const C& p) { return ::kmpy::small::get_pairs(p.F); },                         \
        [](C& p, ::kmpy::F64 v) { ::kmpy::small::set_pairs(p.F, v, #F); }, doc)
