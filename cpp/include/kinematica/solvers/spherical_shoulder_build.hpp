// The spherical-shoulder family's builder (6R, and RRRPRR): the spherical-wrist solver of
// the reversed chain (spherical_wrist_build.hpp), whose wrist centre is this arm's shoulder
// centre seen from its tool frame at q = 0.
//
// Arms it declines (nullopt): any chain but six joints whose first three axes meet; those
// the reversed chain's spherical-wrist builder declines (joints 6, 5, 4 unable to move the
// shoulder centre in three directions, two consecutive shoulder axes coinciding).
#pragma once

#include <optional>

#include "../arm_axes.hpp"
#include "../chain.hpp"
#include "spherical_shoulder.hpp"
#include "spherical_wrist_build.hpp"

namespace km::decoupled {

//! The spherical-shoulder solver of a chain, or nullopt (the arms the header lists).
inline std::optional<SphericalShoulderParams> build_shoulder(const Chain& chain) {
    const ArmAxes A = arm_axes(chain);
    if (A.n != 6 || !A.features.shoulder.found) return std::nullopt;
    const Chain back = chain.reversed();
    ArmAxes B = arm_axes(back);
    // The reversed chain's frame is this arm's tool frame at q = 0: its wrist centre is the
    // shoulder centre seen from there. Taken from this arm, with this arm's size (the
    // reversed chain counts other translations), so that the line geometry's tolerances
    // decide once, on this arm.
    B.features.wrist.found = true;
    B.features.wrist.at = inverse(A.home).apply(A.features.shoulder.at);
    B.size = A.size;
    // where q = 0 is singular, "no-flip" is the bend of q2 > 0, that is of q'5 < 0
    std::optional<SphericalWristParams> wrist = build(back, B, -1.0);
    if (!wrist) return std::nullopt;
    SphericalShoulderParams P;
    P.wrist = *wrist;
    return P;
}

}  // namespace km::decoupled
