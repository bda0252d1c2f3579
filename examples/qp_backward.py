"""Example: solve a small sparse QP with lcprelax.QpSolver and differentiate its solution.

    minimize    ½ xᵀPx + qᵀx
    subject to  x0 + x1 + x2 = 1                  (A x = b)
                x0 − x1 ≤ 0,  0.5 ≤ x0 + 2x2 ≤ 2  (l ≤ G x ≤ u)
                x ≥ 0                              (xl ≤ x ≤ xu)

The same problem as examples/qp_backward.cpp. Conventions (docs/python.md): matrices are
scipy.sparse (a dense ndarray is a TypeError); P is given as its UPPER triangle; the
multipliers satisfy P x + q + Aᵀy + Gᵀz + z_bounds = 0 with z > 0 where an upper side is
active and z < 0 where a lower side is. The solver is unit-agnostic.

backward(w) returns the gradient of ℓ(x*) = wᵀx* with respect to every datum; two entries
are checked against central finite differences. Exit status 1 when a check fails.
Run:  PYTHONPATH=build/python python3 examples/qp_backward.py
"""
import sys

import numpy as np
import scipy.sparse as sp

import lcprelax

inf = np.inf
PROBLEM = dict(
    P=sp.csc_matrix(np.array([[4.0, 1.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 1.0]])),  # upper triangle
    q=np.array([-1.0, -2.0, 1.5]),
    A=sp.csc_matrix(np.array([[1.0, 1.0, 1.0]])),
    b=np.array([1.0]),
    G=sp.csc_matrix(np.array([[1.0, -1.0, 0.0], [1.0, 0.0, 2.0]])),
    l=np.array([-inf, 0.5]),  # row 0 is one-sided (upper only)
    u=np.array([0.0, 2.0]),
    xl=np.zeros(3),
    xu=np.full(3, inf),
)
W = np.array([1.0, 2.0, -1.0])  # ℓ(x) = wᵀx, so ∂ℓ/∂x = w
EPS = 1e-11  # tight, so that the finite differences are accurate


def loss(**changes):
    """ℓ at the solution of PROBLEM with some data replaced (a fresh solver each time)."""
    solver = lcprelax.QpSolver(eps_abs=EPS)
    solver.setup(**dict(PROBLEM, **changes))
    return W @ solver.solve().x


def central(name, i, h=1e-6):
    plus, minus = PROBLEM[name].copy(), PROBLEM[name].copy()
    plus[i] += h
    minus[i] -= h
    return (loss(**{name: plus}) - loss(**{name: minus})) / (2 * h)


def main():
    solver = lcprelax.QpSolver(eps_abs=EPS)
    solver.setup(**PROBLEM)
    r = solver.solve()
    print(f"status {r.status} ({r.message}), {r.iterations} iterations")
    if not r.has_solution:
        return 1
    print(f"objective {r.objective:.10g}; residuals: primal {r.primal_residual:.2e}, "
          f"dual {r.dual_residual:.2e}, gap {r.duality_gap:.2e}")
    print("x =", r.x)
    # Row 1 is on its lower side (z[1] < 0); row 0 and the bounds are inactive.
    print("y =", r.y, " z =", r.z, " z_bounds =", r.z_bounds)

    # The sign convention made explicit (the full symmetric P from its upper triangle).
    P = PROBLEM["P"]
    P_full = P + sp.triu(P, k=1).T
    stationarity = (P_full @ r.x + PROBLEM["q"] + PROBLEM["A"].T @ r.y + PROBLEM["G"].T @ r.z
                    + r.z_bounds)
    print(f"|Px + q + A'y + G'z + z_bounds|_inf = {np.max(np.abs(stationarity)):.2e}")

    g = solver.backward(W)  # reuses the final KKT factorization
    print("dl/dq =", g.dq, " dl/db =", g.db, " dl/dl =", g.dl, " dl/du =", g.du)
    # At roundoff for a well-posed gradient; far above 1e-9 the KKT matrix is singular at
    # the optimum and the gradient does not exist.
    print(f"adjoint residual {g.adjoint_residual:.2e}")

    ok = g.adjoint_residual < 1e-9
    for name, i, adjoint in [("q", 0, g.dq[0]), ("l", 1, g.dl[1])]:
        fd = central(name, i)
        err = abs(adjoint - fd) / max(1.0, abs(fd))
        print(f"dl/d{name}[{i}]: backward {adjoint:.8f}, finite difference {fd:.8f}, relative error {err:.1e}")
        ok = ok and err <= 1e-5
    print("OK: gradients agree" if ok else "FAILED: gradient check")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
