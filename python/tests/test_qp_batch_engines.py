"""lcprelax.QpBatch's dense engine (DenseQpSolver) against the sparse one (QpSolver) on random
small problems of every kind: strictly convex, positive semidefinite, LPs, duplicated rows,
equality rows and fixed sides, infeasible and unbounded ones. Same status on every problem,
same objective where solved (to 1e-6 relative), no NaN in a solution."""
import numpy as np
import pytest
import scipy.sparse as sp

import lcprelax


def _random_problem(rng):
    while True:
        n, me, mi = int(rng.integers(1, 10)), int(rng.integers(0, 3)), int(rng.integers(0, 8))
        if 3 * n + me + 2 * mi <= 64:  # (the dense engine takes up to 128)
            break
    kind = int(rng.integers(0, 4))  # 0 convex, 1 PSD, 2 LP, 3 infeasible row
    B = rng.standard_normal((n, n))
    P = B.T @ B * 10.0 ** rng.uniform(-3, 2)
    if kind == 1:
        C = rng.standard_normal((max(1, n // 2), n))
        P = C.T @ C
    if kind == 2:
        P = np.zeros((n, n))
    A, G = rng.standard_normal((me, n)), rng.standard_normal((mi, n))
    if mi >= 2 and rng.random() < 0.3:
        G[1] = G[0]
    x0 = rng.standard_normal(n)
    gx = G @ x0
    l, u = gx - rng.uniform(0, 1, mi), gx + rng.uniform(0, 1, mi)
    for i in range(mi):
        r = rng.random()
        if r < 0.25:
            l[i] = -np.inf
        elif r < 0.5:
            u[i] = np.inf
        elif r < 0.6:
            l[i] = u[i] = gx[i]
    xl, xu = x0 - rng.uniform(0, 2, n), x0 + rng.uniform(0, 2, n)
    xl[rng.random(n) < 0.3] = -np.inf
    xu[rng.random(n) < 0.3] = np.inf
    if kind == 3 and mi > 0:
        G[0] = 0.0
        G[0, 0], l[0], u[0], xl[0], xu[0] = 1e-3, 1e3, np.inf, -np.inf, 1.0
    q = 3.0 * rng.standard_normal(n)
    args = dict(xl=xl, xu=xu)
    if me:
        args["b"] = A @ x0
    if mi:
        args.update(l=l, u=u)
    mats = (sp.csc_matrix(np.triu(P)), sp.csc_matrix(A) if me else None, sp.csc_matrix(G) if mi else None)
    return mats, q, args


@pytest.mark.parametrize("seed", [1, 2])
def test_dense_and_sparse_engines_agree_on_random_problems(seed):
    rng = np.random.default_rng(seed)
    statuses = set()
    for _ in range(200):
        (P, A, G), q, args = _random_problem(rng)
        r = {}
        for engine in ("dense", "sparse"):
            batch = lcprelax.QpBatch(P, A, G, threads=1, engine=engine, eps_abs=1e-9)
            assert batch.engine == engine
            r[engine] = batch.solve(q, **args)
        d, s = r["dense"], r["sparse"]
        assert d.status[0] == s.status[0]
        statuses.add(d.status[0])
        if d.status[0] == "solved":
            assert np.all(np.isfinite(d.x))
            assert abs(d.objective[0] - s.objective[0]) <= 1e-6 * (1 + abs(s.objective[0]))
            assert d.primal_residual[0] <= 1e-9 and d.dual_residual[0] <= 1e-9 and d.duality_gap[0] <= 1e-9
    assert {"solved", "primal_infeasible", "dual_infeasible"} <= statuses
