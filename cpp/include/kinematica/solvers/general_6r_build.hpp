// The general 6R solver's builder: from a chain of six revolute joints to the Params of the
// labelling of its joints whose elimination is well posed (general_6r.hpp solves with it).
//
// The loop. With G_i a frame whose z is axis i at q = 0 (base frame; its origin at the foot
// of the common normal with the next axis, the last with the fifth's), K_i = G_i⁻¹ G_{i+1}
// and K_6 = G_6⁻¹ M (M the tool at q = 0), the product of exponentials Π G_i Rz(q_i) G_i⁻¹ M
// regroups to T(q) = G_1 Rz(q_1) K_1 ... Rz(q_6) K_6: any base, tool, convention or URDF
// chain. Read as the loop I = Rz(q_1) K_1 ... Rz(q_6) [K_6 T⁻¹ G_1], or reversed
// (q' = -q, joints 6..1: I = Rz(-q_6) K_5⁻¹ ... K_1⁻¹ Rz(-q_1) [G_1⁻¹ T K_6⁻¹]), and turned to
// start at any of its six joints, it gives twelve labellings (LABELLING_START/REVERSE): the
// eight whose L1, L2 hold no target first (the elimination's constants made once), then the
// four with the target at L1 or L2 (made for each target: the well-posed ones where the
// eight degenerate, FANUC CRX, Kinova JACO 2).
//
// The choice. Each labelling is probed on PROBES poses made by FK (PROBE_CONFIGS): how far
// the configuration that made each is from the nearest raw candidate. The first whose
// eigenproblem is accurate to round-off (ACCURATE, the geometric mean over the probes) and
// that holds every probe's configuration (PROBE_TOL, raw or after Newton's step) is kept at
// once; else, of those that hold them after Newton's step, the most accurate. On an arm
// near one whose elimination degenerates (a calibrated UR5) the labellings' root errors
// differ by orders of magnitude, and the first that passes is often not the best (measured
// on 30 calibrated UR5s, 200 poses each: 122 generating configurations missed with the
// first that passes, 9 with the most accurate, 8 of them at singular poses).
//
// The alternates (general_6r.hpp: tried where the chosen labelling's candidates close no
// loop): the next labellings in order that are kept at once too, else the others whose
// raw probe score is within PROBE_TOL (may_alternate; a degenerate labelling, det M ≡ 0,
// scores about 0 and is not probed again), by score, the first ALTERNATES that pass.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "../chain.hpp"
#include "general_6r.hpp"

namespace km::general6r {

//! Shifts (rad) of q'4, q'5, q'6 in the half-angle substitution: a configuration with
//! q'k = shift + π (tan = ∞) is then no special value of a DH table (0, ±π/2, π).
constexpr double PHI[3] = {0.3771, 0.6133, 0.8909};
//! A labelling passes a probe pose when the configuration that made it is among the
//! candidates to this (rad; the check's polish takes them the rest of the way).
constexpr double PROBE_TOL = 1e-6;
//! A labelling whose candidates hold the probe poses' configurations to this (rad; the
//! geometric mean of their distances, before Newton's step) is taken without scoring the
//! others: round-off for a well-posed elimination (generic arms: 1e-15..1e-13), where the
//! ranking could only trade one round-off for another; it saves the other labellings'
//! constants and probes (about 10 of a generic arm's 12 ms of building in Python).
constexpr double ACCURATE = 1e-12;
//! Poses each labelling is probed on.
constexpr int PROBES = 8;
//! Their configurations: uniform in (-π, π], numpy's default_rng(6).uniform(-π, π, (8, 6))
//! written out (reproducible, and no random generator at run time).
constexpr double PROBE_CONFIGS[PROBES][6] = {
    {0.2397936924265509, -0.9847581679958686, -0.8226747951461473, -0.788560078461733,
     3.062707200397904, 0.8341322614811477},
    {1.0953095588356296, -1.0683711188056741, 1.1304560051279005, -2.3689344345096206,
     -2.8165683032376525, 2.200317124970402},
    {-3.085698658954023, 3.0081853122768454, 2.0546206072295448, 1.7920333090860519,
     -2.8394751945374326, -1.8382133040260147},
    {2.1982705927845485, -0.42414760756750125, 0.8009046481796953, -2.3732696820540706,
     -1.9708070338793215, -0.017166210520705327},
    {1.630276583194279, 0.250430200722215, -2.4700453142945857, 2.300814988218379,
     -2.2640898449367772, -0.37914149140104936},
    {0.5456913354825392, -1.1363171893390018, -0.5148808609029172, 2.43136960316206,
     -0.28817388591814597, 0.24659688064192586},
    {2.9561705279185215, -1.4075394657208866, 2.480539907955195, -0.8679873580267703,
     -1.180981117766106, 2.395710664347914},
    {-2.730064447817266, 2.303762074792796, 2.059424684268012, 2.4800664901287144,
     -2.7661266688773907, -1.6411328506132996},
};
//! The labellings in the order they are tried: (start, reversed).
constexpr int LABELLINGS = 12;
constexpr int LABELLING_START[LABELLINGS] = {0, 1, 2, 3, 0, 1, 2, 3, 4, 5, 4, 5};
constexpr bool LABELLING_REVERSE[LABELLINGS] = {false, false, false, false, true, true,
                                                true,  true,  false, false, true, true};
//! Below this squared sine two axes are parallel for the foot of their common normal.
constexpr double FOOT_PARALLEL_TOL = 1e-18;
//! A frame's origin is the foot of the common normal with the next axis only where that
//! lies within this many arm sizes of the axis's point nearest the arm (the walk's); else
//! that point. Nearly parallel axes meet far away (the Kinova Gen3 Lite's axes 2 and 3,
//! 7.3e-6 rad apart, 38 km off; a JACO 2 moved by 1e-8, 4e7 m): a loop of such lengths
//! loses their size times round-off (1.6e-9 m measured), and Newton's step then stalls
//! there instead of closing the loop.
constexpr double FOOT_REACH = 10.0;
//! The chain's own points on the axes are replaced by the walk's nearest points where
//! the arm's size is measured along them (arm_size, chain_build.hpp).
using km::WALK_SIZE_RATIO;

//! The arm as a loop: T(q) = G1 Rz(q1) K1 ... Rz(q6) K6 (base frame, m).
struct Loop {
    Pose K[6]{};
    Pose G1{};
    double size = 1.0;  //!< the arm's size (m): the loop's lengths are scaled by 1 / size
};

//! What build() did, for the tests of its rules.
struct BuildTrace {
    int chosen = -1;   //!< the labelling kept (an index of LABELLING_*), -1: none
    int scored = 0;    //!< labellings whose probes were scored
    int refined = 0;   //!< refined probe passes run
    int probed = 0;    //!< raw probe poses solved in scoring
    int alternates = 0;  //!< alternates kept (general_6r.hpp: ALTERNATES at most)
};

namespace detail {

//! Records each joint's axis (direction, point) of a walk at q = 0.
struct Axes {
    static constexpr bool frames = false;
    static constexpr bool axes = true;
    Vec3 h[6]{}, p[6]{};
    void frame(int, const Pose&) {}
    void axis(int i, const Vec3& z, const Vec3& o) { h[i] = z, p[i] = o; }
};

//! A frame with z axis `z` at `origin` (x any unit normal, from a fixed seed).
inline Pose frame_on(const Vec3& z, const Vec3& origin) {
    const Vec3 seed = std::fabs(z.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
    Vec3 x = cross(z, seed);
    x = (1.0 / norm(x)) * x;
    Pose G;
    G.x = x, G.y = cross(z, x), G.z = z, G.p = origin;
    return G;
}

//! The point of axis i nearest axis j, or axis i's own point p[i] when they are parallel
//! or that point lies farther than FOOT_REACH times the arm's size from it.
inline Vec3 foot(const Vec3* h, const Vec3* p, int i, int j, double size) {
    const Vec3 w = cross(h[i], h[j]);
    const double n2 = dot(w, w);
    if (n2 < FOOT_PARALLEL_TOL) return p[i];
    const double t = dot(cross(p[j] - p[i], h[j]), w) / n2;
    if (!(std::fabs(t) <= FOOT_REACH * size)) return p[i];
    return p[i] + t * h[i];
}

//! A pose with its translation times `scale`.
inline Pose scaled(Pose A, double scale) {
    A.p = scale * A.p;
    return A;
}

}  // namespace detail

//! The loop of a chain of six revolute joints (false for any other chain).
inline bool loop_of(const Chain& chain, Loop& out) {
    const ChainView ch = chain.view();
    if (ch.n != 6) return false;
    for (int i = 0; i < 6; ++i)
        if (ch.joint[i].prismatic) return false;
    double q[6] = {}, c[6], s[6];
    joint_trig(ch, q, c, s);
    detail::Axes axes;
    const Pose M = walk(ch, q, c, s, axes);
    out.size = std::fmax(frame_size(chain), 1e-9);
    Vec3 near[6];
    std::copy(axes.p, axes.p + 6, near);
    const double walked = walked_size(axes.h, near, 6, M.p);
    if (walked < WALK_SIZE_RATIO * out.size) {
        std::copy(near, near + 6, axes.p);
        out.size = std::fmax(walked, 1e-9);
    }
    Pose G[6];
    for (int i = 0; i < 6; ++i) {
        const Vec3 origin = detail::foot(axes.h, axes.p, i, i < 5 ? i + 1 : 4, out.size);
        G[i] = detail::frame_on(axes.h[i], origin);
    }
    for (int i = 0; i < 5; ++i) out.K[i] = inverse(G[i]) * G[i + 1];
    out.K[5] = inverse(G[5]) * M;
    out.G1 = G[0];
    return true;
}

//! The Params of labelling `which` (an index of LABELLING_*) into p; false when its left
//! side is rank-deficient (constants of the arm's below RANK_TOL). ratio: σ8 / σ1 of Q
//! (NaN for a labelling with the target on the left: Q is then the target's).
inline bool labelling(const Loop& loop, int which, General6RParams& p, double* ratio = nullptr) {
    const int start = LABELLING_START[which];
    const bool reverse = LABELLING_REVERSE[which];
    const double scale = 1.0 / loop.size;
    int order[6];
    Pose links[6];
    int target = 5;
    if (reverse) {
        for (int k = 0; k < 6; ++k) order[k] = 5 - k;
        for (int k = 0; k < 5; ++k) links[k] = inverse(loop.K[4 - k]);
        p.t_power = 1;
        p.t_pre = detail::scaled(inverse(loop.G1), scale);
        p.t_post = detail::scaled(inverse(loop.K[5]), scale);
    } else {
        for (int k = 0; k < 6; ++k) order[k] = k;
        for (int k = 0; k < 5; ++k) links[k] = loop.K[k];
        p.t_power = -1;
        p.t_pre = detail::scaled(loop.K[5], scale);
        p.t_post = detail::scaled(loop.G1, scale);
    }
    for (int k = 0; k < 6; ++k) {
        const int from = (k + start) % 6;
        p.order[k] = order[from];
        p.link[k] = from == target ? Pose{} : detail::scaled(links[from], scale);
    }
    p.t_link = (target - start + 6) % 6;
    p.sign = reverse ? -1.0 : 1.0;
    p.scale = scale;
    double r = NaN;
    if (!p.per_target()) {
        Elimination E;
        r = eliminate(p.link[0], p.link[1], E);
        if (!(r > RANK_TOL)) {
            if (ratio != nullptr) *ratio = r;
            return false;
        }
        static_cast<Elimination&>(p) = E;
    }
    if (ratio != nullptr) *ratio = r;
    for (int k = 0; k < 3; ++k) p.phi[k] = PHI[k];
    p.centre = loop.G1.p;
    double reach = 0.0;
    for (int k = 0; k < 6; ++k) reach += norm(loop.K[k].p);
    p.reach = reach * (1.0 + 1e-12) + 1e-12;
    p.refine_misses = true;
    return true;
}

namespace detail {

//! How far (rad, the largest joint difference modulo 2π) probe pose i's configuration is
//! from the nearest candidate of P (INF: none).
inline double probe_one(const General6RParams& P, const ChainView& ch, int i) {
    double Q[SLOTS * 6], c[6], s[6];
    const Pose T = fk(ch, PROBE_CONFIGS[i], c, s);
    SolverInfo info;
    P.solve(T, Q, info);
    double best = INF;
    for (int r = 0; r < SLOTS; ++r) {
        if (!std::isfinite(Q[r * 6])) continue;
        double d = 0.0;
        for (int k = 0; k < 6; ++k) d = std::fmax(d, std::fabs(wrap(Q[r * 6 + k] - PROBE_CONFIGS[i][k])));
        best = std::fmin(best, d);
    }
    return best;
}

//! A probe distance's term of the score: log10 of it clipped to [1e-16, 1].
inline double score_term(double d) { return std::log10(std::clamp(d, 1e-16, 1.0)); }

}  // namespace detail

//! Per probe pose, how far (rad, the largest joint difference modulo 2π) the configuration
//! that made it is from the nearest candidate (INF: none), with Newton's step (`refine`) or
//! as the eigenproblem gives them.
inline void probe(const General6RParams& p, const ChainView& ch, bool refine, double* out) {
    General6RParams P = p;
    P.refine_misses = refine;
    for (int i = 0; i < PROBES; ++i) out[i] = detail::probe_one(P, ch, i);
}

//! (score, worst) of a labelling's raw candidates on the probes: the mean of log10 of the
//! distances clipped to [1e-16, 1] (1: none found; lower is better), and the largest.
//! With `give_up`, scoring stops (false, `score` the mean of the probes scored) once the
//! probes scored so far prove the score above log10(ACCURATE) whatever the others give
//! (each at best -16): such a labelling cannot be kept at once, and is scored in full only
//! if the ranking needs it. Degenerate
//! labellings (det M ≡ 0: eleven of a FANUC CRX's twelve) then cost 3 probes, not 8.
inline bool accuracy(const General6RParams& p, const ChainView& ch, double& score, double& worst,
                     bool give_up = false, int* probed = nullptr) {
    General6RParams P = p;
    P.refine_misses = false;
    double sum = 0.0;
    worst = 0.0;
    for (int i = 0; i < PROBES; ++i) {
        const double d = detail::probe_one(P, ch, i);
        if (probed != nullptr) ++*probed;
        sum += detail::score_term(d);
        worst = std::fmax(worst, d);
        if (give_up && sum - 16.0 * (PROBES - 1 - i) > PROBES * std::log10(ACCURATE)) {
            score = sum / (i + 1);  // the mean so far
            return false;
        }
    }
    score = sum / PROBES;
    return true;
}

//! True when a labelling is kept without scoring the others: accurate to round-off, every
//! probe within PROBE_TOL before Newton's step (`worst`) or after it (`passes`, asked only
//! when needed: Newton's step only takes a candidate nearer the solution it is near).
template <class Passes>
inline bool kept_at_once(double score, double worst, Passes&& passes) {
    return score <= std::log10(ACCURATE) && (worst <= PROBE_TOL || passes());
}

//! True when a labelling whose (mean log10) probe score is `score` may be an alternate: its
//! raw candidates hold the probes' configurations to PROBE_TOL (geometric mean). The
//! degenerate ones (det M ≡ 0: a score near 0) are not asked for their refined probes.
inline bool may_alternate(double score) { return score <= std::log10(PROBE_TOL); }

//! The general 6R solver of a chain of six revolute joints into out; false when no
//! labelling holds the probes' configurations (or the chain is not 6R). Its alternates
//! (general_6r.hpp: ALTERNATES at most): the next labellings in order kept at once too,
//! else those that may (may_alternate) by score, the first that pass the refined probes.
inline bool build(const Chain& chain, General6RParams& out, BuildTrace* trace = nullptr) {
    BuildTrace local;
    BuildTrace& t = trace != nullptr ? *trace : local;
    Loop loop;
    if (!loop_of(chain, loop)) return false;
    const ChainView ch = chain.view();
    auto passes = [&](const General6RParams& p) {
        ++t.refined;
        double d[PROBES];
        probe(p, ch, true, d);
        return *std::max_element(d, d + PROBES) <= PROBE_TOL;
    };
    General6RParams built[LABELLINGS];
    bool usable[LABELLINGS] = {}, full[LABELLINGS] = {}, taken[LABELLINGS] = {};
    double score[LABELLINGS];
    int ranked[LABELLINGS], count = 0, chosen = -1, alternate[ALTERNATES], alternates = 0;
    for (int which = 0; which < LABELLINGS && alternates < ALTERNATES; ++which) {
        if (!(usable[which] = labelling(loop, which, built[which]))) continue;
        double worst;
        full[which] = accuracy(built[which], ch, score[which], worst, true, &t.probed);
        ++t.scored;
        if (!full[which] || !kept_at_once(score[which], worst, [&] { return passes(built[which]); }))
            continue;
        taken[which] = true;
        if (chosen < 0) {
            chosen = which;  // then the alternates: the next kept at once
        } else {
            alternate[alternates++] = which;
        }
    }
    for (int which = 0; which < LABELLINGS; ++which) {
        if (!usable[which] || taken[which]) continue;
        if (chosen < 0 && !full[which]) {  // the ranking chooses: every labelling scored in full
            double worst;
            full[which] = accuracy(built[which], ch, score[which], worst, false, &t.probed);
        }
        ranked[count++] = which;
    }
    std::stable_sort(ranked, ranked + count, [&](int a, int b) { return score[a] < score[b]; });
    for (int i = 0; i < count && alternates < ALTERNATES; ++i) {
        if (chosen >= 0 && !may_alternate(score[ranked[i]])) break;  // the rest score worse
        if (!passes(built[ranked[i]])) continue;
        if (chosen < 0) {
            chosen = ranked[i];
        } else {
            alternate[alternates++] = ranked[i];
        }
    }
    if (chosen < 0) return false;
    out = built[chosen];
    for (int k = 0; k < alternates; ++k) out.alternates.push_back(built[alternate[k]]);
    t.chosen = chosen;
    t.alternates = alternates;
    return true;
}

//! build's solver of a chain, or std::nullopt (the family's builder as a C++ program or
//! the binding calls it: `km::general6r::build(chain)`).
inline std::optional<General6RParams> build(const Chain& chain) {
    General6RParams p;
    if (!build(chain, p)) return std::nullopt;
    return p;
}

}  // namespace km::general6r
