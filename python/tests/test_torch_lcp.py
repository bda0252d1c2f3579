"""lcprelax.torch.LcpLayer (Lemke) and RelaxedLcpLoss (the relaxed LCP loss of the 1-D
block, the seeds' 9-variable QP): gradcheck in float64, bitwise agreement with the
single-problem LemkeSolver and across thread counts, errors on bad input."""
import os

import numpy as np
import pytest
import scipy.sparse as sp

import lcprelax

# ctest sets LCPRELAX_REQUIRE_TORCH when CMake found torch: then a missing torch fails.
torch = __import__("torch") if os.environ.get("LCPRELAX_REQUIRE_TORCH") else pytest.importorskip("torch")
from lcprelax.torch import LcpLayer, RelaxedLcpLoss, SolveError  # noqa: E402


def _t(a, grad=True):
    return torch.tensor(np.asarray(a, dtype=float), dtype=torch.float64, requires_grad=grad)


# A P-matrix LCP (unique solution for every q); random q give a mix of z > 0 and w > 0.
M_PD = sp.csc_matrix(np.array([[3.0, 1.0, 0.0, 0.5], [1.0, 2.0, 0.5, 0.0], [0.0, -0.5, 2.0, 1.0], [0.5, 0.0, -1.0, 3.0]]))


def _block_lcp(v_star, mu_mg=0.5, m=1.0):
    """The 1-D block's LCP (z = λ⁺, λ⁻, γ): M = [[1/m, −1/m, 1], [−1/m, 1/m, 1], [−1, −1, 0]],
    q = (v*, −v*, μmg), as models/block1d.hpp."""
    w = 1.0 / m
    M = sp.csc_matrix(np.array([[w, -w, 1.0], [-w, w, 1.0], [-1.0, -1.0, 0.0]]))
    q = np.stack([v_star, -v_star, np.full_like(v_star, mu_mg)], axis=-1)
    return M, q


def test_lcp_layer_gradcheck_in_q_and_m():
    layer = LcpLayer(M_PD)
    rng = np.random.default_rng(0)
    q = _t(rng.standard_normal((6, 4)))
    Mv = _t(layer.M_pattern.data)
    z = layer(q, M=Mv)
    assert (z > 1e-3).any() and (z.detach().numpy() < 1e-12).any()  # both kinds of indices
    assert torch.autograd.gradcheck(lambda q, Mv: layer(q, M=Mv), (q, Mv), eps=1e-6, atol=1e-8, rtol=1e-6)


def test_lcp_layer_equals_lemke_solver_bitwise_over_threads():
    rng = np.random.default_rng(1)
    qs = rng.standard_normal((7, 4))
    zs = [LcpLayer(M_PD, threads=t)(torch.tensor(qs)).numpy() for t in (1, 2)]
    assert np.array_equal(zs[0], zs[1])
    s = lcprelax.LemkeSolver()
    for k in range(7):
        s.setup(M_PD, qs[k])
        assert np.array_equal(s.solve().z, zs[0][k])


def test_lcp_layer_reports_a_ray_as_solve_error():
    # M = -I with q < 0 in one sample has no solution: Lemke ends on a ray.
    layer = LcpLayer(sp.csc_matrix(-np.eye(2)))
    with pytest.raises(SolveError, match="sample 1"):
        layer(torch.tensor([[1.0, 1.0], [-1.0, 1.0]], dtype=torch.float64))
    with pytest.raises(lcprelax.InputError, match="M has shape"):
        layer(torch.ones(2, dtype=torch.float64), M=torch.ones(3, dtype=torch.float64))


def _block_loss(**kw):
    M, _ = _block_lcp(np.zeros(1))
    P = sp.csc_matrix(np.array([[1.0, -1.0, 0.0]]))  # v⁺ = v* + (λ⁺ − λ⁻)/m with m = 1
    return RelaxedLcpLoss(M, P, soft_nonnegativity=True, soft_lambdas=True, **kw)


def test_relaxed_loss_gradcheck_on_the_block():
    loss = _block_loss(qp=dict(eps_abs=1e-12))
    rng = np.random.default_rng(2)
    v_star = rng.uniform(-1.0, 1.0, 5)
    _, q = _block_lcp(v_star)
    target = np.clip(v_star, -0.3, 0.3)[:, None] + 0.05 * rng.standard_normal((5, 1))
    q_t, p_t, x_t = _t(q), _t(v_star[:, None]), _t(target)
    Mv = _t(loss.M_pattern.data)
    Pv = _t(loss.P_pattern.data)
    c = loss(q_t, x_t, M=Mv, P=Pv, p=p_t)
    assert c.shape == (5,) and torch.isfinite(c).all()

    def f(q, x, Mv, Pv, p):
        return loss(q, x, M=Mv, P=Pv, p=p)

    assert torch.autograd.gradcheck(f, (q_t, x_t, Mv, Pv, p_t), eps=1e-6, atol=1e-5, rtol=1e-4)


def test_relaxed_loss_is_independent_of_threads_and_batching():
    rng = np.random.default_rng(3)
    v_star = rng.uniform(-1.0, 1.0, 8)
    _, q = _block_lcp(v_star)
    target = rng.uniform(-0.5, 0.5, (8, 1))
    p = v_star[:, None]
    cs = [_block_loss(threads=t)(torch.tensor(q), torch.tensor(target), p=torch.tensor(p)).numpy() for t in (1, 2)]
    assert np.array_equal(cs[0], cs[1])
    one = _block_loss()
    for k in range(8):
        ck = one(torch.tensor(q[k]), torch.tensor(target[k]), p=torch.tensor(p[k])).item()
        assert ck == cs[0][k]


def test_relaxed_loss_bad_settings_and_nonconvex_samples():
    with pytest.raises(lcprelax.InputError):
        _block_loss(a1=-1.0)
    with pytest.raises(TypeError, match="unexpected keyword"):
        _block_loss(a9=1.0)
    # sym(M) indefinite with a tiny prediction weight: nonconvex under the default policy.
    M = sp.csc_matrix(np.array([[0.0, 3.0], [3.0, 0.0]]))
    loss = RelaxedLcpLoss(M, sp.csc_matrix(np.array([[0.1, 0.0]])), a2=1.0)
    with pytest.raises(SolveError, match="nonconvex"):
        loss(torch.tensor([1.0, 1.0], dtype=torch.float64), torch.tensor([1.0], dtype=torch.float64))
