// SRS 7R arms (iiwa type) at a given arm angle: kinematica._core.srs.
#include "common.hpp"
#include "kinematica/solvers/srs_angle.hpp"  // srs.hpp, srs_build.hpp
#include "solver_binding.hpp"

namespace kmpy {

namespace {

using km::srs::SRSParams;

//! An SRS arm at one arm angle as a solver (ik.hpp's interface): one per target of a batch
//! with an angle per target, the Params shared.
struct AtAngle {
    const SRSParams& params;
    double psi;
    using Work = km::NoWork;
    Work work(int) const { return {}; }
    int slots() const { return params.slots(); }
    int dof() const { return params.dof(); }
    void solve(const km::ChainView&, const km::Pose& T, const double*, double* Q,
               km::SolverInfo& info, Work&) const {
        params.solve_at(T, psi, Q, info);
    }
};

//! ik_batch with target i at the arm angle psi[i].
BatchAnswer ik_batch_at(const SRSParams& p, const km::Chain& chain, F64 T, F64 psi,
                     const km::CheckOptions& opts, nb::handle q0, nb::handle invalid,
                     int workers) {
    const npy_intp N = shape_f64(T, "T", 3, {-1, 4, 4}).dim[0];  // read by ik_many_rows
    const In angles = in_f64(psi, "psi", 1, {N});  // held while the batch reads it
    const double* angle = angles.data;
    const AtAngle base{checked(p), p.psi};
    return ik_many_rows(base, chain, T, q0, invalid, workers,
                        [&base, angle, &opts](npy_intp i, const km::ChainView& ch,
                                              const km::Pose& P, const double* q0i,
                                              km::IKWork<AtAngle>& work, const km::CheckOut& o) {
                            const AtAngle at{base.params, angle[i]};
                            return solve_checked(at, ch, P, opts, q0i, work, o);
                        });
}

//! The arm angles (N,) of configurations q (N, 7) of an SRS arm; None for any other chain.
nb::object arm_angles(const km::Chain& chain, F64 qh) {
    const In q = in_f64(qh, "q", 2, {-1, 7});
    const auto g = km::srs::angle_geometry(chain);  // srs_points: 7 revolute joints
    if (!g) return nb::none();
    double* out;
    F64 result = new_f64({q.dim[0]}, out);
    const km::ChainView ch = chain.view();
    for (npy_intp i = 0; i < q.dim[0]; ++i) out[i] = km::srs::arm_angle(ch, *g, q.data + 7 * i);
    return result;
}

}  // namespace

void bind_srs(nb::module_& m) {
    nb::module_ sub = m.def_submodule(
        "srs", "SRS 7R arms (axes 1-3 meet, axes 5-7 meet): all 8 solutions at an arm angle.");
    auto cls = bind_family<SRSParams>(
        sub, "SRSParams",
        "An SRS 7R arm as its closed form reads it (solvers/srs.hpp): 8 slots, 7 joints, "
        "solving at the arm angle psi (0 as built).",
        "kinematica/solvers/srs_build.hpp", "km::srs::SRSParams", "km::srs::build",
        [](const km::Chain& c) { return km::srs::build(c); });
    cls.def_rw("psi", &SRSParams::psi, "the arm angle to solve at (rad)");
    cls.def("aimed", &SRSParams::aimed, nb::arg("T"), nb::arg("q4"),
            "(4, 4) T moved along the shoulder-wrist line to the wrist centre q4 puts (srs.hpp).");
    cls.def(
        "at",
        [](SRSParams p, double psi) {
            p.psi = psi;
            return p;
        },
        nb::arg("psi"), "A copy solving at the arm angle psi (rad).");
    cls.def("ik_batch_at", &ik_batch_at, nb::arg("chain"), nb::arg("T"), nb::arg("psi"),
            nb::arg("options"), nb::arg("q0").none(), nb::arg("invalid").none(),
            nb::arg("workers"),
            "ik_batch of targets T (N, 4, 4), target i at the arm angle psi[i] (N,) (rad).");
    sub.def("arm_angles", &arm_angles, nb::arg("chain"), nb::arg("q"),
            "(N,) arm angles (rad) of q (N, 7), NaN where undefined; None for no SRS arm.");
    sub.attr("COLLINEAR_TOL") = km::srs::COLLINEAR_TOL;
    sub.attr("REFERENCE_TOL") = km::srs::REFERENCE_TOL;
}

}  // namespace kmpy
