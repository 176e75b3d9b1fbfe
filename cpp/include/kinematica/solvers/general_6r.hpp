// Closed-form IK of any 6R arm: Raghavan-Roth elimination, Manocha-Canny's eigenproblem.
//
// Any revolute chain is a loop of rotations about z and fixed transforms (the target T in
// one of them, built by the Python builder for a chosen labelling of the joints):
//
//     I = Rz(q'1) L1 Rz(q'2) L2 Rz(q'3) L3 Rz(q'4) L4 Rz(q'5) L5 Rz(q'6) L6
//
// q'k = sign · q[order[k]] (the chain rotated cyclically, or reversed: sign -1). Joint 3'
// turns about the z axis of the frame after L2, so that line (point p, direction l) is
//
//     Rz(q'1) L1 Rz(q'2) L2 · z  =  L6⁻¹ Rz(-q'6) L5⁻¹ Rz(-q'5) L4⁻¹ Rz(-q'4) L3⁻¹ · z
//
// (q'3 eliminated). The left side's 14 quantities p, l, p·p, p·l, p×l,
// (p·p) l - 2 (p·l) p are c0 + Q S2 with S2 the 8 products of (1, c1', s1') ⊗
// (1, c2', s2') but 1 (Raghavan-Roth: these quantities keep that form), Q 14 x 8 and c0
// found exactly from the left side's values on a 3 x 3 grid of (q'1, q'2) (eliminate()).
// Where L1 and L2 hold no T they are constants of the arm, computed once; where one of
// them holds T (t_link 0 or 1: the labelling that starts at the joint after the target)
// they are computed for each target. That choice matters: on arms whose axes meet or are
// parallel in many pairs (FANUC CRX, Kinova JACO 2: every common normal but one of length
// 0), the 8 labellings with constant c0, Q all give det M(x6) ≡ 0, while one of the 4
// with T on the left gives a well-posed pencil (its roots accurate to 1e-14 there).
// N (6 x 14), the left null space of Q, leaves 6 equations
// N (F(q'4, q'5, q'6) - c0) = 0 in the right side only. Each is a trilinear trigonometric
// polynomial; it is found exactly from its values on a 3 x 3 x 3 grid of angles (shifted
// by phi, so that no genuine root sits at tan(π/2)), then the half-angle substitution
// x = tan((q' - phi)/2) makes it a polynomial of degree 2 in each of x4, x5, x6. The 6
// equations and their products with x4 are 12 equations linear in the 12 monomials
// x4^i x5^j (i <= 3, j <= 2): M(x6) u = 0 with M = A0 + A1 x6 + A2 x6², so det M(x6) = 0
// (degree 24, (1 + x6²)⁴ a factor: up to 16 genuine real roots). Its roots are the
// eigenvalues of the 24 x 24 companion matrix, solved as a 16 x 16 one once the 8 at ±i
// are eliminated (general_6r_roots.hpp; the generalized eigenproblem by QZ where A2 is
// ill-conditioned); each real one gives u (M's null vector) hence
// x4, x5, then S2 = Q⁺(F - c0) gives q'1, q'2 and the loop's closure q'3. The shared
// check polishes every candidate by Gauss-Newton on the full pose, dedupes and judges it.
//
// Alternates. The labelling is chosen on probe poses, and an arm near one whose elimination
// degenerates can have a target where the chosen one proves nothing while others are
// well posed: a Kawasaki RS007N with every DH value moved by 2.7e-8 (its spherical wrist
// broken by that), the chosen labelling's pencil nearly singular for every x6 there (M's
// second smallest singular value 1.5e-11 of its largest at the generating root), A2's
// rcond 1.2e-8 (just above LEADING_RCOND_TOL, so the companion matrix is used, not QZ),
// the eigenvalues near the generating root 5e-5 off: no candidate within REFINE_LIMIT
// of a solution that Newton's step can take there, where another labelling's pencil
// (A2's rcond 1.6e-4) gives all 8 to round-off. So the builder keeps the next labellings
// that pass its probes (ALTERNATES, the most accurate first), and where none of the
// chosen one's candidates closes the loop for a target within reach and its elimination
// was ill-conditioned there (ALTERNATE_RCOND), they are tried in turn: the first whose
// candidates close answers.
//
// Why Eigen: the LUs (A2's, with its condition estimate; M's null vector by full
// pivoting) are Eigen's, well kept and tested. The eigenvalues are the core's own
// (eigenvalues.hpp: twice as fast at this size). Only these headers and their binding
// include Eigen.
//
// Out of reach. Every solution makes a real root of det M(x6) (M(x6) u = 0 with u its
// monomial vector, homogenized where q'4 or q'5 is at the shift + π), and a well-conditioned
// A2 puts no root at x6 = ∞. So where no candidate closes, the deflated eigenvalues (16,
// or 24 - 2m where M(i)'s null space has m > 4 dimensions) are checked off the real axis: each one's distance |Im x| over κ(x) (η(x) + PENCIL_EPS), its
// condition number times its backward error plus the pencil's own round-off, must reach
// CERTIFY_MARGIN (general_6r_roots.hpp: real_axis_margin). Then no solution exists: the
// answer is "unreachable". Random arms' targets beyond the workspace are proved so from
// about 1e-7 m out (the margin grows as the distance: the pair nearest the axis splits as
// its square root, its condition as its inverse square root); nearer, a candidate closes
// or the margin falls short, and the numeric search is asked. Where the 8 roots at ±i were
// not deflated, or QZ gave the roots, nothing is proved this way.
//
// Where the method degenerates. A candidate that closes the loop where the loop's Jacobian
// loses rank (σ6/σ1 below SINGULAR_RANK_TOL) is at a double root (a fold: two branches
// meet) or on a continuum (a self-motion: the pose held while joints turn). The two are
// told apart by following the Jacobian's null direction: a step of SELF_MOTION_STEP along
// it, then Gauss-Newton on five joints with the sixth held (the one the step moves most)
// back to the target. On a continuum the loop closes again to round-off (within
// SELF_MOTION_TOL), and the joints that moved (by more than FREE_JOINT_TOL) are the free
// ones: the answer is singular, those joints named, the candidates representatives. At
// a fold it cannot (the target is missed by about the curvature times the step squared):
// near is raised, as for the other families' double roots.
//
// Branch labels: a candidate's class is the signs of sin q2, sin q3, sin q5 (joint values
// in (0, π) or not), 4 slots per class ordered by q1; a ninth group of slots holds the
// members beyond 4 of a class (rare), labelled "further solution".
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <complex>
#include <cstdint>
#include <optional>
#include <vector>

#include "../check.hpp"
#include "../config.hpp"
#include "../ik_types.hpp"
#include "../linalg.hpp"
#include "../so3.hpp"
#include "../trig.hpp"
#include "../types.hpp"
#include "general_6r_roots.hpp"

namespace km::general6r {

constexpr int EQUATIONS = 14;  //!< p, l, p·p, p·l, p×l, (p·p) l - 2 (p·l) p
constexpr int PRODUCTS = 8;    //!< the products of (1, c1', s1') ⊗ (1, c2', s2') but 1
constexpr int REDUCED = 6;     //!< equations left once the products are eliminated
constexpr int CLASSES = 8;     //!< sign classes of (sin q2, sin q3, sin q5)
constexpr int PER_CLASS = 4;   //!< slots of one class
constexpr int FURTHER = 8;     //!< slots of the members beyond PER_CLASS of a class
constexpr int SLOTS = CLASSES * PER_CLASS + FURTHER;

//! The companion matrix A2⁻¹(...) is used when A2's reciprocal condition number (LU
//! estimate) is above this; below (a root near x6 = ∞), the pencil is made again with
//! q'6 shifted by SECOND_SHIFT more, which brings that root to a finite x6. Below it at
//! both shifts (M(x6) nearly singular for every x6: a calibrated UR5, whose exact arm's
//! det M(x6) ≡ 0), the roots are the generalized eigenvalues by QZ (real_roots_qz: a
//! few times the companion's cost, no inverse of A2).
constexpr double LEADING_RCOND_TOL = 1e-8;
//! The second shift of q'6 (rad): far from 0 and π, so that a root at x6 = ∞ for the
//! first is at |x6| = 1 / tan(SECOND_SHIFT / 2) ≈ 1.5 for the second.
constexpr double SECOND_SHIFT = 1.1;
//! A candidate "closes the loop" when the pose it makes is within this of the target (m
//! or rad, the larger; measured as the shared check measures it): half the check's
//! POLISH_LIMIT, so that a candidate that closes is one the check polishes (and calls the
//! target "close"). Where none closes and the pencil has no real root, proven
//! (certifies: every eigenvalue CERTIFY_MARGIN times its error bound from the real axis),
//! the target is out of reach ("unreachable", without a gap). Otherwise near is raised: the
//! elimination proves nothing (a root lost to round-off at a near-double root, a root
//! no solution makes, or the target just out of reach: it cannot tell), so the check says
//! not_found and the numeric search is asked.
constexpr double CLOSURE_TOL = 0.5 * POLISH_LIMIT;
//! A candidate whose pose misses the target by up to this (m or rad; by anything above
//! 0: one that misses by 1e-13 is 1e-13 / σmin off in its joints, 1e-8 at the σmin of
//! 1e-5 seen on calibrated UR5s, where the check takes it as it is, its tolerance
//! 1e-10) is taken by Newton's method on the full pose to the solution near it. Candidates
//! beyond the check's polish (POLISH_LIMIT) come from roots the eigenproblem gets to
//! 1e-5..1e-3 only: on arms near one whose elimination degenerates (a calibrated UR:
//! M(x6) nearly singular for every x6), where an eigenvalue's error is round-off over
//! that distance: misses up to 2e-2 were seen on 2,000 poses of that UR (solutions lost
//! when this was 1e-2). Beyond this the candidate is not near a solution (a complex
//! root's real part: misses of 0.3 and more), and Newton would only wander to another
//! candidate's.
constexpr double REFINE_LIMIT = 1e-1;
//! A split pair's candidate (general_6r_roots.hpp: SPLIT_ROOT_TOL) that Newton takes no
//! nearer than this (m or rad) to the target is at a fold's near miss (a complex pair of
//! solutions), not at a solution, and dropped: one that converges reaches round-off
//! (2e-16 to 7e-16 measured on calibrated UR5s), while a fold's complex pair is split
//! only past REAL_ROOT_TOL (|Im x| of 1e-4 and more; below, its real part is taken as a
//! real root), and its imaginary part grows as the square root of the target's miss:
//! a miss of about 1e-8 (arm-size units) and more (an estimate, not a measurement).
constexpr double SPLIT_CLOSURE_TOL = 1e-12;

//! A candidate that misses the target by more than this before Newton's step (m or rad),
//! of a root another is close to (PAIR_ROOT_TOL), is looked for again as one of two
//! solutions sharing that root x6 (null_pair): a genuine
//! simple root is got to round-off (1e-15..1e-12 on random and makers' arms), while two
//! solutions with one q'6 (a double root: M(x6)'s null space two-dimensional, its one null
//! vector a mix of theirs) give a candidate that misses by 1e-3 and more, and Newton's step
//! may take it to neither (the FANUC CRX-10iA/L: 1 pose in 11,000, 3 of its 4 solutions
//! found). So do the roots of near-real complex pairs (1e-4 and more), whose real part is
//! computed twice: the extraction runs there too.
constexpr double RESOLVE_TOL = 1e-6;
//! A candidate within this (rad, every joint, modulo 2π) of one in the slots already is the
//! same solution and is not added again (both refined to round-off).
constexpr double SAME_CANDIDATE_TOL = 1e-8;

//! True when a candidate that missed by `miss` (m or rad) before Newton's step is looked for
//! again as one of a pair sharing its root (RESOLVE_TOL).
KM_HD inline bool resolves(double miss) { return miss > RESOLVE_TOL; }
//! Two roots x6 within this (relative to 1 + |x|) are one double root: a double root is
//! computed as two reals or a complex pair about √ε·|x| apart (its real part twice), and
//! only there is the extraction run (not at the extraneous real roots some special arms'
//! determinants have at every pose: the Agilex Piper, Doosan M0609, whose candidates miss
//! at 99-100 % of poses, 160-290 µs a pose when each was looked at).
constexpr double PAIR_ROOT_TOL = 1e-4;
//! True when the roots x and y are one double root (PAIR_ROOT_TOL).
KM_HD inline bool close_roots(double x, double y) {
    return std::fabs(x - y) <= PAIR_ROOT_TOL * (1.0 + std::fmax(std::fabs(x), std::fabs(y)));
}

//! True when a split pair's candidate that Newton took to within `closure` of the target
//! (m or rad) is a solution (SPLIT_CLOSURE_TOL).
KM_HD inline bool split_closes(double closure) { return closure <= SPLIT_CLOSURE_TOL; }
//! Newton steps at most (quadratic from REFINE_LIMIT: 1e-1, 1e-2, 1e-4, 1e-8, 1e-15,
//! then the noise floor stops it).
constexpr int REFINE_STEPS = 8;
//! A candidate that closes the loop (CLOSURE_TOL) is at a singular configuration, and
//! tested for a self-motion, when its loop Jacobian's σ6/σ1 (lengths scaled to the arm's
//! size) is below this. On a continuum it is round-off (1e-18..5e-17 measured, the
//! candidate Newton-refined onto it); at a fold the elimination's double root is good to
//! about √ε in the joints and Newton's steps, linear there, take it on (1e-17..3e-9
//! measured). A regular solution whose fold partner is δ rad away has σ6/σ1 of about δ,
//! and the pair is lost to round-off (a complex pair) when δ nears √ε: above this, a fold
//! is far enough for both to be found, and near is not raised.
constexpr double SINGULAR_RANK_TOL = 1e-7;
//! The step (rad, along the unit null direction of the loop's Jacobian) of the
//! self-motion test: large enough that at a fold the held joint leaves the re-closed
//! loop a miss of about the curvature times its square (1e-6..5e-6 measured), far above
//! SELF_MOTION_TOL; small enough that on a continuum Gauss-Newton starts within the
//! curvature times its square of the family and converges in a few steps.
constexpr double SELF_MOTION_STEP = 1e-2;
//! Gauss-Newton steps of the re-closure at most (quadratic from 1e-4: 1e-8, 1e-16 in
//! three, then the noise floor stops it).
constexpr int SELF_MOTION_STEPS = 8;
//! After the step, the loop re-closed with one joint held misses the target by at most
//! this (m or rad): a continuum, or the target within this of one. On one it is
//! round-off (2e-16..1e-15 measured); a fold leaves 1e-6 and more.
constexpr double SELF_MOTION_TOL = 1e-12;
//! A joint that moved by more than this (rad) between the candidate and the re-closed
//! point on its continuum (a step of SELF_MOTION_STEP) is free: one the family holds
//! stays to round-off (below 4e-15 measured), one that moves does by a share of the step
//! (7e-3 for two coaxial axes) or, where it moves only at second order, its square.
constexpr double FREE_JOINT_TOL = 1e-8;

//! True when a joint that moved by d (rad) along a continuum is free (FREE_JOINT_TOL).
KM_HD inline bool moves(double d) { return d > FREE_JOINT_TOL; }

//! The grid of angles the trigonometric polynomials are found from: 0, 2π/3, 4π/3.
constexpr double GRID_STEP = 2.0 * PI / 3.0;
//! A left side is rank-deficient (its products cannot be eliminated: the labelling is
//! unusable, for the arm or, with T on the left, for that target) when σ8 / σ1 of its
//! 14 x 8 matrix Q is below this.
constexpr double RANK_TOL = 1e-9;
//! Labellings kept beside the chosen one (general_6r_build.hpp: the next that pass the
//! probes, the most accurate first), tried in turn where none of the chosen one's
//! candidates closes the loop for a target within reach (its elimination proves nothing
//! there). Not where a closing candidate came from an inaccurate root (a miss before
//! Newton's step of 1e-6..1e-1): on 5,400 poses of the makers' arms that have
//! alternates, 1-4 % of an arm's poses had one, and adding the first alternate's
//! candidates there changed no answer.
constexpr int ALTERNATES = 2;
//! The alternates are tried only where the chosen labelling's elimination was
//! ill-conditioned for the target: A2's reciprocal condition (at the first shift) below
//! this, its left side rank-deficient, or its eigenvalue iteration failed. A well-posed
//! pencil that closes no loop has lost no root: on 848 perturbed makers' arms (seeds 3
//! and 5, 16 a makers' arm) the alternates closed no loop the chosen one missed on 16,960
//! FK poses nor on 16,960 of random orientation, where they ran on 2,888 (17 %: twice or
//! three times a solve each) and 18 of those were below this. The one target they answer
//! (a Kawasaki RS007N moved by 2.7e-8) is at 1.2e-8.
constexpr double ALTERNATE_RCOND = 1e-6;

//! What one solve decided, for the tests of its tolerances (solve fills it when given).
struct Trace {
    double rcond = NaN;    //!< A2's reciprocal condition number at the first shift (LU estimate)
    double shift6 = NaN;   //!< the q'6 shift the pencil was made with
    double closure = INF;  //!< the smallest miss of a candidate (m or rad; INF: no candidate)
    bool deflated = false; //!< the roots at x6 = ±i were eliminated before the eigenproblem
    bool qz = false;       //!< A2 ill-conditioned at both shifts: the roots by QZ
    double rank = NaN;     //!< the smallest σ6/σ1 computed at a closing candidate (NaN: none)
    double reclosure = INF;  //!< the smallest miss of a self-motion test's re-closure
    bool resolved = false;   //!< a root's null space was taken as two-dimensional (RESOLVE_TOL)
    int answered = 0;        //!< the labelling whose candidates were kept: 0 this one, k alternate k
    int tried = 0;           //!< alternates whose pass ran
    //! the chosen labelling's spectrum_margin where none of its candidates closed (value
    //! NaN: not computed, one closed or its eigenvalues were not deflated)
    RootMargin margin{NaN};
};

//! What the self-motion test says of a candidate that closes the loop.
enum class Degeneracy : int {
    regular = 0,    //!< its Jacobian has full rank (σ6/σ1 above SINGULAR_RANK_TOL)
    fold = 1,       //!< rank-deficient, no self-motion: a double root (near)
    continuum = 2,  //!< a self-motion: joints turn with the pose held (singular, free joints)
};

//! The self-motion test's measurements at one candidate (for its tolerances' tests).
struct SelfMotion {
    Degeneracy verdict = Degeneracy::regular;
    double rank = NaN;        //!< σ6/σ1 of the loop's Jacobian (NaN: not computed, the screen passed it)
    double reclosure = INF;   //!< the smallest miss of the re-closures (m or rad; INF: none)
    double moved[6] = {};     //!< per loop joint, how far it moved on the continuum (rad)
    std::uint32_t free = 0;   //!< bit k: loop joint k is free
};

//! The line (point, direction) a loop carries.
struct Line {
    Vec3 p{}, l{0.0, 0.0, 1.0};
};

//! A transform applied to a line.
KM_HD inline Line apply(const Pose& A, const Line& L) { return {A.apply(L.p), A.rotate(L.l)}; }

//! Rz(a) applied to a line (c, s: cosine and sine of a).
KM_HD inline Line turn(double c, double s, const Line& L) {
    return {{c * L.p.x - s * L.p.y, s * L.p.x + c * L.p.y, L.p.z},
            {c * L.l.x - s * L.l.y, s * L.l.x + c * L.l.y, L.l.z}};
}

//! Rz(a) as a pose.
KM_HD inline Pose rz(double a) {
    double s, c;
    sincos(a, s, c);
    Pose P;
    P.x = {c, s, 0.0};
    P.y = {-s, c, 0.0};
    return P;
}

//! The 14 quantities of a line's point and direction.
KM_HD inline void quantities(const Line& L, double* f) {
    const Vec3& p = L.p;
    const Vec3& l = L.l;
    const double pp = dot(p, p), pl = dot(p, l);
    const Vec3 x = cross(p, l);
    f[0] = p.x, f[1] = p.y, f[2] = p.z;
    f[3] = l.x, f[4] = l.y, f[5] = l.z;
    f[6] = pp, f[7] = pl;
    f[8] = x.x, f[9] = x.y, f[10] = x.z;
    f[11] = pp * l.x - 2.0 * pl * p.x;
    f[12] = pp * l.y - 2.0 * pl * p.y;
    f[13] = pp * l.z - 2.0 * pl * p.z;
}

//! From a trigonometric polynomial's values at the grid angles (0, 2π/3, 4π/3) to the
//! coefficients of 1, x, x² of (1 + x²) times it, x = tan(angle/2): the inverse of the
//! grid's (1, cos, sin) matrix, then (1, c, s)(1 + x²) = (1 + x², 1 - x², 2x).
constexpr double HALF_ANGLE[3][3] = {
    {1.0, 0.0, 0.0},
    {0.0, 1.1547005383792515, -1.1547005383792515},  // ±2/√3
    {-1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0},
};

//! From a trigonometric polynomial's values at the grid angles (0, 2π/3, 4π/3) to its
//! coefficients of 1, cos, sin: the inverse of the grid's (1, cos, sin) matrix.
constexpr double FROM_GRID[3][3] = {
    {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0},
    {2.0 / 3.0, -1.0 / 3.0, -1.0 / 3.0},
    {0.0, 0.5773502691896258, -0.5773502691896258},  // ±1/√3
};

//! The elimination's constants of one left side Rz(q'1) L1 Rz(q'2) L2 (lengths scaled).
struct Elimination {
    double N[REDUCED][EQUATIONS]{};    //!< left null space of Q (rows orthonormal)
    double c0[EQUATIONS]{};            //!< the left side's constant part
    double Qp[PRODUCTS][EQUATIONS]{};  //!< Q's pseudo-inverse
};

//! The left side's quantities as c0 + Q S2: its values on the 3 x 3 grid of (q'1, q'2),
//! then FROM_GRID along each angle. S2 (Q's columns): c2, s2, c1, c1 c2, c1 s2, s1, s1 c2,
//! s1 s2 (the products of (1, c1, s1) ⊗ (1, c2, s2) but 1, in that order).
KM_HD inline void left_side(const Pose& L1, const Pose& L2, double* c0, double (*Q)[PRODUCTS]) {
    double F[3][3][EQUATIONS];
    for (int a = 0; a < 3; ++a) {
        const Pose A = rz(a * GRID_STEP) * L1;
        for (int b = 0; b < 3; ++b) {
            const Pose B = A * rz(b * GRID_STEP) * L2;
            quantities(Line{B.p, B.rotate(Vec3{0.0, 0.0, 1.0})}, F[a][b]);
        }
    }
    for (int e = 0; e < EQUATIONS; ++e)
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                double v = 0.0;
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b) v += FROM_GRID[i][a] * FROM_GRID[j][b] * F[a][b][e];
                if (i == 0 && j == 0) {
                    c0[e] = v;
                } else {
                    Q[e][3 * i + j - 1] = v;
                }
            }
}

//! The elimination's constants of the left side L1, L2 into E: c0, Q's left null space
//! and pseudo-inverse from its SVD. Returns σ8 / σ1 of Q; below RANK_TOL, E is unusable.
inline double eliminate(const Pose& L1, const Pose& L2, Elimination& E) {
    using Matrix14x8 = Eigen::Matrix<double, EQUATIONS, PRODUCTS>;
    double Qa[EQUATIONS][PRODUCTS];
    left_side(L1, L2, E.c0, Qa);
    Matrix14x8 Q;
    for (int e = 0; e < EQUATIONS; ++e)
        for (int k = 0; k < PRODUCTS; ++k) Q(e, k) = Qa[e][k];
    const Eigen::JacobiSVD<Matrix14x8> svd(Q, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const auto& s = svd.singularValues();
    const double ratio = s(0) > 0.0 ? s(PRODUCTS - 1) / s(0) : 0.0;
    if (!(ratio > RANK_TOL)) return ratio;
    const auto& U = svd.matrixU();
    const auto& V = svd.matrixV();
    for (int r = 0; r < REDUCED; ++r)
        for (int e = 0; e < EQUATIONS; ++e) E.N[r][e] = U(e, PRODUCTS + r);
    for (int k = 0; k < PRODUCTS; ++k)
        for (int e = 0; e < EQUATIONS; ++e) {
            double v = 0.0;
            for (int j = 0; j < PRODUCTS; ++j) v += V(k, j) * U(e, j) / s(j);
            E.Qp[k][e] = v;
        }
    return ratio;
}

//! A general 6R arm: its loop for one labelling of the joints, and the elimination's
//! constants (lengths scaled by `scale`, so that the arm's size is about 1): the
//! Elimination's fields, used where L1 and L2 hold no target (t_link 2..5).
struct General6RParams : Elimination {
    Pose link[6]{};          //!< L1 ... L6 (the one holding T: unused)
    int t_link = 5;          //!< which L holds the target: L = t_pre · T^t_power · t_post
    int t_power = -1;        //!< +1 or -1
    Pose t_pre{}, t_post{};  //!< (scaled lengths)
    int order[6] = {0, 1, 2, 3, 4, 5};  //!< q'k = sign · q[order[k]]
    double sign = 1.0;                  //!< -1: the chain reversed
    double scale = 1.0;                 //!< lengths times this (1 / the arm's size)
    double phi[3] = {0.0, 0.0, 0.0};    //!< shifts of q'4, q'5, q'6 (rad)
    //! The tool origin stays within `reach` (m) of `centre` (base frame, m): a point on
    //! axis 1 and the sum of the joints' fixed offsets. Beyond it: a proven gap.
    Vec3 centre{};
    double reach = INF;
    //! Take candidates that miss by up to REFINE_LIMIT to the solution near them
    //! (false: as the eigenproblem gives them; for the tests of the other tolerances).
    bool refine_misses = true;
    //! The next labellings that pass the builder's probes (at most ALTERNATES, the most
    //! accurate first; their own alternates empty): where this one's candidates close no
    //! loop for a target within reach, the first whose do answers.
    std::vector<General6RParams> alternates;

    int slots() const { return SLOTS; }

    //! Why these fields cannot be solved with (nullptr when they can).
    const char* invalid() const {
        if (t_link < 0 || t_link > 5) return "t_link must be 0 ... 5";
        if (t_power != 1 && t_power != -1) return "t_power must be 1 or -1";
        if (sign != 1.0 && sign != -1.0) return "sign must be 1 or -1";
        bool seen[6] = {};
        for (int k = 0; k < 6; ++k) {
            if (order[k] < 0 || order[k] > 5 || seen[order[k]]) return "order must be a permutation of 0..5";
            seen[order[k]] = true;
        }
        return nullptr;
    }
    int dof() const { return 6; }
    //! True when L1 or L2 holds the target: c0, N, Qp are computed for each target.
    bool per_target() const { return t_link < 2; }

    //! L_k of one target (T scaled).
    Pose link_of(int k, const Pose& T) const {
        if (k != t_link) return link[k];
        return t_pre * (t_power > 0 ? T : inverse(T)) * t_post;
    }

    //! The right side's line at (q'4, q'5, q'6), from the inverses Li of L3 ... L6.
    static Line right_side(const Pose* Li, double a4, double a5, double a6) {
        double s, c;
        Line L = apply(Li[0], Line{});
        sincos(a4, s, c);
        L = apply(Li[1], turn(c, -s, L));
        sincos(a5, s, c);
        L = apply(Li[2], turn(c, -s, L));
        sincos(a6, s, c);
        return apply(Li[3], turn(c, -s, L));
    }

    //! The 12 x 12 matrices A0, A1, A2 of M(x6) for the inverses Li of L3 ... L6, with
    //! x6 = tan((q'6 - shift6) / 2).
    void pencil(const Elimination& E, const Pose* Li, const double* ph, double shift6,
                Matrix12 A[3]) const {
        // G[a][b][c][e]: the 6 equations at the grid point (a, b, c)
        double G[3][3][3][REDUCED];
        for (int a = 0; a < 3; ++a) {
            double s, c;
            sincos(a * GRID_STEP + ph[0], s, c);
            const Line L4 = apply(Li[1], turn(c, -s, apply(Li[0], Line{})));
            for (int b = 0; b < 3; ++b) {
                sincos(b * GRID_STEP + ph[1], s, c);
                const Line L5 = apply(Li[2], turn(c, -s, L4));
                for (int g = 0; g < 3; ++g) {
                    sincos(g * GRID_STEP + shift6, s, c);
                    double f[EQUATIONS];
                    quantities(apply(Li[3], turn(c, -s, L5)), f);
                    for (int k = 0; k < EQUATIONS; ++k) f[k] -= E.c0[k];
                    for (int e = 0; e < REDUCED; ++e) {
                        double v = 0.0;
                        for (int k = 0; k < EQUATIONS; ++k) v += E.N[e][k] * f[k];
                        G[a][b][g][e] = v;
                    }
                }
            }
        }
        // the half-angle coefficients, one variable at a time: H[i4][i5][i6][e]
        double H1[3][3][3][REDUCED], H2[3][3][3][REDUCED], H[3][3][3][REDUCED];
        half_angle<0>(G, H1);
        half_angle<1>(H1, H2);
        half_angle<2>(H2, H);
        for (int k = 0; k < 3; ++k) A[k].setZero();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k)
                    for (int e = 0; e < REDUCED; ++e) {
                        // equation e times 1 (row 2e) and times x4 (row 2e + 1)
                        A[k](2 * e, 3 * i + j) = H[i][j][k][e];
                        A[k](2 * e + 1, 3 * (i + 1) + j) = H[i][j][k][e];
                    }
    }

    //! HALF_ANGLE applied along one axis (0: q'4, 1: q'5, 2: q'6) of grid values.
    template <int AXIS>
    static void half_angle(const double (&in)[3][3][3][REDUCED], double (&out)[3][3][3][REDUCED]) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k)
                    for (int e = 0; e < REDUCED; ++e) {
                        const int row = AXIS == 0 ? i : (AXIS == 1 ? j : k);
                        double v = 0.0;
                        for (int t = 0; t < 3; ++t) {
                            v += HALF_ANGLE[row][t] * (AXIS == 0   ? in[t][j][k][e]
                                                       : AXIS == 1 ? in[i][t][k][e]
                                                                   : in[i][j][t][e]);
                        }
                        out[i][j][k][e] = v;
                    }
    }

    //! Angle 2 atan2(num, den) + shift of the half-angle ratio num / den.
    static double from_half(double num, double den, double shift) {
        return 2.0 * std::atan2(num, den) + shift;
    }

    //! One candidate's loop angles a (q'1 ... q'6) from a real root x6 and its monomial
    //! vector u, for the target T (scaled). Returns how far its pose is from T (miss).
    double back_substitute(const Elimination& E, const Pose* L, const Pose* Li, const Pose& T,
                           const double* ph, double x6, double shift6, const Vector12& u,
                           double* a) const {
        // x4 = u(i+1, j) / u(i, j), x5 = u(i, j+1) / u(i, j): the best-scaled pair
        int bi = 0, bj = 0;
        double best = -1.0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const double w = u(3 * i + j) * u(3 * i + j) + u(3 * (i + 1) + j) * u(3 * (i + 1) + j);
                if (w > best) best = w, bi = i, bj = j;
            }
        const double a4 = from_half(u(3 * (bi + 1) + bj), u(3 * bi + bj), ph[0]);
        best = -1.0;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 2; ++j) {
                const double w = u(3 * i + j) * u(3 * i + j) + u(3 * i + j + 1) * u(3 * i + j + 1);
                if (w > best) best = w, bi = i, bj = j;
            }
        const double a5 = from_half(u(3 * bi + bj + 1), u(3 * bi + bj), ph[1]);
        const double a6 = 2.0 * std::atan(x6) + shift6;
        double f[EQUATIONS];
        quantities(right_side(Li, a4, a5, a6), f);
        double S[PRODUCTS];
        for (int r = 0; r < PRODUCTS; ++r) {
            double v = 0.0;
            for (int k = 0; k < EQUATIONS; ++k) v += E.Qp[r][k] * (f[k] - E.c0[k]);
            S[r] = v;
        }
        // S: c2, s2, c1, c1 c2, c1 s2, s1, s1 c2, s1 s2 (the builder's order)
        const double a1 = std::atan2(S[5], S[2]);
        const double a2 = std::atan2(S[1], S[0]);
        // closure: Rz(q'3) = (Rz1 L1 Rz2 L2)⁻¹ (L3 Rz4 L4 Rz5 L5 Rz6 L6)⁻¹
        const Pose left = rz(a1) * L[0] * rz(a2) * L[1];
        const Pose right = L[2] * rz(a4) * L[3] * rz(a5) * L[4] * rz(a6) * L[5];
        const Pose W = inverse(right * left);
        const double a3 = std::atan2(W.x.y - W.y.x, W.x.x + W.y.y);
        a[0] = a1, a[1] = a2, a[2] = a3, a[3] = a4, a[4] = a5, a[5] = a6;
        return miss(L, a, T);
    }

    //! The pose (scaled) the loop's angles a (q'1 ... q'6) make. With X the loop's
    //! factors Rz(q'k) L_k before the target's link (and its Rz), Y those after, the loop
    //! X pre T^p post Y = I gives T^p = (post Y X pre)⁻¹.
    Pose pose_of(const Pose* L, const double* a) const {
        Pose X, Y;
        for (int k = 0; k < t_link; ++k) X = X * rz(a[k]) * L[k];
        X = X * rz(a[t_link]);
        for (int k = t_link + 1; k < 6; ++k) Y = Y * rz(a[k]) * L[k];
        const Pose H = t_post * Y * X * t_pre;
        return t_power < 0 ? H : inverse(H);
    }

    //! How far the pose the loop's angles a make is from the target T (scaled): the larger
    //! of the position error (m) and the rotation error (rad), as the shared check
    //! measures a candidate.
    double miss(const Pose* L, const double* a, const Pose& T) const {
        const Pose F = pose_of(L, a);
        return std::fmax(norm(F.p - T.p) / scale, angle_between(F, T));
    }

    //! The loop's product without the target, H(b) = post Y X pre (T^p = H⁻¹ closes the
    //! loop), and its geometric Jacobian J (6 x 6 row-major: rows linear then angular,
    //! column k loop joint k): each joint's axis and origin met along the product.
    Pose loop_jacobian(const Pose* L, const double* b, double* J) const {
        Vec3 axis[6], origin[6];
        Pose H = t_post;
        for (int i = 0; i < 6; ++i) {
            const int k = (t_link + 1 + i) % 6;  // after the target's link, round the loop
            axis[k] = H.rotate(Vec3{0.0, 0.0, 1.0});
            origin[k] = H.p;
            H = H * rz(b[k]);
            if (k != t_link) H = H * L[k];
        }
        H = H * t_pre;
        for (int k = 0; k < 6; ++k) {
            const Vec3 v = cross(axis[k], H.p - origin[k]);
            J[0 * 6 + k] = v.x, J[1 * 6 + k] = v.y, J[2 * 6 + k] = v.z;
            J[3 * 6 + k] = axis[k].x, J[4 * 6 + k] = axis[k].y, J[5 * 6 + k] = axis[k].z;
        }
        return H;
    }

    //! How far the loop's product H misses the target T (scaled), as miss() measures.
    double miss_of(const Pose& H, const Pose& T) const {
        const Pose F = t_power < 0 ? H : inverse(H);
        return std::fmax(norm(F.p - T.p) / scale, angle_between(F, T));
    }

    //! Newton's method on the full pose from the loop angles a whose pose misses T (scaled)
    //! by `from`: at most REFINE_STEPS steps, a taken to the best point met. Returns its
    //! miss. The steps solve H(a) = G for H = post Y X pre (the loop's product without the
    //! target: T^p = H⁻¹, so G = T for p = -1 and T⁻¹ for p = +1), whose Jacobian is the
    //! geometric one of a chain of rotations about z (loop_jacobian), damped as the
    //! check's polish. Ja (6 x 6 row-major) becomes the Jacobian at the a returned.
    double refine(const Pose* L, const Pose& T, double* a, double from, double* Ja) const {
        const Pose G = t_power < 0 ? T : inverse(T);
        double best = from, b[6];
        for (int k = 0; k < 6; ++k) b[k] = a[k];
        for (int step = 0; step <= REFINE_STEPS; ++step) {
            double J[6 * 6], db[6];
            const Pose H = loop_jacobian(L, b, J);
            if (step > 0) {  // the last step's point, judged as miss() judges
                const double now = miss_of(H, T);
                if (!(now < best)) break;  // at the noise floor, or not converging
                best = now;
                for (int k = 0; k < 6; ++k) a[k] = b[k];
            }
            for (int i = 0; i < 6 * 6; ++i) Ja[i] = J[i];  // a is b here
            if (step == REFINE_STEPS) break;
            const Twist e = pose_error(H, G);
            damped_least_squares(J, 6, 6, e.e, POLISH_DAMPING, db);
            for (int k = 0; k < 6; ++k) b[k] += db[k];
        }
        return best;
    }

    //! self_motion at the joint values q (6,), per joint (not per loop joint), of a
    //! solution of the pose T (the arm's frame and units); nullopt where q does not close
    //! the loop to CLOSURE_TOL (the test presumes it). moved and free stay per loop joint
    //! (order maps them to the joints).
    std::optional<SelfMotion> self_motion_at(const Pose& T_in, const double* q) const {
        Pose T = T_in;
        T.p = scale * T.p;
        Pose L[6];
        for (int k = 0; k < 6; ++k) L[k] = link_of(k, T);
        double a[6];
        for (int k = 0; k < 6; ++k) a[k] = sign * q[order[k]];
        if (!(miss(L, a, T) <= CLOSURE_TOL)) return std::nullopt;
        return self_motion(L, T, a);
    }

    //! The self-motion test at the loop angles a, which close the loop for T (scaled).
    //!
    //! Regular when the loop's Jacobian J (at a, 6 x 6 row-major: refine's; nullptr: made
    //! here) has full rank, proven without its SVD for nearly every candidate: |det J|
    //! above SINGULAR_RANK_TOL ‖J‖_F⁶ (σ6 ≥ |det J| / σ1⁵, σ1 ≤ ‖J‖_F: loose, 730 of
    //! 4,000 random poses had a solution it let through), else ‖J‖_F ‖J⁻¹‖_F below
    //! 1 / SINGULAR_RANK_TOL (σ1/σ6 ≤ that product, within 6x of it: 0 of those 4,000);
    //! else σ6/σ1 from the SVD. Below
    //! SINGULAR_RANK_TOL, each null direction v (σi/σ1 below it) is followed: the loop
    //! angles a + SELF_MOTION_STEP v, the joint v moves most held there, the loop closed
    //! again by Gauss-Newton on the other five (six equations: least squares). A miss of
    //! at most SELF_MOTION_TOL is a continuum, its free joints those that moved by more
    //! than FREE_JOINT_TOL; none re-closes: a fold.
    SelfMotion self_motion(const Pose* L, const Pose& T, const double* a,
                           const double* Ja = nullptr) const {
        using Matrix6 = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;
        SelfMotion out;
        Matrix6 J;
        if (Ja != nullptr) {
            J = Eigen::Map<const Matrix6>(Ja);
        } else {
            loop_jacobian(L, a, J.data());
        }
        const double f2 = J.squaredNorm();
        const Eigen::PartialPivLU<Matrix6> lu(J);
        if (std::fabs(lu.determinant()) > SINGULAR_RANK_TOL * f2 * f2 * f2) return out;
        // (a singular J's inverse is inf or NaN: the comparison fails, the SVD decides)
        if (std::sqrt(f2 * lu.inverse().squaredNorm()) * SINGULAR_RANK_TOL < 1.0) return out;
        const Eigen::JacobiSVD<Matrix6> svd(J, Eigen::ComputeFullV);
        const auto& sv = svd.singularValues();
        out.rank = sv(0) > 0.0 ? sv(5) / sv(0) : 0.0;
        if (!(out.rank < SINGULAR_RANK_TOL)) return out;
        out.verdict = Degeneracy::fold;
        const Pose G = t_power < 0 ? T : inverse(T);
        for (int i = 5; i >= 0 && !(sv(i) >= SINGULAR_RANK_TOL * sv(0)); --i) {
            const auto v = svd.matrixV().col(i);
            int hold = 0;
            for (int k = 1; k < 6; ++k)
                if (std::fabs(v(k)) > std::fabs(v(hold))) hold = k;
            double b[6], best_b[6];
            for (int k = 0; k < 6; ++k) b[k] = best_b[k] = a[k] + SELF_MOTION_STEP * v(k);
            double best = INF;
            for (int step = 0; step <= SELF_MOTION_STEPS; ++step) {
                double Jb[6 * 6], Jr[6 * 5], db[5];
                const Pose H = loop_jacobian(L, b, Jb);
                const double now = miss_of(H, T);
                if (now < best) {
                    best = now;
                    for (int k = 0; k < 6; ++k) best_b[k] = b[k];
                } else if (step > 0) {
                    break;  // at the noise floor, or no solution with that joint held
                }
                if (step == SELF_MOTION_STEPS) break;
                for (int r = 0; r < 6; ++r)
                    for (int k = 0, c = 0; k < 6; ++k)
                        if (k != hold) Jr[r * 5 + c++] = Jb[r * 6 + k];
                const Twist e = pose_error(H, G);
                damped_least_squares(Jr, 6, 5, e.e, POLISH_DAMPING, db);
                for (int k = 0, c = 0; k < 6; ++k)
                    if (k != hold) b[k] += db[c++];
            }
            if (best < out.reclosure) out.reclosure = best;
            if (!(best <= SELF_MOTION_TOL)) continue;
            out.verdict = Degeneracy::continuum;
            for (int k = 0; k < 6; ++k) {
                const double d = std::fabs(wrap(best_b[k] - a[k]));
                if (d > out.moved[k]) out.moved[k] = d;
                if (moves(d)) out.free |= std::uint32_t{1} << k;
            }
        }
        return out;
    }

    //! u with M(x) u = 0 (M = A0 + x A1 + x² A2, divided by x² when |x| > 1): from the
    //! full-pivot LU, whose last pivot is the smallest. (Its second smallest pivot says
    //! nothing the answer can use: on calibrated UR5s, M(x6) nearly singular for every
    //! x6, it is tiny at roots whose solutions are all found; a double root or a
    //! continuum is told by the solution's Jacobian, self_motion.)
    static Vector12 null_vector(const Matrix12* A, double x) {
        const Eigen::FullPivLU<Matrix12> lu(matrix_at(A, x));
        const Matrix12& U = lu.matrixLU();
        Vector12 v;
        v(SIZE - 1) = 1.0;
        for (int i = SIZE - 2; i >= 0; --i) {
            double t = -U(i, SIZE - 1);
            for (int j = i + 1; j < SIZE - 1; ++j) t -= U(i, j) * v(j);
            v(i) = t / U(i, i);
        }
        return lu.permutationQ() * v;
    }

    //! True when root r has another within PAIR_ROOT_TOL and is the first of them: a
    //! double root, computed as two (or a complex pair's real part, twice).
    static bool first_of_pair(const double* roots, int found, int r) {
        bool paired = false;
        for (int s = 0; s < found; ++s) {
            if (s == r || !close_roots(roots[r], roots[s])) continue;
            if (s < r) return false;  // the pair's first root looked already
            paired = true;
        }
        return paired;
    }

    //! M(x) = A0 + x A1 + x² A2, divided by x² when |x| > 1.
    static Matrix12 matrix_at(const Matrix12* A, double x) {
        const bool big = std::fabs(x) > 1.0;
        const double y = big ? 1.0 / x : x;
        return big ? Matrix12(A[2] + y * (A[1] + y * A[0])) : Matrix12(A[0] + y * (A[1] + y * A[2]));
    }

    //! The monomial vectors u (x4^i x5^j at 3i + j) of two solutions sharing the root x
    //! (M(x)'s null space two-dimensional): with V (12 x 2) a basis of it (from M's
    //! full-pivot LU, as null_vector's one), u = V c where the rows of
    //! x4^(i+1) x5^j are x4 times those of x4^i x5^j: U1 c = x4 U0 c, in least squares the
    //! 2 x 2 eigenproblem (U0ᵀU0)⁻¹ U0ᵀU1 c = x4 c. Returns how many (0 ... 2: its real
    //! eigenvalues) it wrote to u.
    static int null_pair(const Matrix12* A, double x, Vector12* u) {
        // the basis from M's full-pivot LU, its last two pivots taken as 0: the unknowns of
        // the last two (column-permuted) places free, each set to 1 in turn
        const Eigen::FullPivLU<Matrix12> lu(matrix_at(A, x));
        const Matrix12& R = lu.matrixLU();
        Eigen::Matrix<double, SIZE, 2> V;
        for (int c = 0; c < 2; ++c) {
            Vector12 v = Vector12::Zero();
            v(SIZE - 2 + c) = 1.0;
            for (int i = SIZE - 3; i >= 0; --i) {
                double t = 0.0;
                for (int j = i + 1; j < SIZE; ++j) t -= R(i, j) * v(j);
                v(i) = t / R(i, i);
            }
            V.col(c) = lu.permutationQ() * v;
        }
        Eigen::Matrix<double, 9, 2> U0, U1;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                U0.row(3 * i + j) = V.row(3 * i + j);
                U1.row(3 * i + j) = V.row(3 * (i + 1) + j);
            }
        const Eigen::Matrix2d G = U0.transpose() * U0;
        const Eigen::Matrix2d H = U0.transpose() * U1;
        const double g = G.determinant();
        if (!(std::fabs(g) > 0.0)) return 0;
        const Eigen::Matrix2d B = G.inverse() * H;
        const double half = 0.5 * (B(0, 0) + B(1, 1));
        const double disc = half * half - B.determinant();
        if (!(disc >= 0.0)) return 0;  // a complex pair: no real solutions there
        const double root = std::sqrt(disc);
        const double lambda[2] = {half + root, half - root};
        int count = 0;
        for (double l : lambda) {
            // c in the null space of B - l I: from its row of larger norm
            const Eigen::Vector2d r0(B(0, 0) - l, B(0, 1)), r1(B(1, 0), B(1, 1) - l);
            const Eigen::Vector2d& r = r0.squaredNorm() >= r1.squaredNorm() ? r0 : r1;
            Eigen::Vector2d c(-r(1), r(0));
            if (!(c.squaredNorm() > 0.0)) c = Eigen::Vector2d(1.0, 0.0);  // B = l I
            u[count++] = V * c;
        }
        return count;
    }

    //! The sign class of a candidate: bits of sin q2, sin q3, sin q5 > 0.
    static int sign_class(const double* q) {
        return (std::sin(q[1]) > 0.0 ? 4 : 0) + (std::sin(q[2]) > 0.0 ? 2 : 0) +
               (std::sin(q[4]) > 0.0 ? 1 : 0);
    }

    //! What the passes of one solve have filled and decided so far.
    struct Passes {
        int filled[CLASSES] = {};
        int further = 0;
        double further_closure[FURTHER] = {};  //!< the closure of each further slot's candidate
        bool closes = false, fold = false;
        double rcond = NaN;  //!< A2's reciprocal condition at the first shift
        //! where none closes: the spectrum's margin from the real axis (spectrum_margin;
        //! NaN: not computed, the roots not the deflated companion matrix's)
        RootMargin margin{NaN};
    };

    //! True when q (6) is within SAME_CANDIDATE_TOL of a candidate already in Q.
    static bool already(const double* Q, const double* q) {
        for (int r = 0; r < SLOTS; ++r) {
            if (!std::isfinite(Q[r * 6])) continue;
            double d = 0.0;
            for (int k = 0; k < 6; ++k) d = std::fmax(d, std::fabs(wrap(Q[r * 6 + k] - q[k])));
            if (d <= SAME_CANDIDATE_TOL) return true;
        }
        return false;
    }

    //! The elimination with the half-angle shifts ph (q'4, q'5, q'6): its candidates into
    //! Q's slots (those of a root's two-dimensional null space only where no candidate is
    //! already there). False when the eigenvalue iteration failed.
    bool pass(const Elimination& E, const Pose* L, const Pose* Li, const Pose& T,
              const double* ph, double* Q, Passes& st, SolverInfo& info, Trace* trace) const {
        // M(x6) for the shift ph6, or ph6 + SECOND_SHIFT when A2 is ill-conditioned there
        // (a root near x6 = ∞: q'6 near the shift + π, which the second shift moves to a
        // finite x6); both ill-conditioned: no leading term, not solved here
        Matrix12 A[3];
        double shift6 = ph[2];
        pencil(E, Li, ph, shift6, A);
        Eigen::PartialPivLU<Matrix12> lead(A[2]);
        st.rcond = lead.rcond();
        if (trace != nullptr) trace->rcond = st.rcond;
        bool qz = false;
        if (!(lead.rcond() > LEADING_RCOND_TOL)) {
            shift6 = ph[2] + SECOND_SHIFT;
            pencil(E, Li, ph, shift6, A);
            lead.compute(A[2]);
            // both ill-conditioned: M(x6) nearly singular for every x6 (an arm near one
            // whose elimination degenerates), the generalized eigenproblem by QZ
            qz = !(lead.rcond() > LEADING_RCOND_TOL);
        }
        if (trace != nullptr) trace->shift6 = shift6, trace->qz = qz;
        // the real roots x6 of det M(x6) (general_6r_roots.hpp)
        double roots[ROOTS];
        bool split[ROOTS];
        Spectrum spectrum;
        const int found =
            qz ? real_roots_qz(A, roots, split)
               : real_roots(A, lead, roots, trace != nullptr ? &trace->deflated : nullptr, split,
                            &spectrum);
        if (found < 0) return false;
        // candidates into their classes, each ordered by q1
        auto add = [&](double* a, double closure, bool split_root, bool check_same) {
            double q[6], J[6 * 6];
            bool refined = false;
            if (refine_misses && closure > 0.0 && closure < REFINE_LIMIT) {
                closure = refine(L, T, a, closure, J);
                refined = true;
                // a split pair's candidate that Newton takes no nearer than
                // SPLIT_CLOSURE_TOL is at a fold's near miss (a complex pair), not a solution
                if (split_root && !split_closes(closure)) return;
            }
            for (int k = 0; k < 6; ++k) q[order[k]] = wrap(sign * a[k]);
            if (check_same && already(Q, q)) return;
            if (closure <= CLOSURE_TOL) {  // a solution: at a fold, or on a continuum?
                st.closes = true;
                const SelfMotion sm = self_motion(L, T, a, refined ? J : nullptr);
                if (sm.verdict == Degeneracy::continuum) {
                    info.singular = true;
                    for (int k = 0; k < 6; ++k)
                        if ((sm.free >> k) & 1U) info.set_free(order[k]);
                }
                st.fold |= sm.verdict == Degeneracy::fold;
                if (trace != nullptr) {
                    if (!std::isnan(sm.rank) && !(sm.rank >= trace->rank)) trace->rank = sm.rank;
                    if (sm.reclosure < trace->reclosure) trace->reclosure = sm.reclosure;
                }
            }
            if (trace != nullptr && closure < trace->closure) trace->closure = closure;
            const int cls = sign_class(q);
            int slot;
            if (st.filled[cls] < PER_CLASS) {
                slot = cls * PER_CLASS + st.filled[cls]++;
                // insertion by q1 within the class
                while (slot > cls * PER_CLASS && Q[(slot - 1) * 6] > q[0]) {
                    for (int k = 0; k < 6; ++k) Q[slot * 6 + k] = Q[(slot - 1) * 6 + k];
                    --slot;
                }
            } else if (st.further < FURTHER) {
                slot = CLASSES * PER_CLASS + st.further;
                st.further_closure[st.further++] = closure;
            } else {
                // every slot taken: the further slot of the worst closure yields to a better
                // candidate (split pairs and extraneous roots leave candidates that close
                // nothing: 18 of an Agilex Piper's filled every slot of a class before a
                // root of its generating configuration came, 2 of 4 solutions lost)
                int worst = 0;
                for (int k = 1; k < FURTHER; ++k)
                    if (st.further_closure[k] > st.further_closure[worst]) worst = k;
                if (!(closure < st.further_closure[worst])) return;
                st.further_closure[worst] = closure;
                slot = CLASSES * PER_CLASS + worst;
            }
            for (int k = 0; k < 6; ++k) Q[slot * 6 + k] = q[k];
        };
        for (int r = 0; r < found; ++r) {
            double a[6];
            const Vector12 u = null_vector(A, roots[r]);
            const double closure = back_substitute(E, L, Li, T, ph, roots[r], shift6, u, a);
            add(a, closure, split[r], false);
            if (!(refine_misses && resolves(closure) && first_of_pair(roots, found, r))) continue;
            // perhaps two solutions share this root: each from M's two-dimensional null space
            if (trace != nullptr) trace->resolved = true;
            Vector12 pair[2];
            const int count = null_pair(A, roots[r], pair);
            for (int k = 0; k < count; ++k) {
                double b[6];
                const double c = back_substitute(E, L, Li, T, ph, roots[r], shift6, pair[k], b);
                add(b, c, split[r], true);
            }
        }
        // nothing closes: is there no real root to lose?
        if (!st.closes && spectrum.n > 0) st.margin = spectrum_margin(A, spectrum);
        if (trace != nullptr) trace->margin = st.margin;
        return true;
    }

    //! This labelling's candidates for the target T (scaled) into Q's slots (st: what
    //! its passes filled and decided); false when its elimination proves nothing there
    //! (its left side rank-deficient for T, or the eigenvalue iteration failed).
    bool attempt(const Pose& T, double* Q, Passes& st, SolverInfo& info, Trace* trace) const {
        Pose L[6], Li[4];
        for (int k = 0; k < 6; ++k) L[k] = link_of(k, T);
        for (int k = 0; k < 4; ++k) Li[k] = inverse(L[k + 2]);
        // the left side's constants: the arm's, or (T on the left) this target's
        Elimination local;
        const Elimination* E = this;
        if (per_target()) {
            if (!(eliminate(L[0], L[1], local) > RANK_TOL)) return false;
            E = &local;
        }
        return pass(*E, L, Li, T, phi, Q, st, info, trace);
    }

    //! Candidates for one pose T (base frame) into Q (SLOTS x 6), NaN rows elsewhere;
    //! what it decided into `trace` when given (the chosen labelling's pass, and which
    //! labelling answered). The chosen labelling first; where none of its candidates
    //! closes the loop (the target within reach) and its elimination was ill-conditioned
    //! there (ALTERNATE_RCOND), the alternates in turn, the first whose candidates close
    //! answering (its candidates and flags replace the chosen one's).
    void solve(const Pose& T_in, double* Q, SolverInfo& info, Trace* trace = nullptr) const {
        for (int i = 0; i < SLOTS * 6; ++i) Q[i] = NaN;
        const double far = norm(T_in.p - centre) - reach;
        if (far > 0.0) {  // beyond every configuration's reach
            info.gap = far;
            return;
        }
        Pose T = T_in;
        T.p = scale * T.p;
        Passes st;
        const bool posed = attempt(T, Q, st, info, trace);
        if (posed && st.closes) {
            info.near = st.fold;
            return;
        }
        // no candidate closes and det M(x6) has no real root, proven: out of reach
        if (posed && certifies(st.margin.value)) {
            info.near = false;
            return;
        }
        // a well-posed elimination that closes nothing has lost no root, but may have
        // roots no solution makes: not found
        if (posed && !(st.rcond < ALTERNATE_RCOND)) {
            info.near = true;
            return;
        }
        double R[SLOTS * 6];
        for (std::size_t k = 0; k < alternates.size(); ++k) {
            for (int i = 0; i < SLOTS * 6; ++i) R[i] = NaN;
            Passes other;
            SolverInfo mine = info;
            if (trace != nullptr) trace->tried = static_cast<int>(k) + 1;
            if (!alternates[k].attempt(T, R, other, mine, nullptr)) continue;
            if (!other.closes) {
                if (!certifies(other.margin.value)) continue;
                info.near = false;  // its det M(x6) has no real root: out of reach
                return;
            }
            for (int i = 0; i < SLOTS * 6; ++i) Q[i] = R[i];
            info = mine;
            info.near = other.fold;
            if (trace != nullptr) trace->answered = static_cast<int>(k) + 1;
            return;
        }
        // none closes: the elimination proves nothing (not found: the search is asked)
        info.near = true;
    }
};

}  // namespace km::general6r
