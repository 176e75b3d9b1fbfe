// The builder of a near-degenerate three-parallel 6R arm's solver (near_6r.hpp): the
// family's closed form of the nearby exact arm (parallel_build.hpp) and the general 6R's
// of this arm (general_6r_build.hpp), from a Chain alone.
#pragma once

#include <cmath>
#include <optional>

#include "../arm_axes.hpp"
#include "general_6r_build.hpp"
#include "near_6r.hpp"
#include "parallel_build.hpp"

namespace km {

//! The solver of a three-parallel arm whose axes hold that structure only within the line
//! geometry's tolerance (slack > 0): the family's Params, the general 6R's, and the watch
//! WATCH_FACTOR √(slack / size). nullopt for an arm whose relations hold exactly (slack 0:
//! the family's closed form alone is its answer), one the family declines, or one for
//! which no labelling of the general 6R works.
inline std::optional<Near6RParams<ParallelParams>> build_near_parallel(const Chain& chain) {
    const ArmAxes A = arm_axes(chain);
    if (!(A.features.slack > 0.0)) return std::nullopt;
    std::optional<ParallelParams> family = parallel::build(A);
    if (!family) return std::nullopt;
    Near6RParams<ParallelParams> out;
    out.family = *family;
    if (!general6r::build(chain, out.general)) return std::nullopt;
    out.watch = WATCH_FACTOR * std::sqrt(A.features.slack / A.size);
    return out;
}

}  // namespace km
