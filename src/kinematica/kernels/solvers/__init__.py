"""Closed-form IK solvers as kernels: one module per family of arms.

Each module has ``solve(params, T, Q, info)`` for one target and
``solve_batch`` running it over targets in a parallel loop; ``params`` is a
flat array packed once per arm by the solver's builder in
:mod:`kinematica.ik.analytic`. ``Q`` and ``info`` are described in
:mod:`kinematica.kernels.ik_check`.
"""
