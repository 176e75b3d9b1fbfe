// The general 6R built from a chain alone (general_6r_build.hpp) on a FANUC-CRX-like arm
// (axes 2 and 3 parallel, one common normal of nonzero length, a wrist whose axes do not
// meet: no special family holds it), solving poses made by FK: every solution reaches the
// pose, the configuration that made it is among them, and the builder declines a chain
// that is not 6R.
#include "arms.hpp"
#include "check.hpp"
#include "kinematica/solvers/general_6r_build.hpp"
#include "kinematica/solvers/parallel_build.hpp"
#include "kinematica/solvers/spherical_wrist_build.hpp"

namespace {

constexpr double PI = M_PI;
// CRX-10iA-like standard DH (m, rad): a2 = 0.54 the one common normal, d4 the forearm,
// d5 and d6 the wrist offsets.
const double CRX_D[6] = {0.0, 0.0, 0.0, 0.54, 0.15, 0.16};
const double CRX_A[6] = {0.0, 0.54, 0.0, 0.0, 0.0, 0.0};
const double CRX_ALPHA[6] = {-PI / 2, PI, -PI / 2, PI / 2, -PI / 2, 0.0};

}  // namespace

int main() {
    const km::Chain crx = kmtest::revolute_arm(6, CRX_D, CRX_A, CRX_ALPHA);
    CHECK(!km::decoupled::build(crx).has_value(), "the spherical-wrist builder takes the CRX");
    CHECK(!km::parallel::build(crx).has_value(), "the three-parallel builder takes the CRX");
    const auto params = km::general6r::build(crx);
    CHECK(params.has_value(), "the general 6R builder declines the CRX-like arm");
    if (params) {
        CHECK(params->invalid() == nullptr, "built params invalid: %s", params->invalid());
        const km::ClosedForm<km::general6r::General6RParams> solver{*params};
        kmtest::Uniform u{6};
        for (int k = 0; k < 40; ++k) {
            double q[6];
            for (double& v : q) v = u();
            kmtest::round_trip("general 6R (CRX-like)", solver, crx, q);
        }
    }
    // a 5R chain and a 7R chain: not the family's
    const double d7[7] = {0.3, 0.0, 0.4, 0.0, 0.4, 0.0, 0.1}, a7[7] = {}, al7[7] = {-PI / 2, PI / 2, PI / 2, -PI / 2, -PI / 2, PI / 2, 0.0};
    CHECK(!km::general6r::build(kmtest::revolute_arm(7, d7, a7, al7)).has_value(), "7R built");
    CHECK(!km::general6r::build(kmtest::revolute_arm(5, d7, a7, al7)).has_value(), "5R built");
    return kmtest::failures();
}
