// The arms decoupled at joint 3: joints 1-3 placing a point (ArmPoint), the spherical
// wrist's poses (and the spherical shoulder's, by the reversed chain) and the arm-position
// solver's position targets, bound into the submodule kinematica._core.decoupled (the
// family's tolerances and scalar internals: kinematica._core_testing.decoupled).
#include <cstddef>
#include <initializer_list>
#include <string>

#include "casters.hpp"
#include "common.hpp"
#include "kinematica/solvers/arm_point.hpp"
#include "kinematica/solvers/arm_position.hpp"
#include "kinematica/solvers/arm_position_build.hpp"
#include "kinematica/solvers/arm_quartic.hpp"
#include "kinematica/solvers/spherical_shoulder.hpp"
#include "kinematica/solvers/spherical_wrist.hpp"
#include "kinematica/solvers/spherical_wrist_build.hpp"
#include "kinematica/solvers/spherical_shoulder_build.hpp"
#include "numpy_io.hpp"
#include "solver_binding.hpp"

namespace kmpy {

namespace {

namespace kd = km::decoupled;

//! h (any array or sequence of numbers) as float64 of exactly `shape`, copied into out.
void read_fixed(nb::handle h, const char* name, std::initializer_list<npy_intp> shape,
                double* out) {
    PyObject* arr = PyArray_FROM_OTF(h.ptr(), NPY_DOUBLE, NPY_ARRAY_IN_ARRAY);
    if (arr == nullptr) throw nb::python_error();
    const nb::object owner = nb::steal(arr);
    auto* a = reinterpret_cast<PyArrayObject*>(arr);
    std::string want;
    bool ok = PyArray_NDIM(a) == static_cast<int>(shape.size());
    int i = 0;
    for (const npy_intp d : shape) {
        want += (i == 0 ? "(" : ", ") + std::to_string(d);
        ok = ok && PyArray_DIM(a, i) == d;
        ++i;
    }
    want += shape.size() == 1 ? ",)" : ")";
    if (!ok) fail_value(name, "of shape " + want);
    const auto* src = static_cast<const double*>(PyArray_DATA(a));
    const npy_intp size = PyArray_SIZE(a);
    for (npy_intp k = 0; k < size; ++k) out[k] = src[k];
}

//! A new (n,) float64 array holding data.
F64 write_vector(npy_intp n, const double* data) {
    double* out;
    F64 a = new_f64({n}, out);
    for (npy_intp k = 0; k < n; ++k) out[k] = data[k];
    return a;
}

//! A new (r, c) float64 array holding data (row-major).
F64 write_matrix(npy_intp r, npy_intp c, const double* data) {
    double* out;
    F64 a = new_f64({r, c}, out);
    for (npy_intp k = 0; k < r * c; ++k) out[k] = data[k];
    return a;
}

//! A read-write property of a member double[N]: a (N,) array out, any (N,) sequence in.
template <class C, size_t N>
void vector_prop(nb::class_<C>& cls, const char* name, double (C::*member)[N], const char* doc) {
    constexpr npy_intp n = static_cast<npy_intp>(N);
    cls.def_prop_rw(
        name, [member](const C& c) { return write_vector(n, c.*member); },
        [member, name](C& c, F64 h) { read_fixed(h, name, {n}, c.*member); }, doc);
}

//! A read-write property of a member double[R][K]: a (R, K) array out and in.
template <class C, size_t R, size_t K>
void matrix_prop(nb::class_<C>& cls, const char* name, double (C::*member)[R][K],
                 const char* doc) {
    constexpr npy_intp r = static_cast<npy_intp>(R), k = static_cast<npy_intp>(K);
    cls.def_prop_rw(
        name, [member](const C& c) { return write_matrix(r, k, &(c.*member)[0][0]); },
        [member, name](C& c, F64 h) {
            double tmp[R * K];  // the member is written only once the shape is right
            read_fixed(h, name, {r, k}, tmp);
            for (size_t i = 0; i < R * K; ++i) (c.*member)[i / K][i % K] = tmp[i];
        },
        doc);
}

//! (Q3 (4, 3), free (3,) bool, near, gap, rho, azimuth): ArmPoint::place of one point.
nb::tuple place(const kd::ArmPoint& arm, const km::Vec3& ct) {
    double Q3[4][3];
    kd::ArmState st;
    arm.place(ct, Q3, st);
    F64 Q = write_matrix(4, 3, &Q3[0][0]);
    npy_bool* f;
    Bools F = new_bools({3}, f);
    for (int i = 0; i < 3; ++i) f[i] = st.free[i];
    return nb::make_tuple(Q, F, st.near, st.gap, st.rho, st.azimuth);
}

}  // namespace

void bind_decoupled(nb::module_& m) {
    nb::module_ sub = m.def_submodule(
        "decoupled",
        "Arms decoupled at joint 3: spherical-wrist 6R and RRP arms, and position targets of "
        "longer arms (joints 1-3 place a point).");

    nb::enum_<kd::Shoulder>(sub, "Shoulder", "The geometry of axes 1 and 2.")
        .value("meet", kd::Shoulder::meet)
        .value("parallel", kd::Shoulder::parallel)
        .value("general", kd::Shoulder::general);

    nb::class_<kd::ArmPoint> arm(sub, "ArmPoint",
                                 "Joints 1-3 placing a point fixed after joint 3 (arm_point.hpp).");
    arm.def(nb::init<>())
        .def_rw("kind", &kd::ArmPoint::kind)
        .def_rw("prismatic", &kd::ArmPoint::prismatic, "joint 3 slides")
        .def_rw("parallel23", &kd::ArmPoint::parallel23, "axes 2 and 3 parallel")
        .def_rw("p1", &kd::ArmPoint::p1, "foot point of axis 1 (m, base frame)")
        .def_rw("h1", &kd::ArmPoint::h1, "axis 1 direction")
        .def_rw("h2", &kd::ArmPoint::h2, "axis 2 direction")
        .def_rw("h3", &kd::ArmPoint::h3, "axis 3 direction")
        .def_rw("a1", &kd::ArmPoint::a1, "a unit vector normal to h1")
        .def_rw("b1", &kd::ArmPoint::b1, "h1 x a1")
        .def_rw("a", &kd::ArmPoint::a, "distance of axes 1 and 2 along e1 (m, signed)")
        .def_rw("ca", &kd::ArmPoint::ca, "cos alpha = h1 . h2")
        .def_rw("g", &kd::ArmPoint::g, "h1 . e2")
        .def_rw("elbow", &kd::ArmPoint::elbow, "sign deciding elbow up (axes 2 and 3 parallel)")
        .def_rw("scale", &kd::ArmPoint::scale, "a length of the arm's size (m)")
        .def_rw("r_lo", &kd::ArmPoint::r_lo, "lower bound of |x - p1| (m)")
        .def_rw("r_hi", &kd::ArmPoint::r_hi, "upper bound of |x - p1| (m)")
        .def_rw("z_lo", &kd::ArmPoint::z_lo, "lower bound of h1 . (x - p1) (m)")
        .def_rw("z_hi", &kd::ArmPoint::z_hi, "upper bound of h1 . (x - p1) (m)")
        .def_rw("beta", &kd::ArmPoint::beta, "revolute joint 3: |u| is extreme at q3 = beta, beta + pi")
        .def_rw("dmin", &kd::ArmPoint::dmin, "revolute joint 3: min |u(q3)| (m)")
        .def_rw("dmax", &kd::ArmPoint::dmax, "revolute joint 3: max |u(q3)| (m)")
        .def_rw("b3", &kd::ArmPoint::b3, "slide: U0 . h3 (m)")
        .def_rw("m3", &kd::ArmPoint::m3, "slide: distance of axis 3 from p2 (m)")
        .def_rw("refine", &kd::ArmPoint::refine, "a second pass for nearly meeting or parallel axes");
    matrix_prop(arm, "xframe", &kd::ArmPoint::xframe,
               "(4, 2) components along a1, b1 of h2, e1, e2 and p2 - p1");
    vector_prop(arm, "u1", &kd::ArmPoint::u1, "(3,) u1(q3) on (1, cos q3, sin q3) or (1, q3, q3^2)");
    vector_prop(arm, "u2", &kd::ArmPoint::u2, "(3,) u2(q3), likewise");
    vector_prop(arm, "H", &kd::ArmPoint::H, "(3,) H(q3) = h2 . u, likewise");
    vector_prop(arm, "L", &kd::ArmPoint::L, "(3,) L(q3) = |u|^2, likewise");
    matrix_prop(arm, "fourier", &kd::ArmPoint::fourier,
               "(5, 5) rows turn [X0^2, X0, Y0^2, Y0, 1] into the Fourier coefficients of F");
    arm.def_prop_rw(
        "upper_root",
        [](const kd::ArmPoint& p) {
            npy_bool* b;
            Bools a = new_bools({2, 2}, b);
            for (int i = 0; i < 4; ++i) b[i] = p.upper_root[i / 2][i % 2];
            return a;
        },
        [](kd::ArmPoint& p, Bools h) {
            double v[4];
            read_fixed(h, "upper_root", {2, 2}, v);
            for (int i = 0; i < 4; ++i) p.upper_root[i / 2][i % 2] = v[i] != 0.0;
        },
        "(2, 2) bool: slot 2A + B of a meeting shoulder takes the upper root");
    arm.def("place", &place, nb::arg("ct"),
            "(Q3 (4, 3), free (3,), near, gap, rho, azimuth): every (q1, q2, q3) putting the "
            "point at ct (3,).");
    arm.def("shell_gap", &kd::ArmPoint::shell_gap, nb::arg("r"), nb::arg("zeta"),
            "Distance (m) of a target at |d| = r, h1 . d = zeta outside the reachable shell.");
    arm.def(
        "values",
        [](const kd::ArmPoint& p, double q3) {
            const kd::ArmValues v = p.values(q3);
            return nb::make_tuple(v.u1, v.u2, v.H, v.L);
        },
        nb::arg("q3"), "(u1, u2, H, L) at q3 (rad, or m for a slide).");

    bind_family<kd::SphericalWristParams>(
        sub, "SphericalWristParams",
        "A 6R or RRP arm with a spherical wrist (spherical_wrist.hpp): 8 slots, 6 joints.",
        "kinematica/solvers/spherical_wrist_build.hpp", "km::decoupled::SphericalWristParams",
        "km::decoupled::build", [](const km::Chain& c) { return kd::build(c); },
        "build_spherical_wrist")
        .def_ro("arm", &kd::SphericalWristParams::arm, "joints 1-3 placing the wrist centre");
    bind_family<kd::SphericalShoulderParams>(
        sub, "SphericalShoulderParams",
        "A 6R or RRRPRR arm with a spherical shoulder (spherical_shoulder.hpp): the reversed "
        "chain's spherical wrist, 8 slots, 6 joints.",
        "kinematica/solvers/spherical_shoulder_build.hpp",
        "km::decoupled::SphericalShoulderParams", "km::decoupled::build_shoulder",
        [](const km::Chain& c) { return kd::build_shoulder(c); }, "build_spherical_shoulder")
        .def_ro("wrist", &kd::SphericalShoulderParams::wrist,
                "the reversed chain's SphericalWristParams (its joint j is -q_(7-j))");

    sub.attr("PLACE_RANK_TOL") = kd::PLACE_RANK_TOL;
    sub.attr("PLACE_PROBES") = nb::make_tuple(
        nb::make_tuple(kd::PLACE_PROBES[0][0], kd::PLACE_PROBES[0][1], kd::PLACE_PROBES[0][2]),
        nb::make_tuple(kd::PLACE_PROBES[1][0], kd::PLACE_PROBES[1][1], kd::PLACE_PROBES[1][2]),
        nb::make_tuple(kd::PLACE_PROBES[2][0], kd::PLACE_PROBES[2][1], kd::PLACE_PROBES[2][2]));

    bind_family<kd::ArmPositionParams>(
        sub, "ArmPositionParams",
        "Position targets of an arm of n > 3 joints (arm_position.hpp): 4 slots, n joints.",
        "kinematica/solvers/arm_position_build.hpp", "km::decoupled::ArmPositionParams",
        "km::decoupled::build_position", [](const km::Chain& c) { return kd::build_position(c); },
        "build_arm_position")
        .def_ro("arm", &kd::ArmPositionParams::arm, "joints 1-3 placing the tool origin");

    sub.attr("MAX_POSITION_DOF") = kd::MAX_POSITION_DOF;
}

}  // namespace kmpy
