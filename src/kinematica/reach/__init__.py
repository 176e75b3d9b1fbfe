"""Where the arm can really work: reachability maps by exact IK, and base placement.

* :func:`reachability`: a voxel map of the share of a fixed set of tool
  orientations the arm reaches at each voxel centre (its closed-form IK within
  the joint limits), the dexterous voxels, the best manipulability and the
  solution count; saved as a VTK image (ParaView) or ``.npz``.
* :func:`base_placement`: the base positions (and yaws) from which every pose
  of a task is reachable, ranked by the worst manipulability over the task.
"""

from kinematica.reach.build import reachability
from kinematica.reach.files import load_map, save_map
from kinematica.reach.orientations import ball_set, cone_set, planar_set, so3_set
from kinematica.reach.placement import BasePlacement, base_placement
from kinematica.reach.reachmap import ReachabilityMap, ReachabilitySlice

__all__ = [
    "BasePlacement",
    "ReachabilityMap",
    "ReachabilitySlice",
    "ball_set",
    "base_placement",
    "cone_set",
    "load_map",
    "planar_set",
    "reachability",
    "save_map",
    "so3_set",
]
