// Forward kinematics of the core's chain (chain.hpp, chain_build.hpp) against a planar 2R
// worked by hand: tool at (a1 c1 + a2 c12, a1 s1 + a2 s12, 0), turned by q1 + q2 about z,
// in both DH conventions, and a base and tool transform composed around it.
#include "arms.hpp"
#include "check.hpp"
#include "kinematica/chain.hpp"
#include "kinematica/chain_build.hpp"

namespace {

constexpr double TOL = 1e-14;  // a few ulps of the link lengths

void check_pose(const km::Pose& T, double x, double y, double z, double angle, const char* what) {
    const double c = std::cos(angle), s = std::sin(angle);
    const double want[3][4] = {{c, -s, 0.0, x}, {s, c, 0.0, y}, {0.0, 0.0, 1.0, z}};
    for (int i = 0; i < 3; ++i) {
        const double got[4] = {T.x[i], T.y[i], T.z[i], T.p[i]};
        for (int j = 0; j < 4; ++j) {
            CHECK(std::fabs(got[j] - want[i][j]) <= TOL, "%s: T[%d][%d] = %.17g, by hand %.17g", what,
                  i, j, got[j], want[i][j]);
        }
    }
}

}  // namespace

int main() {
    const double a1 = 0.7, a2 = 0.45, d[2] = {0.0, 0.0}, a[2] = {a1, a2}, alpha[2] = {0.0, 0.0};
    const km::Chain standard = kmtest::revolute_arm(2, d, a, alpha);
    const double theta[2] = {0.0, 0.0}, lo[2] = {-INFINITY, -INFINITY}, hi[2] = {INFINITY, INFINITY};
    const bool prismatic[2] = {false, false};
    // Craig's convention: a_{i-1} before joint i, the last link's length in the tool
    const double a_mod[2] = {0.0, a1};
    km::Pose tool;
    tool.p = {a2, 0.0, 0.0};
    const km::Chain modified = km::Chain::from_dh(2, prismatic, theta, d, a_mod, alpha, lo, hi, true,
                                                  km::Pose{}, tool);
    // the same arm lifted by 0.3 m and turned by 0.5 rad about z at its base
    km::Pose base;
    base.x = {std::cos(0.5), std::sin(0.5), 0.0};
    base.y = {-std::sin(0.5), std::cos(0.5), 0.0};
    base.p = {0.0, 0.0, 0.3};
    const km::Chain moved = km::Chain::from_dh(2, prismatic, theta, d, a, alpha, lo, hi, false, base,
                                               km::Pose{});
    CHECK(standard.dof() == 2 && modified.dof() == 2, "dof %d %d", standard.dof(), modified.dof());
    kmtest::Uniform u{2};
    for (int k = 0; k < 50; ++k) {
        const double q[2] = {u(), u()};
        const double x = a1 * std::cos(q[0]) + a2 * std::cos(q[0] + q[1]);
        const double y = a1 * std::sin(q[0]) + a2 * std::sin(q[0] + q[1]);
        check_pose(kmtest::pose_of(standard, q), x, y, 0.0, q[0] + q[1], "standard");
        check_pose(kmtest::pose_of(modified, q), x, y, 0.0, q[0] + q[1], "modified");
        const double c = std::cos(0.5), s = std::sin(0.5);
        check_pose(kmtest::pose_of(moved, q), c * x - s * y, s * x + c * y, 0.3, q[0] + q[1] + 0.5,
                   "base");
    }
    // the reversed chain's FK is the inverse pose at the reversed, negated joint values
    const double q[2] = {0.3, -1.2};
    const double qr[2] = {-q[1], -q[0]};
    const km::Pose T = kmtest::pose_of(standard, q), R = kmtest::pose_of(standard.reversed(), qr);
    const km::Pose I = T * R;
    for (int i = 0; i < 3; ++i) {
        CHECK(std::fabs(I.p[i]) <= TOL, "reversed: T R translation %.3g", I.p[i]);
    }
    return kmtest::failures();
}
