// The general 6R family's internals bound for the tests (kinematica._core_testing.general6r):
// the header's tolerances and scalar steps (real roots, null vectors, the self-motion test,
// the builder's labellings, probes and trace), a solver's fields read as a dict and set by
// name (hand-made cases), and the near-6R solver's watch. The product binding
// (cpp/python/bind_general6r.cpp) registers the family by its builder alone.
#include <nanobind/nanobind.h>
#include <nanobind/stl/complex.h>
#include <nanobind/stl/optional.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "casters.hpp"
#include "common.hpp"
#include "kinematica/solvers/general_6r.hpp"
#include "kinematica/solvers/general_6r_build.hpp"
#include "kinematica/solvers/near_6r.hpp"
#include "kinematica/solvers/near_6r_build.hpp"
#include "numpy_io.hpp"
#include "small_fields.hpp"

namespace kmpy {

namespace {

namespace kg = km::general6r;
using kg::General6RParams;

//! A (R, K) float field: a new array out, any array of exactly that shape in.
template <int R, int K>
F64 get_matrix(const double (&v)[R][K]) {
    double* out;
    F64 a = new_f64({R, K}, out);
    for (int i = 0; i < R; ++i)
        for (int j = 0; j < K; ++j) out[i * K + j] = v[i][j];
    return a;
}

template <int R, int K>
void set_matrix(double (&v)[R][K], nb::handle src, const char* name) {
    PyArrayObject* a = small::exact_array(src, name, NPY_DOUBLE, R, K);
    const auto* d = static_cast<const double*>(PyArray_DATA(a));
    for (int i = 0; i < R; ++i)
        for (int j = 0; j < K; ++j) v[i][j] = d[i * K + j];
    Py_DECREF(a);
}

//! A[0] = M (12, 12), A[1] = A[2] = 0: the quadratic M(x) whose value at x = 0 is M.
void constant_quadratic(nb::handle M, kg::Matrix12 (&A)[3]) {
    PyArrayObject* a = small::exact_array(M, "M", NPY_DOUBLE, kg::SIZE, kg::SIZE);
    const auto* d = static_cast<const double*>(PyArray_DATA(a));
    for (int i = 0; i < kg::SIZE; ++i)
        for (int j = 0; j < kg::SIZE; ++j) A[0](i, j) = d[i * kg::SIZE + j];
    Py_DECREF(a);
    A[1].setZero();
    A[2].setZero();
}

//! u (12,): the header's null vector of M (12, 12).
F64 null_vector_of(nb::handle M) {
    kg::Matrix12 A[3];
    constant_quadratic(M, A);
    const kg::Vector12 u = kg::General6RParams::null_vector(A, 0.0);  // M(0) = A0
    double* out;
    F64 ua = new_f64({kg::SIZE}, out);
    for (int i = 0; i < kg::SIZE; ++i) out[i] = u(i);
    return ua;
}

//! (k, 12): the header's monomial vectors of two solutions sharing a root, M (12, 12)
//! its matrix there (null space two-dimensional).
F64 null_pair_of(nb::handle M) {
    kg::Matrix12 A[3];
    constant_quadratic(M, A);
    kg::Vector12 u[2];
    const int count = kg::General6RParams::null_pair(A, 0.0, u);  // M(0) = A0
    double* out;
    F64 ua = new_f64({count, kg::SIZE}, out);
    for (int k = 0; k < count; ++k)
        for (int i = 0; i < kg::SIZE; ++i) out[k * kg::SIZE + i] = u[k](i);
    return ua;
}

//! A2, A1, A0 of a matrix quadratic M(x) = A0 + A1 x + A2 x² (each (12, 12)).
void read_quadratic(nb::handle A0, nb::handle A1, nb::handle A2, kg::Matrix12 (&A)[3]) {
    const nb::handle src[3] = {A0, A1, A2};
    const char* names[3] = {"A0", "A1", "A2"};
    for (int k = 0; k < 3; ++k) {
        PyArrayObject* a = small::exact_array(src[k], names[k], NPY_DOUBLE, kg::SIZE, kg::SIZE);
        const auto* d = static_cast<const double*>(PyArray_DATA(a));
        for (int i = 0; i < kg::SIZE; ++i)
            for (int j = 0; j < kg::SIZE; ++j) A[k](i, j) = d[i * kg::SIZE + j];
        Py_DECREF(a);
    }
}

//! (roots (k,), deflated): the header's real roots of det M(x) (general_6r_roots.hpp).
nb::tuple real_roots_of(nb::handle A0, nb::handle A1, nb::handle A2) {
    kg::Matrix12 A[3];
    read_quadratic(A0, A1, A2, A);
    const Eigen::PartialPivLU<kg::Matrix12> lead(A[2]);
    double roots[kg::ROOTS];
    bool deflated = false;
    const int found = kg::real_roots(A, lead, roots, &deflated);
    if (found < 0) throw nb::value_error("the eigenvalue iteration did not converge");
    double* out;
    F64 r = new_f64({found}, out);
    for (int i = 0; i < found; ++i) out[i] = roots[i];
    return nb::make_tuple(r, deflated);
}

//! (A0, A1, A2) of the chosen labelling's pencil M(x6) for the pose T at the first shift.
nb::tuple pencil_of(const General6RParams& p, const km::Pose& T_in) {
    if (const char* why = p.invalid()) throw nb::value_error(why);
    km::Pose T = T_in;
    T.p = p.scale * T.p;
    km::Pose L[6], Li[4];
    for (int k = 0; k < 6; ++k) L[k] = p.link_of(k, T);
    for (int k = 0; k < 4; ++k) Li[k] = km::inverse(L[k + 2]);
    kg::Elimination local;
    const kg::Elimination* E = &p;
    if (p.per_target()) {
        if (!(kg::eliminate(L[0], L[1], local) > kg::RANK_TOL))
            throw nb::value_error("the left side is rank-deficient for this target");
        E = &local;
    }
    kg::Matrix12 A[3];
    p.pencil(*E, Li, p.phi, p.phi[2], A);
    nb::object out[3];
    for (int k = 0; k < 3; ++k) {
        double* d;
        F64 a = new_f64({kg::SIZE, kg::SIZE}, d);
        for (int i = 0; i < kg::SIZE; ++i)
            for (int j = 0; j < kg::SIZE; ++j) d[i * kg::SIZE + j] = A[k](i, j);
        out[k] = std::move(a);
    }
    return nb::make_tuple(out[0], out[1], out[2]);
}

//! (value, kappa, eta) of the eigenvalue x of det(A0 + A1 x + A2 x²): its RootMargin.
nb::tuple real_axis_margin_of(nb::handle A0, nb::handle A1, nb::handle A2, std::complex<double> x) {
    kg::Matrix12 A[3];
    read_quadratic(A0, A1, A2, A);
    const kg::RootMargin m = kg::real_axis_margin(A, x);
    return nb::make_tuple(m.value, m.kappa, m.eta);
}

//! (nullity, last pivot above SPURIOUS_TOL / 1st, first below / 1st) of M(i)'s elimination;
//! nullity 0 where it is not deflated.
nb::tuple spurious_of(nb::handle A0, nb::handle A1, nb::handle A2) {
    kg::Matrix12 A[3];
    read_quadratic(A0, A1, A2, A);
    kg::SpuriousBasis Z;
    double ratios[2] = {km::NaN, km::NaN};
    const int nullity = kg::spurious_subspace(A, Z, ratios);
    return nb::make_tuple(nullity, ratios[0], ratios[1]);
}

//! (re (N,), im (N,)) of eigenvalues.hpp for a (N, N) matrix, N = 16 or 24.
template <int N>
nb::tuple eigenvalues_n(PyArrayObject* a) {
    double M[N][N];
    const auto* d = static_cast<const double*>(PyArray_DATA(a));
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) M[i][j] = d[i * N + j];
    double *re, *im;
    F64 ra = new_f64({N}, re), ia = new_f64({N}, im);
    if (!km::eigen::eigenvalues(M, re, im)) throw nb::value_error("the eigenvalue iteration did not converge");
    return nb::make_tuple(ra, ia);
}

nb::tuple eigenvalues_of(nb::handle A) {
    const bool big = nb::len(A) == kg::ROOTS;
    const int n = big ? kg::ROOTS : kg::GENUINE;
    PyArrayObject* a = small::exact_array(A, "A", NPY_DOUBLE, n, n);
    nb::tuple out = big ? eigenvalues_n<kg::ROOTS>(a) : eigenvalues_n<kg::GENUINE>(a);
    Py_DECREF(a);
    return out;
}

//! The Trace of one solve of the pose T (the solver's info into `info` when given).
kg::Trace traced(const General6RParams& p, const km::Pose& T, km::SolverInfo* info = nullptr) {
    if (const char* why = p.invalid()) throw nb::value_error(why);
    double Q[kg::SLOTS * 6];
    km::SolverInfo local;
    kg::Trace t;
    p.solve(T, Q, info != nullptr ? *info : local, &t);
    return t;
}

//! (rcond, shift6, closure, near, deflated, qz) of one solve of the pose T: its Trace and flag.
nb::tuple trace_of(const General6RParams& p, const km::Pose& T) {
    km::SolverInfo info;
    const kg::Trace t = traced(p, T, &info);
    return nb::make_tuple(t.rcond, t.shift6, t.closure, info.near, t.deflated, t.qz);
}

//! (singular, near, free mask, rank, reclosure) of one solve of the pose T: the solver's
//! info and the self-motion tests' smallest σ6/σ1 (NaN: none computed) and re-closure.
nb::tuple degeneracy_of(const General6RParams& p, const km::Pose& T) {
    km::SolverInfo info;
    const kg::Trace t = traced(p, T, &info);
    return nb::make_tuple(info.singular, info.near, info.free, t.rank, t.reclosure);
}

//! (verdict, rank, reclosure, moved (6,), free mask) of the self-motion test at the joint
//! values q (6,) of a solution of the pose T; moved and the mask per joint (not per loop
//! joint). Refused when q does not close the loop (CLOSURE_TOL): the test presumes it.
nb::tuple self_motion_of(const General6RParams& p, const km::Pose& T_in, nb::handle qh) {
    PyArrayObject* qa = small::exact_array(qh, "q", NPY_DOUBLE, 6, 0);
    double q[6];
    for (int k = 0; k < 6; ++k) q[k] = static_cast<const double*>(PyArray_DATA(qa))[k];
    Py_DECREF(qa);
    const std::optional<kg::SelfMotion> at = p.self_motion_at(T_in, q);
    if (!at) throw nb::value_error("q does not close the loop for T (its miss is above CLOSURE_TOL)");
    const kg::SelfMotion& sm = *at;
    double* out;
    F64 moved = new_f64({6}, out);
    std::uint32_t free = 0;
    for (int k = 0; k < 6; ++k) {
        out[p.order[k]] = sm.moved[k];
        if ((sm.free >> k) & 1U) free |= std::uint32_t{1} << p.order[k];
    }
    return nb::make_tuple(static_cast<int>(sm.verdict), sm.rank, sm.reclosure, moved, free);
}

//! (roots (k,), split (k,)): the header's real roots of det M(x) by QZ.
nb::tuple real_roots_qz_of(nb::handle A0, nb::handle A1, nb::handle A2) {
    kg::Matrix12 A[3];
    read_quadratic(A0, A1, A2, A);
    double roots[kg::ROOTS];
    bool split[kg::ROOTS];
    const int found = kg::real_roots_qz(A, roots, split);
    if (found < 0) throw nb::value_error("the QZ iteration did not converge");
    double *out, *sp;
    F64 r = new_f64({found}, out), s = new_f64({found}, sp);
    for (int i = 0; i < found; ++i) out[i] = roots[i], sp[i] = split[i] ? 1.0 : 0.0;
    return nb::make_tuple(r, s);
}

//! (c0 (14,), Q (14, 8)): the left side Rz(q'1) L1 Rz(q'2) L2 · z as c0 + Q S2.
nb::tuple left_side_of(const km::Pose& L1, const km::Pose& L2) {
    double *c0, *Q;
    F64 ca = new_f64({kg::EQUATIONS}, c0), Qa = new_f64({kg::EQUATIONS, kg::PRODUCTS}, Q);
    double q[kg::EQUATIONS][kg::PRODUCTS];
    kg::left_side(L1, L2, c0, q);
    for (int e = 0; e < kg::EQUATIONS; ++e)
        for (int k = 0; k < kg::PRODUCTS; ++k) Q[e * kg::PRODUCTS + k] = q[e][k];
    return nb::make_tuple(ca, Qa);
}

//! The params' own c0, N, Qp from their L1, L2 (t_link 2..5); σ8 / σ1 of Q.
double eliminate_params(General6RParams& p) {
    if (p.per_target()) throw nb::value_error("L1 or L2 holds the target: its constants are the target's");
    kg::Elimination E;
    const double ratio = kg::eliminate(p.link[0], p.link[1], E);
    if (ratio > kg::RANK_TOL) static_cast<kg::Elimination&>(p) = E;
    return ratio;
}

//! The Params of labelling `which` of a chain (or None: not 6R, or its left side
//! rank-deficient), and σ8 / σ1 of its Q (NaN with the target on the left).
nb::tuple labelling_of(const km::Chain& chain, int which) {
    if (which < 0 || which >= kg::LABELLINGS) throw nb::value_error("which must be 0 ... 11");
    kg::Loop loop;
    if (!kg::loop_of(chain, loop)) return nb::make_tuple(nb::none(), km::NaN);
    General6RParams p;
    double ratio = km::NaN;
    if (!kg::labelling(loop, which, p, &ratio)) return nb::make_tuple(nb::none(), ratio);
    return nb::make_tuple(nb::cast(std::move(p)), ratio);
}

//! (PROBES,) the probe distances of a labelling's candidates (builder's probe()).
F64 probe_of(const General6RParams& p, const km::Chain& chain, bool refine) {
    if (chain.dof() != 6) throw nb::value_error("the chain must have 6 joints");
    if (const char* why = p.invalid()) throw nb::value_error(why);
    double* out;
    F64 a = new_f64({kg::PROBES}, out);
    kg::probe(p, chain.view(), refine, out);
    return a;
}

//! (score, worst) of a labelling on the probes (builder's accuracy()).
nb::tuple accuracy_of(const General6RParams& p, const km::Chain& chain) {
    if (chain.dof() != 6) throw nb::value_error("the chain must have 6 joints");
    if (const char* why = p.invalid()) throw nb::value_error(why);
    double score, worst;
    kg::accuracy(p, chain.view(), score, worst);
    return nb::make_tuple(score, worst);
}

//! (params or None, chosen, scored, refined, probed): the builder's choice and what it did.
nb::tuple build_of(const km::Chain& chain) {
    General6RParams p;
    kg::BuildTrace t;
    const bool found = kg::build(chain, p, &t);
    nb::object params = found ? nb::cast(std::move(p)) : nb::object(nb::none());
    return nb::make_tuple(params, t.chosen, t.scored, t.refined, t.probed);
}

//! (answered, tried) of one solve of the pose T: the labelling whose candidates were
//! kept (0: the chosen one, k: alternate k) and how many alternates' passes ran.
nb::tuple attempts_of(const General6RParams& p, const km::Pose& T) {
    const kg::Trace t = traced(p, T);
    return nb::make_tuple(t.answered, t.tried);
}

//! The fields of a solver as a dict of arrays and numbers (the names general_6r.hpp gives).
nb::dict fields_of(const General6RParams& p) {
    nb::dict d;
    double* out;
    F64 link = new_f64({6, 4, 4}, out);
    for (int k = 0; k < 6; ++k) p.link[k].to_rows(out + 16 * k);
    d["link"] = link;
    d["t_link"] = p.t_link;
    d["t_power"] = p.t_power;
    d["t_pre"] = p.t_pre;
    d["t_post"] = p.t_post;
    d["order"] = small::get_ints(p.order);
    d["sign"] = p.sign;
    d["scale"] = p.scale;
    d["phi"] = small::get_vec(p.phi);
    d["centre"] = p.centre;
    d["reach"] = p.reach;
    d["refine_misses"] = p.refine_misses;
    d["c0"] = small::get_vec(p.c0);
    d["N"] = get_matrix(p.N);
    d["Qp"] = get_matrix(p.Qp);
    d["per_target"] = p.per_target();
    nb::list alts;
    for (const General6RParams& a : p.alternates) alts.append(nb::cast(a, nb::rv_policy::copy));
    d["alternates"] = alts;
    return d;
}

//! Sets the named fields of p in place (a hand-made case); each value checked for shape.
void set_fields(General6RParams& p, const nb::kwargs& kw) {
    for (auto [key, value] : kw) {
        const std::string name = nb::str(key).c_str();
        if (name == "t_link") p.t_link = nb::cast<int>(value);
        else if (name == "t_power") p.t_power = nb::cast<int>(value);
        else if (name == "sign") p.sign = nb::cast<double>(value);
        else if (name == "scale") p.scale = nb::cast<double>(value);
        else if (name == "reach") p.reach = nb::cast<double>(value);
        else if (name == "refine_misses") p.refine_misses = nb::cast<bool>(value);
        else if (name == "centre") p.centre = nb::cast<km::Vec3>(value);
        else if (name == "order") small::set_ints(p.order, value, "order", 0, 5);
        else if (name == "phi") small::set_vec(p.phi, value, "phi");
        else if (name == "c0") small::set_vec(p.c0, value, "c0");
        else if (name == "N") set_matrix(p.N, value, "N");
        else if (name == "Qp") set_matrix(p.Qp, value, "Qp");
        else if (name == "alternates") {
            std::vector<General6RParams> alts;
            for (nb::handle a : nb::iter(value)) alts.push_back(nb::cast<const General6RParams&>(a));
            for (const General6RParams& a : alts)
                if (!a.alternates.empty()) throw nb::value_error("an alternate has no alternates");
            p.alternates = std::move(alts);
        }
        else throw nb::value_error(("no settable field " + name).c_str());
    }
}

}  // namespace

void bind_general6r_testing(nb::module_& m) {
    nb::module_ sub = m.def_submodule("general6r", "The general 6R family's internals and tolerances.");
    sub.attr("EQUATIONS") = kg::EQUATIONS;
    sub.attr("PRODUCTS") = kg::PRODUCTS;
    sub.attr("REDUCED") = kg::REDUCED;
    sub.attr("SLOTS") = kg::SLOTS;
    sub.attr("CLASSES") = kg::CLASSES;
    sub.attr("PER_CLASS") = kg::PER_CLASS;
    sub.attr("FURTHER") = kg::FURTHER;
    sub.attr("REAL_ROOT_TOL") = kg::REAL_ROOT_TOL;
    sub.attr("LEADING_RCOND_TOL") = kg::LEADING_RCOND_TOL;
    sub.attr("CLOSURE_TOL") = kg::CLOSURE_TOL;
    sub.attr("SECOND_SHIFT") = kg::SECOND_SHIFT;
    sub.def("real_root", [](double re, double im) { return kg::real_root({re, im}); },
            nb::arg("re"), nb::arg("im"), "True when the eigenvalue re + i im is taken as a real root.");
    sub.def("null_vector", &null_vector_of, nb::arg("M"),
            "u: M u = 0 from M's full-pivot LU (M (12, 12), its null space one-dimensional).");
    sub.def("null_pair", &null_pair_of, nb::arg("M"),
            "(k, 12), k <= 2: the monomial vectors (x4^i x5^j at 3i + j) of the solutions "
            "whose two-dimensional null space M (12, 12) has.");
    sub.attr("SPURIOUS_TOL") = kg::SPURIOUS_TOL;
    sub.attr("SPLIT_ROOT_TOL") = kg::SPLIT_ROOT_TOL;
    sub.attr("RANK_TOL") = kg::RANK_TOL;
    sub.attr("PROBE_TOL") = kg::PROBE_TOL;
    sub.attr("ACCURATE") = kg::ACCURATE;
    sub.attr("PROBES") = kg::PROBES;
    sub.attr("FOOT_PARALLEL_TOL") = kg::FOOT_PARALLEL_TOL;
    sub.attr("FOOT_REACH") = kg::FOOT_REACH;
    sub.def("foot",
            [](const km::Vec3& hi, const km::Vec3& pi, const km::Vec3& hj, const km::Vec3& pj,
               double size) {
                const km::Vec3 h[2] = {hi, hj}, p[2] = {pi, pj};
                return kg::detail::foot(h, p, 0, 1, size);
            },
            nb::arg("hi"), nb::arg("pi"), nb::arg("hj"), nb::arg("pj"), nb::arg("size"),
            "The origin the builder gives axis i's frame: the foot of its common normal with "
            "axis j, or its own point pi (parallel axes, or a foot beyond FOOT_REACH sizes).");
    {
        nb::list configs, labellings;
        for (const auto& row : kg::PROBE_CONFIGS) {
            configs.append(nb::make_tuple(row[0], row[1], row[2], row[3], row[4], row[5]));
        }
        for (int i = 0; i < kg::LABELLINGS; ++i) {
            labellings.append(nb::make_tuple(kg::LABELLING_START[i], kg::LABELLING_REVERSE[i]));
        }
        sub.attr("PROBE_CONFIGS") = nb::tuple(configs);
        sub.attr("LABELLINGS") = nb::tuple(labellings);
        sub.attr("PHI") = nb::make_tuple(kg::PHI[0], kg::PHI[1], kg::PHI[2]);
    }
    sub.def("kept_at_once",
            [](double score, double worst, bool passes) {
                return kg::kept_at_once(score, worst, [passes] { return passes; });
            },
            nb::arg("score"), nb::arg("worst"), nb::arg("passes"),
            "True when the builder keeps a labelling without scoring the others (score: "
            "mean log10 of its probe distances; worst: the largest; passes: the refined "
            "probes within PROBE_TOL).");
    sub.def(
        "loop_size",
        [](const km::Chain& c) -> std::optional<double> {
            kg::Loop loop;
            if (!kg::loop_of(c, loop)) return std::nullopt;
            return loop.size;
        },
        nb::arg("chain"),
        "The size (m) the loop of a 6R chain is built in (general_6r_build.hpp): arm_size "
        "(chain_build.hpp); None for any other chain.");
    sub.attr("WALK_SIZE_RATIO") = km::WALK_SIZE_RATIO;
    sub.def("labelling", &labelling_of, nb::arg("chain"), nb::arg("which"),
            "(params or None, sigma8/sigma1 of Q): labelling `which` (an index of LABELLINGS) "
            "of a 6R chain; None where its left side is rank-deficient (ratio NaN: the target "
            "on the left, Q the target's).");
    sub.def("probe", &probe_of, nb::arg("params"), nb::arg("chain"), nb::arg("refine"),
            "(PROBES,) per probe pose, the distance (rad) of its configuration to the nearest "
            "candidate (inf: none), with Newton's step or (refine False) without.");
    sub.def("accuracy", &accuracy_of, nb::arg("params"), nb::arg("chain"),
            "(score, worst): the mean log10 of the raw probe distances clipped to [1e-16, 1], "
            "and the largest.");
    sub.def("build_trace", &build_of, nb::arg("chain"),
            "(params or None, chosen, scored, refined, probed): the general 6R solver of a 6R "
            "chain (general_6r_build.hpp), the labelling kept (an index of LABELLINGS, -1: "
            "none), how many were scored, how many refined probe passes ran and how many raw "
            "probe poses were solved.");
    sub.def("left_side", &left_side_of, nb::arg("L1"), nb::arg("L2"),
            "(c0 (14,), Q (14, 8)): the quantities of the line Rz(q'1) L1 Rz(q'2) L2 z as "
            "c0 + Q S2, S2 = (c2, s2, c1, c1 c2, c1 s2, s1, s1 c2, s1 s2) of q'1, q'2.");
    sub.attr("REFINE_LIMIT") = kg::REFINE_LIMIT;
    sub.attr("RESOLVE_TOL") = kg::RESOLVE_TOL;
    sub.attr("SAME_CANDIDATE_TOL") = kg::SAME_CANDIDATE_TOL;
    sub.attr("PAIR_ROOT_TOL") = kg::PAIR_ROOT_TOL;
    sub.def("close_roots", &kg::close_roots, nb::arg("x"), nb::arg("y"),
            "True when the roots x and y of det M are taken as one double root.");
    sub.def("resolves", &kg::resolves, nb::arg("miss"),
            "True when a candidate that missed by `worst` (m or rad) before Newton's step is "
            "looked for again as one of two solutions sharing its root.");
    sub.def("resolved",
            [](const General6RParams& p, const km::Pose& T) { return traced(p, T).resolved; },
            nb::arg("params"), nb::arg("T"),
            "True when the solve of the pose T took a root's null space as two-dimensional "
            "(a candidate missed by over RESOLVE_TOL).");
    sub.attr("SPLIT_CLOSURE_TOL") = kg::SPLIT_CLOSURE_TOL;
    sub.def("split_closes", &kg::split_closes, nb::arg("closure"),
            "True when a split pair's candidate Newton took to within closure (m or rad) of the "
            "target is a solution.");
    sub.attr("REFINE_STEPS") = kg::REFINE_STEPS;
    sub.attr("SINGULAR_RANK_TOL") = kg::SINGULAR_RANK_TOL;
    sub.attr("SELF_MOTION_STEP") = kg::SELF_MOTION_STEP;
    sub.attr("SELF_MOTION_STEPS") = kg::SELF_MOTION_STEPS;
    sub.attr("SELF_MOTION_TOL") = kg::SELF_MOTION_TOL;
    sub.attr("FREE_JOINT_TOL") = kg::FREE_JOINT_TOL;
    sub.def("moves", &kg::moves, nb::arg("d"),
            "True when a joint that moved by d (rad) along a continuum is taken as free.");
    sub.attr("DEGENERACY") = nb::make_tuple("regular", "fold", "continuum");
    sub.def("degeneracy", &degeneracy_of, nb::arg("params"), nb::arg("T"),
            "(singular, near, free, rank, reclosure) of one solve: the solver's flags and free "
            "joint mask, the smallest sigma6/sigma1 of a closing candidate's loop Jacobian the "
            "self-motion test computed (NaN: none; its screen proved every one regular) and "
            "the smallest miss of its re-closures (inf: none).");
    sub.def("self_motion", &self_motion_of, nb::arg("params"), nb::arg("T"), nb::arg("q"),
            "(verdict, rank, reclosure, moved, free) of the self-motion test at the solution q "
            "(6,) of the pose T: verdict an index of DEGENERACY, sigma6/sigma1 (NaN: the screen "
            "proved it regular), the re-closure's miss, how far each joint moved on the "
            "continuum (rad) and the free joints' mask.");
    sub.attr("QR_STEPS") = km::eigen::QR_STEPS;
    sub.def("real_roots", &real_roots_of, nb::arg("A0"), nb::arg("A1"), nb::arg("A2"),
            "(roots, deflated): the real roots of det(A0 + A1 x + A2 x²), each A (12, 12); "
            "deflated when its 8 roots at x = ±i were eliminated first.");
    sub.def("real_roots_qz", &real_roots_qz_of, nb::arg("A0"), nb::arg("A1"), nb::arg("A2"),
            "(roots, split): the real roots of det(A0 + A1 x + A2 x²) as generalized eigenvalues "
            "by QZ (no inverse of A2; a root at x = inf as +-1e300), split 1.0 for the two "
            "candidates of a nearly real pair.");
    sub.def("spurious_pivots", &spurious_of, nb::arg("A0"), nb::arg("A1"), nb::arg("A2"),
            "(nullity, last, small): the dimension of M(i)'s null space deflated as the spurious "
            "roots' (0: not deflated), and its elimination's last pivot above SPURIOUS_TOL and "
            "first below it over the first.");
    sub.def("eigenvalues", &eigenvalues_of, nb::arg("A"),
            "(re, im): the eigenvalues of A (16, 16) or (24, 24) by the core's Hessenberg QR.");
    sub.def("trace", &trace_of, nb::arg("params"), nb::arg("T"),
            "(rcond, shift6, closure, near, deflated, qz) of one solve: A2's rcond at the first "
            "shift, the shift used, the smallest candidate closure (inf: none), the near flag, "
            "whether the roots at x6 = ±i were eliminated before the eigenproblem, whether the "
            "roots came from QZ (A2 ill-conditioned at both shifts).");

    sub.def("pencil", &pencil_of, nb::arg("params"), nb::arg("T"),
            "(A0, A1, A2), each (12, 12): the chosen labelling's M(x6) for the pose T at the "
            "first shift.");
    sub.def("real_axis_margin", &real_axis_margin_of, nb::arg("A0"), nb::arg("A1"), nb::arg("A2"),
            nb::arg("x"),
            "(value, kappa, eta) of the eigenvalue x of det(A0 + A1 x + A2 x²): its distance "
            "from the real axis over its first-order error bound, its condition number and "
            "backward error.");
    sub.attr("PENCIL_EPS") = kg::PENCIL_EPS;
    sub.attr("MAX_NULLITY") = kg::MAX_NULLITY;
    sub.attr("EXTRA_NULL_TOL") = kg::EXTRA_NULL_TOL;
    sub.attr("CERTIFY_MARGIN") = kg::CERTIFY_MARGIN;
    sub.def("certifies", &kg::certifies, nb::arg("margin"),
            "True when a spectrum's margin from the real axis proves det M has no real root.");
    sub.def("margin",
            [](const General6RParams& p, const km::Pose& T) {
                const kg::RootMargin m = traced(p, T).margin;
                return nb::make_tuple(m.value, m.kappa, m.eta);
            },
            nb::arg("params"), nb::arg("T"),
            "(margin, kappa, eta) of the chosen labelling's spectrum for the pose T where none "
            "of its candidates closed: the least of its eigenvalues' distances from the real "
            "axis over their error bounds, that eigenvalue's condition number and backward "
            "error (margin NaN: not computed).");
    sub.attr("ALTERNATES") = kg::ALTERNATES;
    sub.attr("ALTERNATE_RCOND") = kg::ALTERNATE_RCOND;
    sub.def("may_alternate", &kg::may_alternate, nb::arg("score"),
            "True when a labelling whose mean log10 probe distance is `score` may be an "
            "alternate (its raw candidates within PROBE_TOL of the probes, geometric mean).");
    sub.def("attempts", &attempts_of, nb::arg("params"), nb::arg("T"),
            "(answered, tried) of one solve: the labelling whose candidates were kept (0: the "
            "chosen one, k: alternate k), how many alternates' passes ran.");
    sub.def("fields", &fields_of, nb::arg("params"),
            "The solver's fields (link (6, 4, 4), t_link, t_power, t_pre, t_post, order, sign, "
            "scale, phi, centre, reach, refine_misses, c0, N, Qp), per_target and alternates "
            "(a list of General6RParams copies), as a dict.");
    sub.def("set", &set_fields, nb::arg("params"), nb::arg("fields"),
            "Sets the named fields of a General6RParams in place (t_link, t_power, sign, scale, "
            "reach, refine_misses, centre, order, phi, c0, N, Qp, alternates: a sequence of "
            "General6RParams without their own), each checked for shape.");
    sub.def("blank", [] { return General6RParams{}; },
            "A General6RParams as the header default-constructs it (no arm).");
    sub.def("eliminate", &eliminate_params, nb::arg("params"),
            "c0, N and Qp from L1 and L2 (which hold no target): returns sigma8/sigma1 of Q; "
            "the fields are left as they were when it is not above RANK_TOL.");

    using NearParallel = km::Near6RParams<km::ParallelParams>;
    sub.def("set_watch", [](NearParallel& p, double watch) { p.watch = watch; },
            nb::arg("params"), nb::arg("watch"),
            "Sets a near-6R solver's watch (rad; inf: the general 6R at every target).");
    sub.def("watch", [](const NearParallel& p) { return p.watch; }, nb::arg("params"),
            "A near-6R solver's watch: the general 6R runs where the family's candidates lie "
            "within it of its singular sets (rad; inf: everywhere).");
    sub.attr("WATCH_FACTOR") = km::WATCH_FACTOR;
    sub.attr("NEAR_GAP") = km::NEAR_GAP;
}

}  // namespace kmpy
