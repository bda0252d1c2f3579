"""QpSolver: a small QP solved with its KKT conditions recomputed in NumPy, the same
solution as the C++ command line on a Maros-Meszaros file, update() and settings."""
import json
import subprocess

import numpy as np
import pytest
import scipy.sparse as sp

import lcprelax
from helpers import full_p


def kkt_residuals(prob, r):
    """Dual residual, primal residual and complementarity of result r (∞-norms), with the
    sign convention Px + q + Aᵀy + Gᵀz + z_bounds = 0, z > 0 at an active upper side."""
    P = full_p(prob["P"])
    A, G = prob["A"].toarray(), prob["G"].toarray()
    x, y, z, zb = r.x, r.y, r.z, r.z_bounds
    dual = P @ x + prob["q"] + A.T @ y + G.T @ z + zb
    gx = G @ x
    primal = max(
        np.max(np.abs(A @ x - prob["b"]), initial=0.0),
        np.max(np.maximum(prob["l"] - gx, 0.0), initial=0.0),
        np.max(np.maximum(gx - prob["u"], 0.0), initial=0.0),
        np.max(np.maximum(prob["xl"] - x, 0.0)),
        np.max(np.maximum(x - prob["xu"], 0.0)),
    )

    def comp(value, lo, hi, mult):
        # z⁺·(distance to the upper side), or z⁺ itself where that side is +∞; same below.
        up = np.maximum(mult, 0.0) * np.where(np.isfinite(hi), hi - value, 1.0)
        down = np.maximum(-mult, 0.0) * np.where(np.isfinite(lo), value - lo, 1.0)
        return max(np.max(np.abs(up), initial=0.0), np.max(np.abs(down), initial=0.0))

    complementarity = max(comp(gx, prob["l"], prob["u"], z), comp(x, prob["xl"], prob["xu"], zb))
    return np.max(np.abs(dual)), primal, complementarity


def test_small_qp_solved_with_kkt_residuals(small_qp):
    solver = lcprelax.QpSolver()
    solver.setup(**small_qp)
    r = solver.solve()
    assert r.status == "solved", r.message
    assert r.has_solution
    dual, primal, comp = kkt_residuals(small_qp, r)
    assert dual <= 1e-8
    assert primal <= 1e-8
    assert comp <= 1e-8
    # The active set the fixture promises: row 0 upper, row 1 lower, bound x3 upper.
    assert r.z[0] > 0.5 and r.z[1] < -0.5 and r.z_bounds[3] > 0.5
    P = full_p(small_qp["P"])
    assert r.objective == pytest.approx(0.5 * r.x @ P @ r.x + small_qp["q"] @ r.x, abs=1e-10)
    assert r.x.dtype == np.float64 and r.x.shape == (5,)


def test_result_arrays_are_copies(small_qp):
    solver = lcprelax.QpSolver()
    solver.setup(**small_qp)
    first = solver.solve()
    x = first.x.copy()
    solver.update(q=small_qp["q"] + 0.1)
    second = solver.solve()
    assert np.array_equal(first.x, x)  # the first result did not change under the second solve
    assert not np.array_equal(second.x, x)


def test_matches_command_line_bitwise(data_dir, cli_path, tmp_path):
    path = data_dir / "maros_meszaros" / "HS76.qps"
    out = tmp_path / "solution.json"
    run = subprocess.run(
        [cli_path, "qp", str(path), "--json", "--solution", str(out)], capture_output=True, text=True, check=False
    )
    report = json.loads(run.stdout)
    cli = json.loads(out.read_text())

    model = lcprelax.read_qps(path)
    solver = lcprelax.QpSolver()
    solver.setup(**model["problem"])
    r = solver.solve()
    assert report["status"] == "solved" and r.status == "solved"
    assert r.iterations == report["iterations"]
    # JSON numbers are printed round-trip exact, so the same computation gives equal bits.
    assert np.array_equal(r.x, np.array(cli["x"]))
    assert np.array_equal(r.z, np.array(cli["y_rows"]))
    assert np.array_equal(r.z_bounds, np.array(cli["y_bounds"]))
    assert r.objective == report["objective"]


def test_update_changes_values_and_refuses_new_pattern(small_qp):
    solver = lcprelax.QpSolver()
    solver.setup(**small_qp)
    solver.solve()
    new_q = small_qp["q"] * 1.5
    solver.update(q=new_q)
    r = solver.solve()
    fresh = lcprelax.QpSolver()
    fresh.setup(**dict(small_qp, q=new_q))
    assert r.status == "solved"
    assert np.allclose(r.x, fresh.solve().x, atol=1e-9)
    assert np.array_equal(solver.problem()["q"], new_q)
    with pytest.raises(lcprelax.InputError, match="pattern"):
        solver.update(P=sp.identity(5, format="csc"))


def test_settings_keywords():
    solver = lcprelax.QpSolver(eps_abs=1e-7, max_iter=50, polish=False, kkt_backend="dense")
    s = solver.settings
    assert s["eps_abs"] == 1e-7 and s["max_iter"] == 50 and s["polish"] is False
    assert s["kkt_backend"] == "dense"
    solver.set_settings(max_iter=7)
    assert solver.settings["max_iter"] == 7
    with pytest.raises(TypeError, match="max_iterations"):
        lcprelax.QpSolver(max_iterations=10)
    with pytest.raises(TypeError, match="max_iter"):
        lcprelax.QpSolver(max_iter=2.5)
    with pytest.raises(TypeError, match="polish"):
        lcprelax.QpSolver(polish=1)
    with pytest.raises(lcprelax.InputError, match="eps_abs"):
        lcprelax.QpSolver(eps_abs=-1.0)
    with pytest.raises(lcprelax.InputError, match="kkt_form"):
        lcprelax.QpSolver(kkt_form="diagonal")


def test_infeasible_is_a_status_and_backward_refuses_it():
    solver = lcprelax.QpSolver()
    G = sp.csc_matrix(np.array([[1.0], [1.0]]))
    solver.setup(sp.csc_matrix((1, 1)), np.array([1.0]), G=G, l=np.array([1.0, -np.inf]), u=np.array([np.inf, 0.0]))
    r = solver.solve()
    assert r.status == "primal_infeasible" and not r.has_solution
    with pytest.raises(lcprelax.UsageError, match="solved"):
        solver.backward(np.ones(1))
