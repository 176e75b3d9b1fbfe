// What kinematica.spatial computes through the core: wrap, the SO(3) log, the angle
// between rotations, the pose error (one source each, shared with the solvers). Each
// batch checks its arrays and makes its result with the GIL held, then runs its rows
// through run_rows: the GIL released, Ctrl-C read between blocks.
#include "casters.hpp"
#include "common.hpp"
#include "interrupt.hpp"
#include "kinematica/so3.hpp"

namespace kmpy {

namespace {

//! Angles per block of wrap (one takes 5-30 ns): a block of about 0.1 ms at most.
constexpr long ANGLE_BLOCK = 4096;

F64 wrap_many(F64 a) {
    const In in = in_f64(a, "angle", 1);
    double* out;
    F64 r = new_f64({in.dim[0]}, out);
    run_rows(in.dim[0], ANGLE_BLOCK, 1, [&](long i0, long i1) {
        for (long i = i0; i < i1; ++i) out[i] = km::wrap(in.data[i]);
    });
    return r;
}

nb::tuple so3_log(F64 R) {
    const In in = in_f64(R, "R", 3, {-1, 3, 3});
    double *v, *angle;
    nb::object V = new_f64({in.dim[0], 3}, v), A = new_f64({in.dim[0]}, angle);
    run_rows(in.dim[0], FK_BLOCK, 1, [&](long i0, long i1) {
        for (long i = i0; i < i1; ++i) {
            const double* m = in.data + 9 * i;
            put(km::rotvec(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], angle[i]), v + 3 * i);
        }
    });
    return nb::make_tuple(V, A);
}

km::Pose rotation_pose(const double* m) {
    const double T[12] = {m[0], m[1], m[2], 0.0, m[3], m[4], m[5], 0.0, m[6], m[7], m[8], 0.0};
    return km::Pose::from_rows(T);
}

F64 angles_between(F64 Ra, F64 Rb) {
    const In a = in_f64(Ra, "R_a", 3, {-1, 3, 3});
    const In b = in_f64(Rb, "R_b", 3, {a.dim[0], 3, 3});
    double* out;
    F64 r = new_f64({a.dim[0]}, out);
    run_rows(a.dim[0], FK_BLOCK, 1, [&](long i0, long i1) {
        for (long i = i0; i < i1; ++i) {
            // the angle of R_aᵀ R_b: angle_between(T, Tt) is that of Rtᵀ R
            out[i] = km::angle_between(rotation_pose(b.data + 9 * i), rotation_pose(a.data + 9 * i));
        }
    });
    return r;
}

F64 pose_errors(F64 Tc, F64 Tt) {
    const In c = in_f64(Tc, "T_current", 3, {-1, 4, 4});
    const In t = in_f64(Tt, "T_target", 3, {c.dim[0], 4, 4});
    double* out;
    F64 r = new_f64({c.dim[0], 6}, out);
    run_rows(c.dim[0], FK_BLOCK, 1, [&](long i0, long i1) {
        for (long i = i0; i < i1; ++i) {
            const km::Twist e =
                km::pose_error(km::Pose::from_rows(c.data + 16 * i), km::Pose::from_rows(t.data + 16 * i));
            for (int k = 0; k < 6; ++k) out[6 * i + k] = e.e[k];
        }
    });
    return r;
}

}  // namespace

void bind_spatial(nb::module_& m) {
    m.def("wrap", &wrap_many, nb::arg("angle"), "Angles (N,) wrapped to (-π, π].");
    m.def("so3_log", &so3_log, nb::arg("R"), "(rotation vectors (N, 3), angles (N,)) of R (N, 3, 3).");
    m.def("rotation_angles", &angles_between, nb::arg("R_a"), nb::arg("R_b"),
          "The angle (N,) of R_aᵀ R_b for R_a, R_b (N, 3, 3).");
    m.def("pose_errors", &pose_errors, nb::arg("T_current"), nb::arg("T_target"),
          "(N, 6): p_target − p_current, then the rotation vector of R_target R_currentᵀ.");
}

}  // namespace kmpy
