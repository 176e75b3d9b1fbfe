"""Closed-form IK solvers as kernels: one module per family, ``solve`` and ``solve_batch``.

Each solver fills, per target, candidate rows ``Q (m, n)`` (NaN rows: no real
solution on that branch) and its ``info`` row; the check kernel of
:mod:`kinematica.kernels.ik_check` judges them.
"""
