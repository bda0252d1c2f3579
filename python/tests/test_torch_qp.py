"""lcprelax.torch.QpLayer and its engine lcprelax.QpBatch: gradients against central
differences (torch.autograd.gradcheck, float64), bitwise agreement with the single-problem
QpSolver and across thread counts, and clear errors on bad input."""
import os

import numpy as np
import pytest
import scipy.sparse as sp

import lcprelax

# ctest sets LCPRELAX_REQUIRE_TORCH when CMake found torch: then a missing torch fails.
torch = __import__("torch") if os.environ.get("LCPRELAX_REQUIRE_TORCH") else pytest.importorskip("torch")
from lcprelax.torch import QpLayer, SolveError  # noqa: E402

# Tight tolerance: gradcheck's central differences (eps 1e-6) must not see the interior
# point's residual in x.
TIGHT = dict(eps_abs=1e-12)


def _t(a, grad=True):
    return torch.tensor(np.asarray(a, dtype=float), dtype=torch.float64, requires_grad=grad)


def _batch_q(small_qp, B, seed=0):
    """B cost vectors near the fixture's: small changes keep its (strict) active set."""
    rng = np.random.default_rng(seed)
    return small_qp["q"] + 0.02 * rng.standard_normal((B, small_qp["q"].size))


def _layer(small_qp, **kw):
    return QpLayer(small_qp["P"], small_qp["A"], small_qp["G"], **kw)


@pytest.mark.parametrize("engine", ["dense", "sparse"])
def test_gradcheck_every_input_batched_and_shared(small_qp, engine):
    layer = _layer(small_qp, engine=engine, **TIGHT)
    q = _t(_batch_q(small_qp, 3))                      # batched (3, n)
    Pv = _t(layer.P_pattern.data)                      # shared values of P's entries
    Av = _t(layer.A_pattern.data)
    b = _t(small_qp["b"])
    Gv = _t(np.tile(layer.G_pattern.data, (3, 1)))     # batched values of G
    l = _t(small_qp["l"][None, :])                     # shape (1, m): shared
    u = _t(small_qp["u"], grad=False)                  # +inf entry: not differentiated
    xl, xu = _t(small_qp["xl"]), _t(small_qp["xu"])

    def f(q, Pv, Av, b, Gv, l, xl, xu):
        return layer(q, P=Pv, A=Av, b=b, G=Gv, l=l, u=u, xl=xl, xu=xu)

    assert torch.autograd.gradcheck(f, (q, Pv, Av, b, Gv, l, xl, xu), eps=1e-6, atol=1e-5, rtol=1e-4)


def test_gradcheck_through_the_multipliers(small_qp):
    layer = _layer(small_qp, multipliers=True, **TIGHT)
    q = _t(_batch_q(small_qp, 2, seed=1))
    fixed = {k: torch.tensor(small_qp[k], dtype=torch.float64) for k in ("b", "l", "u", "xl", "xu")}

    def f(q):
        x, y, z = layer(q, **fixed)
        return x.sum(dim=1) + 0.3 * y[:, 0] - 0.7 * z[:, 0] + 0.2 * z[:, 1]

    assert torch.autograd.gradcheck(f, (q,), eps=1e-6, atol=1e-5, rtol=1e-4)


def test_results_equal_the_single_solver_bitwise_and_over_threads(small_qp):
    qs = _batch_q(small_qp, 6, seed=2)
    fixed = {k: torch.tensor(small_qp[k], dtype=torch.float64) for k in ("b", "l", "u", "xl", "xu")}
    outs = []
    for threads in (1, 2):
        layer = _layer(small_qp, threads=threads, multipliers=True, engine="sparse")
        outs.append([t.detach().numpy().copy() for t in layer(torch.tensor(qs), **fixed)])
        outs.append([t.detach().numpy().copy() for t in layer(torch.tensor(qs), **fixed)])  # update() path
    for o in outs[1:]:
        for a, b in zip(outs[0], o):
            assert np.array_equal(a, b)
    s = lcprelax.QpSolver()
    for k, qk in enumerate(qs):
        s.setup(small_qp["P"], qk, small_qp["A"], small_qp["b"], small_qp["G"], small_qp["l"], small_qp["u"],
                small_qp["xl"], small_qp["xu"])
        r = s.solve()
        assert np.array_equal(r.x, outs[0][0][k]) and np.array_equal(r.z, outs[0][2][k])


def test_backward_equals_the_single_solver_and_survives_a_second_forward(small_qp):
    layer = _layer(small_qp, engine="sparse")
    fixed = {k: torch.tensor(small_qp[k], dtype=torch.float64) for k in ("b", "l", "u", "xl", "xu")}
    q1 = _t(_batch_q(small_qp, 2, seed=3))
    x1 = layer(q1, **fixed)
    layer(_t(_batch_q(small_qp, 4, seed=4)), **fixed)  # another batch solved before backward
    w = torch.tensor([1.0, -2.0, 0.5, 3.0, 1.5], dtype=torch.float64)
    (x1 * w).sum().backward()
    s = lcprelax.QpSolver()
    for k in range(2):
        s.setup(small_qp["P"], q1[k].detach().numpy(), small_qp["A"], small_qp["b"], small_qp["G"], small_qp["l"],
                small_qp["u"], small_qp["xl"], small_qp["xu"])
        s.solve()
        assert np.array_equal(s.backward(w.numpy()).dq, q1.grad[k].numpy())


def test_dense_engine_is_the_default_for_small_problems_and_agrees_with_qpsolver(small_qp):
    assert _layer(small_qp).engine.engine == "dense"
    assert _layer(small_qp, engine="sparse").engine.engine == "sparse"
    with pytest.raises(lcprelax.InputError, match="engine"):
        _layer(small_qp, engine="fast")
    qs = _batch_q(small_qp, 5, seed=5)
    fixed = {k: torch.tensor(small_qp[k], dtype=torch.float64) for k in ("b", "l", "u", "xl", "xu")}
    outs = []
    for threads in (1, 2):
        layer = _layer(small_qp, threads=threads, multipliers=True, eps_abs=1e-11)
        outs.append([t.detach().numpy().copy() for t in layer(torch.tensor(qs), **fixed)])
    for a, b in zip(outs[0], outs[1]):
        assert np.array_equal(a, b)  # the same for every thread count
    s = lcprelax.QpSolver(eps_abs=1e-11)
    for k, qk in enumerate(qs):
        s.setup(small_qp["P"], qk, small_qp["A"], small_qp["b"], small_qp["G"], small_qp["l"], small_qp["u"],
                small_qp["xl"], small_qp["xu"])
        r = s.solve()
        assert np.abs(r.x - outs[0][0][k]).max() < 1e-8
        assert np.abs(r.z - outs[0][2][k]).max() < 1e-7


def test_unbatched_call_returns_unbatched_tensors(small_qp):
    layer = _layer(small_qp)
    x = layer(torch.tensor(small_qp["q"]), b=torch.tensor(small_qp["b"]), l=torch.tensor(small_qp["l"]),
              u=torch.tensor(small_qp["u"]), xl=torch.tensor(small_qp["xl"]), xu=torch.tensor(small_qp["xu"]))
    assert x.shape == (5,)
    x1 = layer(torch.tensor(small_qp["q"])[None, :], b=torch.tensor(small_qp["b"]), l=torch.tensor(small_qp["l"]),
               u=torch.tensor(small_qp["u"]), xl=torch.tensor(small_qp["xl"]), xu=torch.tensor(small_qp["xu"]))
    assert x1.shape == (1, 5) and torch.equal(x1[0], x)  # a batch of one keeps its dimension


def test_bad_input_raises_clear_errors(small_qp):
    layer = _layer(small_qp)
    b = torch.tensor(small_qp["b"])
    with pytest.raises(TypeError, match="float64"):
        layer(torch.tensor(small_qp["q"], dtype=torch.float32), b=b)
    with pytest.raises(lcprelax.InputError, match=r"q has shape \(2, 4\)"):
        layer(torch.zeros(2, 4, dtype=torch.float64), b=b)
    with pytest.raises(lcprelax.InputError, match="batch size"):
        layer(torch.zeros(3, 5, dtype=torch.float64), b=torch.zeros(2, 1, dtype=torch.float64))
    q = torch.tensor(np.tile(small_qp["q"], (3, 1)))
    q[2, 1] = float("nan")
    with pytest.raises(lcprelax.InputError, match="sample 2"):
        layer(q, b=b)
    with pytest.raises(lcprelax.InputError, match="b is required"):
        layer(torch.tensor(small_qp["q"]))
    with pytest.raises(TypeError, match="scipy.sparse"):
        QpLayer(np.eye(2))
    with pytest.raises(lcprelax.InputError, match="upper triangle"):
        QpLayer(sp.csc_matrix(np.ones((2, 2))))(torch.zeros(2, dtype=torch.float64))


def test_a_sample_without_solution_raises_solve_error():
    # x0 ≥ 1 and x0 ≤ -1 through two rows: sample 1 is primal infeasible, sample 0 is not.
    G = sp.csc_matrix(np.array([[1.0, 0.0], [1.0, 0.0]]))
    layer = QpLayer(sp.identity(2, format="csc"), G=G)
    l = torch.tensor([[0.0, -np.inf], [1.0, -np.inf]], dtype=torch.float64)
    u = torch.tensor([[np.inf, 2.0], [np.inf, -1.0]], dtype=torch.float64)
    with pytest.raises(SolveError, match="sample 1 ended with status 'primal_infeasible'"):
        layer(torch.zeros(2, dtype=torch.float64), l=l, u=u)


def test_batch_engine_backward_needs_a_solution():
    batch = lcprelax.QpBatch(sp.identity(2, format="csc"))
    with pytest.raises(lcprelax.UsageError, match="before solve"):
        batch.backward(np.ones(2))
