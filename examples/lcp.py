"""Example: solve a small LCP with lcprelax.LemkeSolver, check it, and differentiate it.

    find z, w  with  w = M z + q,   0 ≤ z ⊥ w ≥ 0

The same problem as examples/lcp.cpp: M sparse tridiagonal (not symmetric, positive
definite symmetric part, so exactly one solution). In a contact model z would be impulses
(N·s) and w velocities (m/s); the solver is unit-agnostic. M must be scipy.sparse.

backward(c) returns ∂ℓ/∂q and ∂ℓ/∂M (on M's pattern) for ℓ(z*) = cᵀz*; ∂ℓ/∂q[2] is checked
against a central finite difference. Exit status 1 when a check fails.
Run:  PYTHONPATH=build/python python3 examples/lcp.py
"""
import sys

import numpy as np
import scipy.sparse as sp

import lcprelax

M = sp.diags([[-1.0] * 3, [2.0] * 4, [1.0] * 3], offsets=[-1, 0, 1], format="csc")
Q = np.array([-1.0, 2.0, -3.0, 1.0])
C = np.ones(4)  # ℓ(z) = cᵀz, so ∂ℓ/∂z = c


def loss(q):
    """ℓ at the solution for this q (a fresh solver)."""
    solver = lcprelax.LemkeSolver()
    solver.setup(M, q)
    r = solver.solve()
    return C @ r.z if r.has_solution else np.nan


def main():
    solver = lcprelax.LemkeSolver()
    solver.setup(M, Q)
    r = solver.solve()
    print(f"status {r.status}, {r.pivots} pivots, reported complementarity {r.complementarity:.2e}")
    if not r.has_solution:
        print("FAILED:", r.message)
        return 1

    # Independent check: recompute w from z; z ≥ 0, w ≥ 0 and min(z_i, w_i) = 0.
    w = M @ r.z + Q
    tol = 1e-10
    for i in range(4):
        print(f"  i={i}  z={r.z[i]:.6f}  w={w[i]:.6f}  basic={'z' if r.z_basic[i] else 'w'}")
    residual = np.max(np.abs(np.minimum(r.z, w)))
    print(f"max |min(z, w)| = {residual:.2e}")
    ok = r.z.min() >= -tol and w.min() >= -tol and residual <= tol and np.allclose(w, r.w, atol=tol)

    g = solver.backward(C)  # ∂ℓ/∂q is zero on rows where w is basic
    print("dl/dq =", g.dq, f" dl/dM(2,3) = {g.dM[2, 3]:.6f}")

    h = 1e-6
    q_plus, q_minus = Q.copy(), Q.copy()
    q_plus[2] += h
    q_minus[2] -= h
    fd = (loss(q_plus) - loss(q_minus)) / (2 * h)
    err = abs(g.dq[2] - fd) / max(1.0, abs(fd))
    print(f"dl/dq[2]: backward {g.dq[2]:.8f}, finite difference {fd:.8f}, relative error {err:.1e}")
    ok = ok and err <= 1e-6  # z* is piecewise linear in q: the difference is exact to roundoff
    print("OK: complementary, gradient agrees" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
