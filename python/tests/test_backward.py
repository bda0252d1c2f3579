"""QpSolver.backward against central finite differences of the solution: the loss
ℓ(x*) = wᵀx* is differentiated with respect to q, active row bounds (u, l) and an
active variable bound xu, on the small QP of conftest.py (strictly complementary active set)."""
import numpy as np
import pytest
import scipy.sparse as sp

import lcprelax

W = np.array([0.7, -1.3, 0.4, 2.0, -0.9])
H = 1e-5


def loss(problem, **changes):
    solver = lcprelax.QpSolver(eps_abs=1e-12)
    solver.setup(**dict(problem, **changes))
    r = solver.solve()
    assert r.status == "solved", r.message
    return W @ r.x


def central(problem, name, i):
    plus, minus = problem[name].copy(), problem[name].copy()
    plus[i] += H
    minus[i] -= H
    return (loss(problem, **{name: plus}) - loss(problem, **{name: minus})) / (2 * H)


@pytest.fixture
def gradient(small_qp):
    solver = lcprelax.QpSolver(eps_abs=1e-12)
    solver.setup(**small_qp)
    assert solver.solve().status == "solved"
    g = solver.backward(W)
    assert g.adjoint_residual < 1e-9
    return g


def rel_error(a, b):
    return np.max(np.abs(np.asarray(a) - np.asarray(b))) / max(1.0, np.max(np.abs(b)))


def test_backward_q_matches_finite_differences(small_qp, gradient):
    fd = np.array([central(small_qp, "q", i) for i in range(5)])
    assert np.max(np.abs(fd)) > 1e-2  # the test would see a wrong gradient
    assert rel_error(gradient.dq, fd) <= 1e-5


def test_backward_bounds_match_finite_differences(small_qp, gradient):
    fd_u0 = central(small_qp, "u", 0)  # the active upper side of row 0
    fd_xu3 = central(small_qp, "xu", 3)  # the active upper bound of x3
    fd_l1 = central(small_qp, "l", 1)  # the active lower side of row 1
    assert abs(fd_u0) > 1e-2 and abs(fd_xu3) > 1e-2 and abs(fd_l1) > 1e-2
    assert rel_error([gradient.du[0]], [fd_u0]) <= 1e-5
    assert rel_error([gradient.dxu[3]], [fd_xu3]) <= 1e-5
    assert rel_error([gradient.dl[1]], [fd_l1]) <= 1e-5
    # Inactive bounds get zero gradient (up to the interior iterate's s/z ratio).
    assert gradient.du[1] == 0.0  # u[1] = +inf
    assert abs(gradient.dxl[0]) <= 1e-9 and abs(gradient.dxu[4]) <= 1e-9


def test_backward_types_and_patterns(small_qp, gradient):
    assert sp.issparse(gradient.dP) and gradient.dP.shape == (5, 5)
    assert sp.issparse(gradient.dA) and gradient.dA.shape == (1, 5)
    assert sp.issparse(gradient.dG) and gradient.dG.shape == (2, 5)
    # dP lives on P's upper-triangular pattern.
    assert sp.tril(gradient.dP, k=-1).nnz == 0
    assert gradient.dP.nnz == small_qp["P"].nnz
    for name, size in [("dq", 5), ("db", 1), ("dl", 2), ("du", 2), ("dxl", 5), ("dxu", 5)]:
        assert getattr(gradient, name).shape == (size,)


def test_backward_checks_sizes(small_qp):
    solver = lcprelax.QpSolver()
    solver.setup(**small_qp)
    solver.solve()
    with pytest.raises(lcprelax.InputError, match="expected 5"):
        solver.backward(np.ones(3))
    with pytest.raises(lcprelax.InputError, match="expected 2"):
        solver.backward(np.ones(5), dl_dz=np.ones(4))
