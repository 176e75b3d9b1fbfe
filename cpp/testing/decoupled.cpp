// The decoupled families' built values the tests pin (kinematica._core_testing.decoupled):
// the spherical wrist's twin identity (read, and a solver with it switched off, to compare
// with the solved flip), the SRS arm's points and extremes as its builder reads them.
#include <nanobind/nanobind.h>

#include <optional>
#include <utility>

#include "casters.hpp"
#include "common.hpp"
#include "kinematica/solvers/arm_position_build.hpp"
#include "kinematica/solvers/spherical_wrist_build.hpp"
#include "kinematica/solvers/srs_build.hpp"

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

}  // namespace

void bind_decoupled_testing(nb::module_& m) {
    nb::module_ sub = m.def_submodule("decoupled", "The decoupled families' built values.");
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
}

}  // namespace kmpy
