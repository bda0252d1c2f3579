"""LemkeSolver: a 3x3 positive definite LCP solved to complementarity 1e-10 (checked in
NumPy), its backward pass against finite differences, warm start and settings (a crash path
along the covering vector among them), and the
Siconos LCP reader feeding the solver."""
import numpy as np
import pytest
import scipy.sparse as sp

import lcprelax

M = np.array([[4.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, 2.0]])
Q = np.array([-1.0, 2.0, -3.0])


def check_complementary(M, q, r, tol=1e-10):
    z = r.z
    w = M @ z + q
    assert np.min(z) >= -tol
    assert np.min(w) >= -tol
    assert np.max(np.abs(np.minimum(z, w))) <= tol
    assert np.max(np.abs(z * w)) <= tol
    assert np.allclose(r.w, w, atol=1e-12)


def test_small_lcp_solved():
    solver = lcprelax.LemkeSolver()
    solver.setup(sp.csr_matrix(M), Q)
    r = solver.solve()
    assert r.status == "solved", r.message
    assert r.has_solution and r.pivots > 0
    check_complementary(M, Q, r)
    assert r.complementarity <= 1e-10
    # Known active set: z1 = 0 (w1 > 0), z0 and z2 positive.
    assert r.z[0] > 0.1 and r.z[2] > 0.1 and r.z[1] == 0.0
    assert r.z_basic.dtype == np.bool_ and list(r.z_basic) == [True, False, True]


def test_lcp_backward_matches_finite_differences():
    g_z = np.array([1.0, -0.5, 2.0])
    solver = lcprelax.LemkeSolver()
    solver.setup(sp.csc_matrix(M), Q)
    assert solver.solve().status == "solved"
    grad = solver.backward(g_z)
    h = 1e-6
    fd = np.zeros(3)
    for i in range(3):
        values = []
        for sign in (1.0, -1.0):
            q = Q.copy()
            q[i] += sign * h
            s = lcprelax.LemkeSolver()
            s.setup(sp.csc_matrix(M), q)
            values.append(g_z @ s.solve().z)
        fd[i] = (values[0] - values[1]) / (2 * h)
    assert np.max(np.abs(fd)) > 0.1
    assert np.max(np.abs(grad.dq - fd)) / np.max(np.abs(fd)) <= 1e-6
    assert sp.issparse(grad.dM) and grad.dM.shape == (3, 3)


def test_warm_start_and_update_q():
    solver = lcprelax.LemkeSolver(method="dense")
    solver.setup(sp.csc_matrix(M), Q)
    first = solver.solve()
    solver.update_q(Q * 2.0)
    solver.warm_start(first.z_basic)
    second = solver.solve()
    assert second.status == "solved" and second.warm_started and second.pivots == 0
    assert np.allclose(second.z, 2.0 * first.z, atol=1e-12)


def test_diagnostics_of_a_crash_path():
    # The basis of Q's solution {z0, z2} is infeasible for q2 = (-1, -5, -1) (its basic
    # w1 = -5 + z0 + z2 < 0): with crash_start Lemke runs from it and reports the crash
    # path's pivots.
    solver = lcprelax.LemkeSolver(method="sparse", crash_start=True)
    solver.setup(sp.csc_matrix(M), Q)
    first = solver.solve()
    assert first.crash_pivots == 0 and not first.crash_started and first.regularization == 0.0
    assert first.tie_breaks >= 0 and first.ray_rechecks == 0 and first.repair_rounds == 0
    q2 = np.array([-1.0, -5.0, -1.0])
    solver.update_q(q2)
    solver.warm_start(first.z_basic)
    r = solver.solve()
    assert r.status == "solved", r.message
    check_complementary(M, q2, r)
    assert not r.warm_started and r.crash_started
    assert 0 < r.crash_pivots <= r.pivots
    assert r.refactorizations >= 1  # the crash basis is factorized from scratch
    assert r.regularization == 0.0


def test_warm_start_point_purifies_a_degenerate_solution():
    # M = J J^T (6 x 6, rank 2) and a solution loading every row: purification keeps w and
    # finds a vertex solution (at most 2 basic z) without a pivot.
    rng = np.random.default_rng(4)
    J = rng.standard_normal((6, 2))
    Md = J @ J.T
    z = rng.uniform(0.5, 2.0, 6)
    q = -Md @ z
    solver = lcprelax.LemkeSolver()
    solver.setup(sp.csc_matrix(Md), q)
    solver.warm_start_point(z)
    r = solver.solve()
    assert r.status == "solved", r.message
    assert r.warm_started and r.pivots == 0 and r.purification_steps > 0
    assert np.count_nonzero(r.z_basic) <= 2
    check_complementary(Md, q, r, tol=1e-9)
    with pytest.raises(lcprelax.InputError):
        solver.warm_start_point(z[:5])
    with pytest.raises(lcprelax.InputError):
        solver.warm_start_point(z, np.zeros(5, dtype=bool))


def test_lemke_settings():
    assert lcprelax.LemkeSolver().settings["lu_ordering"] == "colamd"
    for ordering in ("colamd", "amd"):
        solver = lcprelax.LemkeSolver(method="sparse", max_pivots=100, covering=np.ones(3), lu_ordering=ordering)
        assert solver.settings["method"] == "sparse" and solver.settings["max_pivots"] == 100
        assert solver.settings["lu_ordering"] == ordering
        solver.setup(sp.csc_matrix(M), Q)
        r = solver.solve()
        assert r.method == "sparse"
        check_complementary(M, Q, r)
    with pytest.raises(lcprelax.InputError, match="lu_ordering"):
        lcprelax.LemkeSolver(lu_ordering="metis")
    # The homotopy crash path: from the basis that solves q + u it reaches q's solution.
    u = np.array([0.5, 0.75, 1.0])
    perturbed = lcprelax.LemkeSolver()
    perturbed.setup(sp.csc_matrix(M), Q + 2.0 * u)
    basis = perturbed.solve().z_basic
    along = lcprelax.LemkeSolver(crash_start=True, crash_cold_fallback=False, crash_flip_rounds=0,
                                 crash_covering_from_basis=False, covering=u)
    assert along.settings["crash_covering_from_basis"] is False
    along.setup(sp.csc_matrix(M), Q)
    along.warm_start(basis)
    check_complementary(M, Q, along.solve())
    with pytest.raises(TypeError, match="pivots"):
        lcprelax.LemkeSolver(pivots=3)
    with pytest.raises(lcprelax.InputError, match="method"):
        lcprelax.LemkeSolver(method="fast")


def test_siconos_lcp_file_solved(data_dir):
    data = lcprelax.read_siconos_lcp(data_dir / "siconos" / "handmade" / "lcp_dense.dat")
    assert sp.issparse(data["M"]) and data["M"].shape == (4, 4)
    # Dense storage is column-major: the printed line "4 -1 0 0" is the first column.
    assert data["M"][1, 0] == -1.0 and data["M"][0, 1] == 1.0
    solver = lcprelax.LemkeSolver()
    solver.setup(data["M"], data["q"])
    r = solver.solve()
    assert r.status == "solved"
    check_complementary(data["M"].toarray(), data["q"], r)


def test_lifted_form_gives_the_plain_solution_and_rejects_a_wrong_one():
    # M = J diag(d) J^T + H with a positive definite H: the sparse basis factorizes K (the
    # momentum rows kept) and must end where the plain basis does.
    rng = np.random.default_rng(4)
    n, m = 40, 12
    J = sp.random(n, m, density=0.2, random_state=5, format="csc")
    d = rng.uniform(0.5, 2.0, m)
    H = sp.diags(rng.uniform(0.1, 1.0, n)).tocsc()
    Mm = (J @ sp.diags(d) @ J.T + H).tocsc()
    q = rng.uniform(-1.0, 1.0, n)
    results = []
    for lifted in (None, (J, d, H)):
        s = lcprelax.LemkeSolver(method="sparse", refactor_interval=5)
        s.setup(Mm, q, lifted=lifted)
        r = s.solve()
        assert r.status == "solved", r.message
        check_complementary(Mm.toarray(), q, r)
        results.append((r.z.copy(), r.pivots))
    assert results[0][1] == results[1][1]
    assert np.allclose(results[0][0], results[1][0], rtol=1e-9, atol=1e-12)
    s = lcprelax.LemkeSolver(method="sparse")
    with pytest.raises(lcprelax.InputError, match="differs from M"):
        s.setup(Mm, q, lifted=(J, d, H * 2.0))
    with pytest.raises(lcprelax.InputError, match="d > 0"):
        s.setup(Mm, q, lifted=(J, -d, H))
    with pytest.raises(lcprelax.InputError, match="tuple"):
        s.setup(Mm, q, lifted=(J, d))
    assert lcprelax.LemkeSolver(lifted_basis=False).settings["lifted_basis"] is False
