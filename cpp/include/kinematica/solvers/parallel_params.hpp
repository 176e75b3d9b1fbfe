// Three-parallel 6R arms (UR type): the arm's parameters, the family's tolerances, and
// the pairs (q1, q5) the solver works through.
//
// ParallelParams holds the arm (base frame, q = 0) as kinematica.ik.analytic.parallel
// fills it. The method is described in parallel_pairs.hpp (the pairs (q1, q5)),
// parallel_quartic.hpp (axes 5 and 6 apart) and parallel.hpp (the rest).
#pragma once

#include "../config.hpp"
#include "../ik_types.hpp"
#include "../trig.hpp"
#include "../types.hpp"

namespace km {

//! How axes 5 and 6 lie: they decide which equation holds q1 alone.
enum class ParallelMode : int {
    meet = 0,      //!< axes 5 and 6 meet (every UR and its clones)
    parallel = 1,  //!< axes 5 and 6 parallel
    general = 2,   //!< apart (a5 != 0): the quartic
};

//! A UR-type arm (axes 2, 3, 4 parallel) for the closed form of parallel.hpp.
struct ParallelParams {
    // --- vectors, base frame, q = 0
    Vec3 k;       //!< direction of axes 2, 3, 4 (along axis 2)
    Vec3 h1;      //!< axis 1 direction
    Vec3 p1;      //!< a point on axis 1
    Vec3 kpar;    //!< (h1·k) h1: k1 = kpar + cos q1 kperp + sin q1 hk
    Vec3 kperp;   //!< k - kpar
    Vec3 hk;      //!< h1 × k
    Vec3 h5;      //!< axis 5 direction
    Vec3 p5;      //!< on axis 5: foot of the common normal with axis 6 (their meeting point)
    Vec3 h6;      //!< axis 6 direction
    Vec3 p6;      //!< on axis 6: foot of the common normal with axis 5
    Vec3 h6par;   //!< (h5·h6) h5: R5 h6 = h6par + cos q5 h6perp + sin q5 h5xh6
    Vec3 h6perp;  //!< h6 - h6par
    Vec3 h5xh6;   //!< h5 × h6
    Vec3 p2;      //!< a point on axis 2
    Vec3 p4;      //!< a point on axis 4
    Vec3 e1;      //!< unit vector across k: plane coordinates are (·e1, ·e2)
    Vec3 e2;      //!< k × e1
    Pose home;    //!< M, the tool pose at q = 0
    Vec3 p1s;     //!< on axis 1: foot of the common normal with axis 2
    Vec3 a6;      //!< on axis 6: |G(a6) - p1s| <= bound for every reachable target
    // --- scalars
    ParallelMode mode = ParallelMode::meet;
    //! k·R5 h6 = D1 cos q5 + E1 sin q5 + F1 (equation (1)'s right side)
    double D1 = 0.0, E1 = 0.0, F1 = 0.0;
    //! the right side of (2), F2 including k·(p5 - p1)
    double D2 = 0.0, E2 = 0.0, F2 = 0.0;
    //! 2x2 row-major inverse of [[D1, E1], [D2, E2]] (ParallelMode::general)
    double minv[4] = {0.0, 0.0, 0.0, 0.0};
    double wlo = 0.0;    //!< 1 - |D1, E1| - F1, exactly (1 - the largest k·R5 h6)
    double whi = 0.0;    //!< 1 - |D1, E1| + F1, exactly (1 + the smallest k·R5 h6)
    double len_a = 0.0;  //!< |A|, A the plane coordinates of p3 - p2
    double len_b = 0.0;  //!< |B|, B the plane coordinates of p4 - p3
    double arg_a = 0.0;  //!< arg A
    double arg_b = 0.0;  //!< arg B
    double zup[2] = {0.0, 0.0};  //!< plane coordinates of h1 × k ("elbow up" side)
    double sign3 = 1.0;  //!< h3·k = ±1
    double sign4 = 1.0;  //!< h4·k = ±1
    double bound = 0.0;  //!< reach bound about p1s (m)
    double lip = 1.0;    //!< |h1·k| + |kperp|: (2)'s sides move at most this per metre of target
    double scale = 1.0;  //!< size of the arm (m), for relative tolerances
    //! how far the real arm may put axis 4 from this one's (m): 0 for an arm of the
    //! family, the line geometry's slack for a near-degenerate one (the triangle's elbows
    //! then straddle its fold)
    double slack = 0.0;
    double q1rep = 0.0;  //!< q1 given when q1 is free (middle of its limits)
    double q2rep = 0.0;  //!< q2 given when q2 is free

    //! Candidate slots: four pairs (q1, q5) times two elbows.
    KM_HD int slots() const { return 8; }
    KM_HD int dof() const { return 6; }
    //! Every solution of one target T (base frame): candidates Q (8, 6, row-major; NaN
    //! rows: no real solution on that branch) and info. Defined in parallel.hpp.
    KM_HD void solve(const Pose& T, double* Q, SolverInfo& info) const;
    //! solve(), and how close its pairs (q1, q5) and elbows lie to the family's singular
    //! sets (rad; parallel.hpp's pair_margin, 0 where q1 is free).
    KM_HD void solve(const Pose& T, double* Q, SolverInfo& info, double& margin) const;
};

namespace parallel {

//! A point within this fraction of the arm's size from an axis, or two unit vectors
//! within this sine of parallel, is on it: the solutions form a continuum (q1 free with
//! the wrist point on axis 1; q6 free with axis 6 along k; q2 free with axis 4 on axis
//! 2). Moving along such a continuum moves the tool by at most about this fraction of
//! the arm's size.
constexpr double CONTINUUM_TOL = 1e-12;
//! Axis 6 within this sine of k (the wrist nearly aligned, beyond CONTINUUM_TOL): q4 and
//! q6 turn about axes that far from one, so configurations along the continuum of the
//! aligned wrist move the tool by about this fraction of the arm's size per radian, and
//! an arc of them meets the tolerances around each solution; on an arm whose axes 2-4
//! are parallel only within the line geometry's tolerance, the real solutions lie
//! anywhere along it (near_6r.hpp gives such an arm the general 6R's candidates too).
//! The target is marked near.
constexpr double NEAR_ALIGNED_TOL = 1e-7;
//! An equation missing a root by at most this (relative to the arm's size, or absolute
//! for unit vectors) may be a double root moved by round-off or a target within
//! tolerance of the workspace boundary: its least-squares angle is proposed (the check
//! decides by FK) and the target is marked near. Two merging quartic roots split into a
//! complex pair a ± bi with b about the square root of such a miss: roots with
//! |b| <= sqrt(NEAR_TOL) (1 + |t|) are polished as real, and kept when they then meet
//! (1) and (2) to TRIG_TOL (a root) or NEAR_TOL (near).
constexpr double NEAR_TOL = 1e-6;
//! The two roots of a cos θ + b sin θ = c (q1, or q5 when axes 5 and 6 are parallel)
//! whose discriminant r² - c² is within this fraction of r² are one double root:
//! round-off of the target (~1e-16) splits a double root into two roots about 1e-8
//! apart, which the other joints amplify past the check's deduplication.
constexpr double DOUBLE_ROOT_TOL = 1e-14;

//! Where q1 turns freely, the q1 values at which the pairs are sought: q1rep + 2π j /
//! FREE_Q1_SAMPLES (j = 0 .. FREE_Q1_SAMPLES - 1). The continuum through a solution spans
//! an arc of q1 that ends where q5 or the elbow reaches a double root; a pair may have
//! several arcs, each lying anywhere (q1rep may lie off all of them: on an arm whose
//! range of k·R5 h6 is less than [-1, 1], or with axes 5 and 6 apart), and each arc gets
//! its own representative (parallel.hpp's free_q1_arcs). An arc shorter than the step,
//! 2π / FREE_Q1_SAMPLES (0.098 rad), may be stepped over: where no arc is found the
//! target is then at once on a continuum and within about that of its end, and is
//! marked near (not found, never unreachable).
constexpr int FREE_Q1_SAMPLES = 64;

//! What a pair is: none, a root, or a representative of a continuum in which q1 turns
//! freely (the other joints following it).
enum class PairKind : int { none = 0, root = 1, free_q1 = 2 };

//! One pair (q1, q5) with its cosines and sines, and the seed a quartic root starts from.
struct Pair {
    double q1 = NaN, q5 = NaN, c1 = NaN, s1 = NaN, c5 = NaN, s5 = NaN;
    double seed1 = NaN, seed5 = NaN;
};

//! The (up to) four pairs of one target and what each is.
struct Pairs {
    Pair pair[4];
    PairKind kind[4] = {PairKind::none, PairKind::none, PairKind::none, PairKind::none};
    //! q1 turns freely (an equation independent of q1), whether or not the other
    //! equation has a root at the representative q1 tried
    bool free_q1 = false;
};

//! A direction y seen by (1) or (2): k1·y = a cos q1 + b sin q1 + c.
struct Sides {
    double a = 0.0, b = 0.0, c = 0.0;
};

//! max(a, b) by Python's rule: b only when b > a holds (a on a tie, and when either is
//! NaN). Unlike fmax it is defined on signed zeros, so every build gives the same bits.
KM_HD inline double larger(double a, double b) { return b > a ? b : a; }
//! min(a, b) by Python's rule: b only when b < a holds.
KM_HD inline double smaller(double a, double b) { return b < a ? b : a; }

//! k1 = R1 k, the direction of axis 2 after joint 1 turns by q1.
KM_HD inline Vec3 axis2_now(const ParallelParams& P, double c1, double s1) {
    return {P.kpar.x + c1 * P.kperp.x + s1 * P.hk.x, P.kpar.y + c1 * P.kperp.y + s1 * P.hk.y,
            P.kpar.z + c1 * P.kperp.z + s1 * P.hk.z};
}

//! pair = (q1, q5, cos q1, sin q1, cos q5, sin q5).
KM_HD inline void store_pair(Pair& pair, double q1, double q5) {
    pair.q1 = q1;
    pair.q5 = q5;
    sincos(q1, pair.s1, pair.c1);
    sincos(q5, pair.s5, pair.c5);
}

}  // namespace parallel
}  // namespace km
