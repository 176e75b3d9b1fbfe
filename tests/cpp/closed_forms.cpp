// One closed form per family the core builds from a chain alone (<family>_build.hpp),
// solving poses made by FK in C++: every solution reaches the pose, the configuration that
// made it is among them, and each builder declines an arm outside its family.
#include <cstdio>

#include "arms.hpp"
#include "check.hpp"
#include "kinematica/solvers/parallel_build.hpp"
#include "kinematica/solvers/spherical_shoulder_build.hpp"
#include "kinematica/solvers/spherical_wrist_build.hpp"
#include "kinematica/solvers/srs_build.hpp"

namespace {

constexpr double PI = M_PI;
constexpr int POSES = 40;

// The PUMA 560 (spherical wrist) and the UR5 (axes 2, 3, 4 parallel): standard DH, m, rad.
const double PUMA_D[6] = {0.0, 0.0, 0.15005, 0.4318, 0.0, 0.0};
const double PUMA_A[6] = {0.0, 0.4318, 0.0203, 0.0, 0.0, 0.0};
const double PUMA_ALPHA[6] = {PI / 2, 0.0, -PI / 2, PI / 2, -PI / 2, 0.0};
const double UR5_D[6] = {0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823};
const double UR5_A[6] = {0.0, -0.425, -0.39225, 0.0, 0.0, 0.0};
const double UR5_ALPHA[6] = {PI / 2, 0.0, 0.0, PI / 2, -PI / 2, 0.0};
// The KUKA iiwa 14 (spherical shoulder, elbow, spherical wrist: SRS).
const double IIWA_D[7] = {0.36, 0.0, 0.42, 0.0, 0.4, 0.0, 0.126};
const double IIWA_A[7] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
const double IIWA_ALPHA[7] = {-PI / 2, PI / 2, PI / 2, -PI / 2, -PI / 2, PI / 2, 0.0};

//! POSES round trips of the solver on the chain; the solutions' count in [1, most].
template <class Params>
void round_trips(const char* name, const Params& params, const km::Chain& chain, int most,
                 bool find_q = true) {
    const km::ClosedForm<Params> solver{params};
    kmtest::Uniform u{7};
    for (int k = 0; k < POSES; ++k) {
        double q[7];
        for (int j = 0; j < chain.dof(); ++j) q[j] = u();
        const int count = kmtest::round_trip(name, solver, chain, q, find_q);
        CHECK(count <= most, "%s: %d solutions, at most %d", name, count, most);
    }
}

}  // namespace

int main() {
    const km::Chain puma = kmtest::revolute_arm(6, PUMA_D, PUMA_A, PUMA_ALPHA);
    const km::Chain ur5 = kmtest::revolute_arm(6, UR5_D, UR5_A, UR5_ALPHA);
    const km::Chain iiwa = kmtest::revolute_arm(7, IIWA_D, IIWA_A, IIWA_ALPHA);

    const auto wrist = km::decoupled::build(puma);
    CHECK(wrist.has_value(), "the spherical-wrist builder declines the PUMA 560");
    if (wrist) round_trips("spherical wrist (PUMA 560)", *wrist, puma, 8);
    CHECK(!km::decoupled::build(ur5).has_value(), "the spherical-wrist builder takes the UR5");

    const auto parallel = km::parallel::build(ur5);
    CHECK(parallel.has_value(), "the three-parallel builder declines the UR5");
    if (parallel) round_trips("three-parallel (UR5)", *parallel, ur5, 8);
    CHECK(!km::parallel::build(puma).has_value(), "the three-parallel builder takes the PUMA");

    // the PUMA reversed: its wrist becomes a spherical shoulder
    const km::Chain shoulder_arm = puma.reversed();
    const auto shoulder = km::decoupled::build_shoulder(shoulder_arm);
    CHECK(shoulder.has_value(), "the spherical-shoulder builder declines the reversed PUMA");
    if (shoulder) round_trips("spherical shoulder (PUMA reversed)", *shoulder, shoulder_arm, 8);
    CHECK(!km::decoupled::build_shoulder(ur5).has_value(), "the shoulder builder takes the UR5");

    // the SRS arm at an arm angle: its solutions reach the pose (the generating q has its
    // own arm angle, so it is not asked for)
    auto srs = km::srs::build(iiwa);
    CHECK(srs.has_value(), "the SRS builder declines the iiwa");
    if (srs) {
        srs->psi = 0.4;
        round_trips("SRS (iiwa) at psi 0.4", *srs, iiwa, 8, false);
    }
    CHECK(!km::srs::build(puma).has_value(), "the SRS builder takes a 6R arm");
    return kmtest::failures();
}
