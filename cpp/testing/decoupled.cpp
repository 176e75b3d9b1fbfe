// The decoupled families' built values and internals the tests pin
// (kinematica._core_testing.decoupled): the spherical wrist's twin identity (read, and a
// solver with it switched off, to compare with the solved flip), the SRS arm's points and
// extremes as its builder reads them, what the arm-position builder reads (the bounds on
// joints 4..n, joints 1-3 placing a point), the scalar root finders of joints 1-3 and the
// family's tolerances.
#include <nanobind/nanobind.h>
#include <nanobind/stl/optional.h>

#include <optional>
#include <utility>

#include "casters.hpp"
#include "common.hpp"
#include "kinematica/solvers/arm_point.hpp"
#include "kinematica/solvers/arm_position_build.hpp"
#include "kinematica/solvers/arm_quartic.hpp"
#include "kinematica/solvers/spherical_wrist_build.hpp"
#include "kinematica/solvers/srs_build.hpp"
#include "numpy_io.hpp"
#include "small_fields.hpp"

namespace kmpy {

namespace {

namespace kd = km::decoupled;

kd::SphericalWristParams wrist_of(const km::Chain& chain) {
    const std::optional<kd::SphericalWristParams> P = kd::build(chain);
    if (!P) throw nb::value_error("the spherical-wrist family declines this chain");
    return *P;
}

//! The SRS builder's values (srs.hpp names them), or None where it declines the chain.
nb::object srs_values(const km::Chain& chain) {
    const std::optional<km::srs::SRSParams> found = km::srs::build(chain);
    if (!found) return nb::none();
    const km::srs::SRSParams& P = *found;
    nb::dict d;
    const std::pair<const char*, km::Vec3> vectors[] = {{"s", P.s},   {"w_tool", P.w_tool},
                                                        {"se", P.se}, {"ew", P.ew},
                                                        {"h4", P.h4}, {"ref", P.ref},
                                                        {"ref_alt", P.ref_alt}};
    for (const auto& [name, v] : vectors) d[name] = v;
    d["stretched"] = P.stretched;
    d["d_max"] = P.d_max;
    d["d_min"] = P.d_min;
    d["scale"] = P.scale;
    return d;
}

//! An ArmPoint's values (arm_point.hpp names them), by name.
nb::dict arm_point_values(const kd::ArmPoint& a) {
    nb::dict d;
    const std::pair<const char*, km::Vec3> vectors[] = {{"p1", a.p1}, {"h1", a.h1}, {"h2", a.h2},
                                                        {"h3", a.h3}, {"a1", a.a1}, {"b1", a.b1}};
    for (const auto& [name, v] : vectors) d[name] = v;
    const std::pair<const char*, double> numbers[] = {
        {"a", a.a},         {"ca", a.ca},       {"g", a.g},         {"elbow", a.elbow},
        {"scale", a.scale}, {"r_lo", a.r_lo},   {"r_hi", a.r_hi},   {"z_lo", a.z_lo},
        {"z_hi", a.z_hi},   {"beta", a.beta},   {"dmin", a.dmin},   {"dmax", a.dmax},
        {"b3", a.b3},       {"m3", a.m3}};
    for (const auto& [name, v] : numbers) d[name] = v;
    d["kind"] = static_cast<int>(a.kind);
    d["prismatic"] = a.prismatic;
    d["parallel23"] = a.parallel23;
    d["refine"] = a.refine;
    return d;
}

//! The K numbers of h (any sequence) as float64.
template <int K>
void read_numbers(nb::handle h, const char* name, double (&out)[K]) {
    PyArrayObject* a = small::exact_array(h, name, NPY_DOUBLE, K, 0);
    const auto* d = static_cast<const double*>(PyArray_DATA(a));
    for (int i = 0; i < K; ++i) out[i] = d[i];
    Py_DECREF(a);
}

//! (self_motion, q (4,), near): the real roots of the trigonometric polynomial F (5,).
nb::tuple trig_roots(nb::handle Fh, double size) {
    double F[5], q[4];
    read_numbers(Fh, "F", F);
    bool near = false;
    const bool self_motion = kd::trig_roots(F, size, q, near);
    return nb::make_tuple(self_motion, small::get_vec(q), near);
}

//! (q (4,), near): the real roots of the quartic k (5,), highest power first.
nb::tuple slide_roots(nb::handle kh) {
    double k[5], q[4];
    read_numbers(kh, "k", k);
    bool near = false;
    kd::slide_roots(k, q, near);
    return nb::make_tuple(small::get_vec(q), near);
}

}  // namespace

void bind_decoupled_testing(nb::module_& m) {
    nb::module_ sub = m.def_submodule("decoupled", "The decoupled families' built values.");
    sub.attr("MAX_POSITION_DOF") = kd::MAX_POSITION_DOF;
    sub.attr("PLACE_RANK_TOL") = kd::PLACE_RANK_TOL;
    nb::list probes;  // (3, 3): the configurations of joints 1-3 places_point tries
    for (const auto& p : kd::PLACE_PROBES) probes.append(nb::make_tuple(p[0], p[1], p[2]));
    sub.attr("PLACE_PROBES") = probes;
    sub.def("wrist_twin", [](const km::Chain& chain) { return wrist_of(chain).twin; },
            nb::arg("chain"),
            "The built spherical-wrist solver's twin flag (its flip by the identity).");
    sub.def(
        "wrist_solved_flip",
        [](const km::Chain& chain) {
            kd::SphericalWristParams P = wrist_of(chain);
            P.twin = false;
            return P;
        },
        nb::arg("chain"),
        "The chain's spherical-wrist solver with the twin identity off (the flip solved).");
    sub.def("arm_point_values", &arm_point_values, nb::arg("arm"),
            "A built ArmPoint's values (a dict: kind 0 meet, 1 parallel, 2 general).");
    sub.def("srs_values", &srs_values, nb::arg("chain"),
            "The SRS builder's values (a dict), or None where it declines the chain.");
    sub.def("reach_after_joint3", &kd::reach_after_joint3, nb::arg("chain"),
            "The arm-position builder's bound (m) on how far joints 4..n move the tool origin.");
    sub.def("nearest_foot", &kd::nearest_foot, nb::arg("p"), nb::arg("h"), nb::arg("q"),
            nb::arg("g"), nb::arg("x"),
            "The point of line (p, h) nearest line (q, g); of parallel lines, nearest x.");
    sub.def(
        "wrist_chain",
        [](const km::Chain& chain) -> nb::object {
            km::Vec3 C;
            double R = 0.0;
            if (!kd::wrist_chain(km::arm_axes(chain), C, R)) return nb::none();
            return nb::make_tuple(C, R);
        },
        nb::arg("chain"),
        "(C (3,), R): a point on axis 4 and the bound on the tool origin's distance from it, "
        "or None (a joint after the third slides).");
    sub.attr("PARALLEL_SIN2") = kd::PARALLEL_SIN2;
    sub.def(
        "arm_geometry",
        [](F64 h, F64 p, bool prismatic, const km::Vec3& c,
           double size) -> std::optional<kd::ArmPoint> {
            const In hh = in_f64(h, "h", 2, {3, 3}), pp = in_f64(p, "p", 2, {3, 3});
            km::Vec3 H[3], P[3];
            for (int i = 0; i < 3; ++i) {
                H[i] = {hh.data[3 * i], hh.data[3 * i + 1], hh.data[3 * i + 2]};
                P[i] = {pp.data[3 * i], pp.data[3 * i + 1], pp.data[3 * i + 2]};
            }
            return kd::arm_geometry(H, P, prismatic, c, size);
        },
        nb::arg("h"), nb::arg("p"), nb::arg("prismatic"), nb::arg("c"), nb::arg("size"),
        "The ArmPoint of joints 1-3 (axes h, p (3, 3) at q = 0, joint 3 a slide or not)\n"
        "placing the point c (3,), or None (arm_point_build.hpp says when).");
    sub.def(
        "places_point",
        [](const km::Chain& chain, const km::Vec3& c_tool) {
            if (chain.dof() < 3) throw nb::value_error("joints 1-3 need a chain of 3 joints or more");
            return kd::places_point(chain, c_tool);
        },
        nb::arg("chain"), nb::arg("c_tool"),
        "True when joints 1-3 move the point c_tool (3,), fixed in the tool frame, in three\n"
        "directions (at one of PLACE_PROBES, σmin / σmax above PLACE_RANK_TOL).");
    sub.def(
        "clamped_root",
        [](double diff, double size, double other, double scale) {
            bool near = false;
            const double root = kd::clamped_root(diff, size, other, scale, near);
            return nb::make_tuple(root, near);
        },
        nb::arg("diff"), nb::arg("size"), nb::arg("other"), nb::arg("scale"),
        "(sqrt(diff * other) clamped at a fold, near flag).");
    sub.def("trig_roots", &trig_roots, nb::arg("F"), nb::arg("size"),
            "(self_motion, q (4,), near): real roots of F0 + F1 cos q + F2 sin q + F3 cos 2q + "
            "F4 sin 2q.");
    sub.def("slide_roots", &slide_roots, nb::arg("k"),
            "(q (4,), near): real roots of the quartic k (5,), highest power first.");
    sub.def("bounded_step", &kd::bounded_step, nb::arg("f"), nb::arg("df"),
            "The Newton step f / df, or 0 when longer than MAX_NEWTON_STEP.");

    sub.attr("SINGULAR_TOL") = kd::SINGULAR_TOL;
    sub.attr("NEAR_TOL") = kd::NEAR_TOL;
    sub.attr("NEAR_SET_TOL") = kd::NEAR_SET_TOL;
    sub.attr("DOUBLE_ROOT_TOL") = kd::DOUBLE_ROOT_TOL;
    sub.attr("HUGE_REACH") = kd::HUGE_REACH;
    sub.attr("IMAG_TOL") = kd::IMAG_TOL;
    sub.attr("NEWTON_STEPS") = kd::NEWTON_STEPS;
    sub.attr("MAX_NEWTON_STEP") = kd::MAX_NEWTON_STEP;
    sub.attr("SELF_MOTION_TOL") = kd::SELF_MOTION_TOL;
    sub.attr("TWIN_TOL") = kd::TWIN_TOL;
    sub.attr("WRIST_SINGULAR_TOL") = kd::WRIST_SINGULAR_TOL;
    sub.attr("NEAR_ALIGNED_TOL") = kd::NEAR_ALIGNED_TOL;
}

}  // namespace kmpy
