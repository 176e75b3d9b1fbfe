// Time-optimal timing of a joint path (topp.hpp) for kinematica.motion.optimal: one path per
// call, every array checked here before the core sees it.
#include <string>
#include <vector>

#include "common.hpp"
#include "interrupt.hpp"
#include "kinematica/topp.hpp"
#include "numpy_io.hpp"

namespace kmpy {

namespace {

namespace kt = km::topp;

nb::tuple time_optimal(F64 s, F64 coef, F64 vlo, F64 vhi, F64 alo, F64 ahi, F64 cap, double x_start,
                       double x_end, double x_max, bool sets) {
    const In S = in_f64(s, "s", 1);
    const npy_intp N = S.dim[0] - 1;
    if (N < 1) fail_value("s", "at least 2 grid points");
    const In C = in_f64(coef, "coef", 3, {N, -1, -1});
    const npy_intp n = C.dim[2];
    const int degree = static_cast<int>(C.dim[1]) - 1;
    if (n < 1) fail_value("coef", "of at least one joint");
    if (degree < 1 || degree > kt::MAX_DEGREE) {
        fail_value("coef", "of degree 1 to " + std::to_string(kt::MAX_DEGREE) + " (axis 1 of size 2 to 6)");
    }
    const In VL = in_f64(vlo, "vlo", 1, {n}), VH = in_f64(vhi, "vhi", 1, {n});
    const In AL = in_f64(alo, "alo", 1, {n}), AH = in_f64(ahi, "ahi", 1, {n});
    const In CP = in_f64(cap, "cap", 1, {N});
    // Problem's fields in their order: n, N, degree, the arrays s, coef, vlo, vhi, alo, ahi, cap
    const kt::Problem P{static_cast<int>(n), static_cast<int>(N), degree, S.data, C.data, VL.data,
                        VH.data, AL.data, AH.data, CP.data, x_start, x_end, x_max};
    if (const char* why = P.invalid()) throw nb::value_error(why);
    const npy_intp M = N + 1;
    double* x;
    F64 X = new_f64({6, M}, x);  // rows x, k_lo, k_hi, r_lo, r_hi, mvc: Output's arrays in order
    kt::Output out{x, x + M, x + 2 * M, x + 3 * M, x + 4 * M, x + 5 * M};
    {
        nb::gil_scoped_release release;
        kt::Workspace ws;
        SignalPoll interrupted;
        kt::time_optimal(P, out, ws, sets, std::ref(interrupted));
    }
    if (out.status == kt::Status::interrupted) throw nb::python_error();
    return nb::make_tuple(static_cast<int>(out.status), out.stage, static_cast<int>(out.kind), out.joint, X);
}

}  // namespace

void bind_topp(nb::module_& m) {
    m.def("time_optimal", &time_optimal, nb::arg("s"), nb::arg("coef"), nb::arg("vlo"), nb::arg("vhi"),
          nb::arg("alo"), nb::arg("ahi"), nb::arg("cap"), nb::arg("x_start"), nb::arg("x_end"),
          nb::arg("x_max"), nb::arg("sets") = true,
          "TOPP-RA on a grid s (N+1,): (status, stage, kind, joint, rows x, k_lo, k_hi, r_lo, r_hi, "
          "mvc (6, N+1)).");
    m.attr("TOPP_MAX_DEGREE") = kt::MAX_DEGREE;
}

}  // namespace kmpy
