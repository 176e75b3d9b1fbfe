// Arrays across the binding, through NumPy's C API: checked inputs, new outputs.
//
// nanobind's ndarray caster serves any framework through DLPack and costs about 0.4 µs
// per array; a single FK or IK call moves two or three small arrays, so the hot paths
// read and make NumPy arrays directly (about 0.05 µs each), as eigenpy does for
// Pinocchio. Every input is checked here (type, dtype, shape) before any pointer reaches
// the core, and one laid out otherwise than the core reads (misaligned, strided, swapped) is
// copied: a wrong array is a TypeError or ValueError, never a crash.
#pragma once

#include <nanobind/nanobind.h>

#include <initializer_list>
#include <string>

#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#define PY_ARRAY_UNIQUE_SYMBOL kinematica_core_ARRAY_API
#ifndef KM_NUMPY_IMPORT
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

namespace kmpy {

namespace nb = nanobind;

//! Every object is let through to the checks below (which say what is wrong).
inline bool any_object(PyObject*) { return true; }

//! Arrays across the binding, named for the type stubs; the checks are in_f64 & co.
class F64 : public nb::object {
public:
    NB_OBJECT_DEFAULT(F64, nb::object, "numpy.typing.NDArray[numpy.float64]", any_object)
};
class I64 : public nb::object {
public:
    NB_OBJECT_DEFAULT(I64, nb::object, "numpy.typing.NDArray[numpy.int64]", any_object)
};
class Bools : public nb::object {
public:
    NB_OBJECT_DEFAULT(Bools, nb::object, "numpy.typing.NDArray[numpy.bool_]", any_object)
};

//! A checked float64 input array: C-contiguous, aligned, native byte order, of the given
//! rank. `data` points into the caller's array, or into `copy` (held as long as this In is)
//! when the caller's was not laid out so.
struct In {
    const double* data = nullptr;
    int ndim = 0;
    npy_intp dim[4] = {0, 0, 0, 0};
    nb::object copy;
    npy_intp size() const {
        npy_intp s = 1;
        for (int i = 0; i < ndim; ++i) s *= dim[i];
        return s;
    }
};

[[noreturn]] inline void fail_type(const char* name, const std::string& what) {
    throw nb::type_error((std::string(name) + " must be " + what).c_str());
}
[[noreturn]] inline void fail_value(const char* name, const std::string& what) {
    throw nb::value_error((std::string(name) + " must be " + what).c_str());
}

//! The dimensions of h, checked as in_f64 checks them (data not read, nothing copied).
inline In shape_f64(nb::handle h, const char* name, int ndim, std::initializer_list<npy_intp> tail = {}) {
    PyObject* o = h.ptr();
    if (!PyArray_Check(o)) fail_type(name, "a numpy array");
    auto* a = reinterpret_cast<PyArrayObject*>(o);
    if (PyArray_TYPE(a) != NPY_DOUBLE) fail_type(name, "of dtype float64");
    if (PyArray_NDIM(a) != ndim) fail_value(name, "of rank " + std::to_string(ndim));
    In in;
    in.ndim = ndim;
    for (int i = 0; i < ndim; ++i) in.dim[i] = PyArray_DIM(a, i);
    int i = ndim - static_cast<int>(tail.size());
    for (const npy_intp want : tail) {
        if (want >= 0 && in.dim[i] != want) {
            fail_value(name, "of size " + std::to_string(want) + " along axis " + std::to_string(i) +
                                 ", got " + std::to_string(in.dim[i]));
        }
        ++i;
    }
    return in;
}

//! h as a float64 array of rank ndim whose trailing dimensions are `tail` (-1: any). A
//! float64 array the core cannot read in place (a row of a packed record array, a buffer
//! read at an odd offset, strided, byte-swapped) is copied once, here, to one it can.
inline In in_f64(nb::handle h, const char* name, int ndim, std::initializer_list<npy_intp> tail = {}) {
    In in = shape_f64(h, name, ndim, tail);
    auto* a = reinterpret_cast<PyArrayObject*>(h.ptr());
    if (!PyArray_IS_C_CONTIGUOUS(a) || !PyArray_ISALIGNED(a) || !PyArray_ISNOTSWAPPED(a)) {
        // PyArray_FromArray steals the reference to the descriptor
        PyObject* c = PyArray_FromArray(a, PyArray_DescrFromType(NPY_DOUBLE),
                                        NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED);
        if (c == nullptr) throw nb::python_error();
        in.copy = nb::steal(c);
        a = reinterpret_cast<PyArrayObject*>(c);
    }
    in.data = static_cast<const double*>(PyArray_DATA(a));
    return in;
}

//! A checked bool (or uint8) input vector of length n, or nullptr for None.
inline const npy_bool* in_flags(nb::handle h, const char* name, npy_intp n) {
    if (h.is_none()) return nullptr;
    PyObject* o = h.ptr();
    if (!PyArray_Check(o)) fail_type(name, "a numpy array or None");
    auto* a = reinterpret_cast<PyArrayObject*>(o);
    if (PyArray_TYPE(a) != NPY_BOOL) fail_type(name, "of dtype bool");
    if (!PyArray_IS_C_CONTIGUOUS(a) || PyArray_NDIM(a) != 1 || PyArray_DIM(a, 0) != n) {
        fail_value(name, "a contiguous vector of length " + std::to_string(n));
    }
    return static_cast<const npy_bool*>(PyArray_DATA(a));
}

//! The array a made read-only (what it holds is the core's answer, not a buffer to fill).
template <class A>
A read_only(A a) {
    PyArray_CLEARFLAGS(reinterpret_cast<PyArrayObject*>(a.ptr()), NPY_ARRAY_WRITEABLE);
    return a;
}

//! A new array of the given dtype and shape (uninitialised), owned by the returned object.
template <class T>
inline nb::object new_array(std::initializer_list<npy_intp> dims, T*& data, int typenum) {
    npy_intp d[4];
    int nd = 0;
    for (const npy_intp v : dims) d[nd++] = v;
    PyObject* r = PyArray_SimpleNew(nd, d, typenum);
    if (r == nullptr) throw nb::python_error();
    data = static_cast<T*>(PyArray_DATA(reinterpret_cast<PyArrayObject*>(r)));
    return nb::steal(r);
}

inline F64 new_f64(std::initializer_list<npy_intp> dims, double*& data) {
    return nb::borrow<F64>(new_array(dims, data, NPY_DOUBLE));
}

inline I64 new_i64(std::initializer_list<npy_intp> dims, npy_int64*& data) {
    return nb::borrow<I64>(new_array(dims, data, NPY_INT64));
}

inline Bools new_bools(std::initializer_list<npy_intp> dims, npy_bool*& data) {
    return nb::borrow<Bools>(new_array(dims, data, NPY_BOOL));
}

}  // namespace kmpy
