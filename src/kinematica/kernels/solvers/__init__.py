"""Closed-form IK solver kernels: one module per family of arms.

Each module has a scalar kernel ``solve(params, T, Q, info)`` over one target
and ``solve_batch`` running it in a parallel loop; ``params`` is a flat array
packed once per arm by the family's builder in :mod:`kinematica.ik.analytic`
(its offsets are the module's ``P_*`` constants). What ``Q`` and ``info``
hold is described in :mod:`kinematica.kernels.ik_check`.
"""
