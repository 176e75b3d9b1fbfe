// The line geometry of joint axes (lines.hpp): a chain's whole feature set in one call, the
// predicates and the tolerances, for kinematica.dh.lines and kinematica.ik.structure.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include "casters.hpp"
#include "common.hpp"
#include "kinematica/arm_axes.hpp"
#include "kinematica/chain.hpp"
#include "kinematica/lines.hpp"

namespace kmpy {

namespace {

namespace kl = km::lines;
using km::Vec3;

//! A new read-only float64 array of shape (rows, 3) holding v[0 .. rows).
nb::object readonly_rows(const Vec3* v, npy_intp rows) {
    double* out;
    nb::object a = new_f64({rows, 3}, out);
    for (npy_intp i = 0; i < rows; ++i) put(v[i], out + 3 * i);
    return read_only(a);
}

//! A centre as a read-only (3,) array, or None.
nb::object centre_or_none(const kl::Centre& c) {
    return c.found ? read_only(nb::cast(c.at)) : nb::object(nb::none());
}

//! The pairs (i, i + 1) whose flag is set, as a tuple of tuples.
nb::tuple pairs(const bool* flag, int count) {
    nb::list out;
    for (int i = 0; i < count; ++i) {
        if (flag[i]) out.append(nb::make_tuple(i, i + 1));
    }
    return nb::steal<nb::tuple>(PyList_AsTuple(out.ptr()));
}

nb::tuple features(const km::Chain& chain) {
    const km::ArmAxes A = km::arm_axes(chain);
    std::string types(static_cast<size_t>(A.n), 'R');
    for (int i = 0; i < A.n; ++i) {
        if (A.prismatic[i]) types[static_cast<size_t>(i)] = 'P';
    }
    return nb::make_tuple(types, readonly_rows(A.h.data(), A.n), readonly_rows(A.p.data(), A.n),
                          pairs(A.parallel.get(), A.n - 1), pairs(A.meet.get(), A.n - 1),
                          centre_or_none(A.features.wrist), A.size, A.features.slack,
                          centre_or_none(A.features.shoulder));
}

//! (k, 3) float64 arrays as Vec3 lines.
std::vector<Vec3> vec3_rows(const In& a) {
    std::vector<Vec3> out(static_cast<size_t>(a.dim[0]));
    for (size_t i = 0; i < out.size(); ++i) {
        out[i] = {a.data[3 * i], a.data[3 * i + 1], a.data[3 * i + 2]};
    }
    return out;
}

std::optional<Vec3> common_point(F64 h, F64 p, double size) {
    const In hh = in_f64(h, "h", 2, {-1, 3});
    const In pp = in_f64(p, "p", 2, {hh.dim[0], 3});
    const std::vector<Vec3> H = vec3_rows(hh), P = vec3_rows(pp);
    Vec3 c;
    if (!kl::common_point(H.data(), P.data(), static_cast<int>(H.size()), size, c)) {
        return std::nullopt;
    }
    return c;
}

}  // namespace

void bind_lines(nb::module_& m) {
    nb::module_ sub = m.def_submodule(
        "lines", "Joint axes as lines: the one line geometry and its tolerances (lines.hpp).");
    sub.attr("AXIS_ANGLE_TOL") = kl::AXIS_ANGLE_TOL;
    sub.attr("AXIS_LENGTH_TOL") = kl::AXIS_LENGTH_TOL;
    sub.attr("AXIS_EXACT_TOL") = kl::AXIS_EXACT_TOL;
    sub.def("length_tol", &kl::length_tol, nb::arg("size"), "The distance (m) below which lines meet.");
    sub.def("lines_parallel", &kl::lines_parallel, nb::arg("hA"), nb::arg("hB"),
            "True when unit directions hA, hB (3,) are parallel or anti-parallel.");
    sub.def("lines_perpendicular", &kl::lines_perpendicular, nb::arg("hA"), nb::arg("hB"),
            "True when unit directions hA, hB (3,) are perpendicular.");
    sub.def("line_distance", &kl::line_distance, nb::arg("hA"), nb::arg("pA"), nb::arg("hB"),
            nb::arg("pB"), "Distance (m) between lines pA + t hA and pB + s hB (unit directions).");
    sub.def("common_point", &common_point, nb::arg("h"), nb::arg("p"), nb::arg("size"),
            "(3,) the least-squares point of the lines p[i] + t h[i] ((k, 3) each), or None.");
    sub.def("arm_size", &km::arm_size, nb::arg("chain"),
            "The arm's size (m), the line tolerance's scale (chain_build.hpp: its frames' or along its axes).");
    sub.def("features", &features, nb::arg("chain"),
            "Features' fields in order, of a chain's axes at q = 0 (kinematica.ik.structure).");
}

}  // namespace kmpy
