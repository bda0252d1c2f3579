"""lcprelax: sparse interior-point QP (with an adjoint backward pass), Lemke LCP, readers.

Batched, parallel versions (QpBatch, LemkeBatch, RelaxedLcpBatch) back the PyTorch layers
of ``lcprelax.torch`` (QpLayer, LcpLayer, RelaxedLcpLoss; imported separately, it needs torch).
Simulation: :class:`Simulator` steps a scene (JSON file or text; ``pile_scene`` and friends
generate one); SI units, poses (x, y, θ) per body. Learning: :class:`BlockObjective`,
:class:`PolygonObjective` and :class:`SceneObjective` give a loss and its gradient in the
learned parameters
(``evaluate(theta) -> (loss, gradient)``).

The solvers and readers are implemented in C++ (the compiled module ``lcprelax._lcprelax``);
this package re-exports them. Conventions (docs/python.md, docs/conventions.md):

* QP: ``min ½xᵀPx + qᵀx + r  s.t.  Ax = b,  l ≤ Gx ≤ u,  xl ≤ x ≤ xu``; **P is given as its
  upper triangle** (scipy.sparse, any format); multipliers satisfy
  ``Px + q + Aᵀy + Gᵀz + z_bounds = 0`` with z > 0 where an upper side is active and z < 0
  where a lower side is.
* LCP: ``w = Mz + q,  0 ≤ z ⊥ w ≥ 0``.
* Matrices must be scipy.sparse (a dense ndarray is a TypeError); vectors are 1-D float
  arrays; results hold copies. No units.
* Bad input raises :class:`InputError` (a ValueError); calls out of order raise
  :class:`UsageError` (a RuntimeError).

Example::

    import numpy as np, scipy.sparse as sp, lcprelax
    s = lcprelax.QpSolver(eps_abs=1e-10)
    s.setup(sp.csc_matrix(np.array([[2.0, 0.5], [0.0, 1.0]])), np.array([1.0, -1.0]),
            xl=np.zeros(2))
    r = s.solve()          # r.status, r.x, r.y, r.z, r.z_bounds, r.objective, ...
    g = s.backward(np.ones(2))   # g.dq, g.dP, g.dxl, ...
"""
from ._lcprelax import (  # noqa: F401
    BlockObjective,
    Objective,
    PolygonObjective,
    SceneObjective,
    Simulator,
    StepStats,
    box_stack_scene,
    generate_block_data,
    incline_scene,
    pile_scene,
    pyramid_scene,
    InputError,
    LcpGradient,
    LcpResult,
    LemkeSolver,
    LcpBatchResult,
    LemkeBatch,
    QpBatch,
    QpBatchResult,
    QpGradient,
    QpResult,
    QpSolver,
    RelaxedLcpBatch,
    RelaxedLcpBatchResult,
    UsageError,
    parse_qps,
    parse_siconos_fc2d,
    parse_siconos_lcp,
    read_qps,
    read_siconos_fc2d,
    read_siconos_lcp,
)

__all__ = [
    "InputError",
    "UsageError",
    "QpSolver",
    "QpResult",
    "QpGradient",
    "LemkeSolver",
    "LcpResult",
    "LcpGradient",
    "QpBatch",
    "QpBatchResult",
    "LemkeBatch",
    "LcpBatchResult",
    "RelaxedLcpBatch",
    "RelaxedLcpBatchResult",
    "read_qps",
    "parse_qps",
    "read_siconos_lcp",
    "parse_siconos_lcp",
    "read_siconos_fc2d",
    "parse_siconos_fc2d",
    "Simulator",
    "StepStats",
    "pile_scene",
    "box_stack_scene",
    "pyramid_scene",
    "incline_scene",
    "Objective",
    "BlockObjective",
    "PolygonObjective",
    "SceneObjective",
    "generate_block_data",
]
