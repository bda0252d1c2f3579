#!/usr/bin/env python3
"""QpLayer forward + backward per sample against a dense batched PyTorch reference.

The problem is the relaxed LCP QP of the 1-D block (Parmar, Halm & Posa, IROS 2021; the
seeds' QP, learn/relaxed_lcp.hpp) with soft nonnegativity and soft lambdas: 9 variables
x = (λ, s, t), 6 rows and 6 bounds,
    min ½xᵀHx + hᵀx   s.t.  Mλ + s ≥ −q,  λ + t ≥ 0,  s, t ≥ 0,
H = blockdiag(2a1 PᵀP + a2(M + Mᵀ) + εI, (a3 + ε)I, (a4 + ε)I), h = (2a1 Pᵀ(p − x̄) + a2 q, 0, 0),
with M the block's LCP matrix (m = 1), P = [1, −1, 0], weights a1 = a2 = 1, a3 = a4 = 20,
ε = 1e-3. Each sample has its own v* and target x̄ (so its own h and row bounds); the loss is
Σ wᵀx over the batch, and gradients are taken for h, the row bounds and the values of H.

- lcprelax: lcprelax.torch.QpLayer (interior point in C++, OpenMP over samples, backward =
  one adjoint solve with each sample's final factorization), eps_abs = 1e-9, with each
  engine: "dense" (DenseQpSolver, the default for a problem this small) and "sparse"
  (QpSolver).
- reference: written here, dense and batched in PyTorch: a Mehrotra predictor-corrector
  interior point on all B problems at once (torch.linalg.cholesky / cholesky_solve of the
  9×9 normal matrices H + Cᵀ(Z/S)C, every bound as a row of C; a sample stops moving once
  its residuals meet the tolerance, the batch once all do), stopped when every sample's
  residuals are ≤ 1e-9; backward by the implicit function theorem on the KKT conditions
  (OptNet, Amos & Kolter 2017) with one batched dense solve of the 21×21 adjoint system.
Both compute the same x and gradients: the run checks them against each other with both
solvers at 1e-12: the median over samples of the largest gradient difference relative to the
largest gradient, and how many samples differ by more than 1e-6 (samples with a weakly active
constraint, where the gradient is one-sided and each interior point gives its own
interpolation; FD sits between them) (at 1e-9 they may differ by ~1e-4 in x: the relaxed QP's curvature along
λ⁺ = λ⁻ is only ε = 1e-3, so x is determined to ~√(2·tol/ε), and its gradients by 1/ε more).

Times are wall-clock seconds per sample of forward + backward, best of 3 repetitions of
enough calls to take ≳ 0.3 s, threads set for both (OpenMP for lcprelax,
torch.set_num_threads for the reference), all in one run.

Usage: PYTHONPATH=build/python python3 bench/run_qp_layer.py [--csv bench/results/qp_layer.csv]
"""
import argparse
import math
import time

import numpy as np
import scipy.sparse as sp
import torch

from lcprelax.torch import QpLayer

AGREE_TOL = 1e-11  # both solvers, for the agreement check
A1, A2, A3, A4, EPS = 1.0, 1.0, 20.0, 20.0, 1e-3
M_BLOCK = np.array([[1.0, -1.0, 1.0], [-1.0, 1.0, 1.0], [-1.0, -1.0, 0.0]])
P_PRED = np.array([[1.0, -1.0, 0.0]])


def relaxed_block_qp():
    """H (9×9), the rows C_rows (6×9) of Mλ + s ≥ −q and λ + t ≥ 0."""
    H = np.zeros((9, 9))
    H[:3, :3] = 2 * A1 * P_PRED.T @ P_PRED + A2 * (M_BLOCK + M_BLOCK.T) + EPS * np.eye(3)
    H[3:6, 3:6] = (A3 + EPS) * np.eye(3)
    H[6:, 6:] = (A4 + EPS) * np.eye(3)
    G = np.zeros((6, 9))
    G[:3, :3], G[:3, 3:6] = M_BLOCK, np.eye(3)
    G[3:, :3], G[3:, 6:] = np.eye(3), np.eye(3)
    return H, G


def samples(B, rng):
    """Per-sample h (B, 9) and row lower bounds l (B, 6) for random states and targets."""
    v_star = rng.uniform(-1.0, 1.0, B)
    target = np.clip(v_star, -0.5, 0.5) + 0.05 * rng.standard_normal(B)
    q = np.stack([v_star, -v_star, np.full(B, 0.5)], axis=1)  # μmg = 0.5
    h = np.zeros((B, 9))
    h[:, :3] = 2 * A1 * (v_star - target)[:, None] * P_PRED[0] + A2 * q
    l = np.concatenate([-q, np.zeros((B, 3))], axis=1)
    return h, l


def ipm_reference(H, h, C, d, tol=1e-9, max_iter=80):
    """Batched Mehrotra interior point: min ½xᵀHx + hᵀx s.t. Cx ≥ d (all float64 tensors,
    H (B|1, n, n), h (B, n), C (m, n), d (B, m)). Returns x, z (multipliers ≥ 0), s = Cx − d."""
    B, n, m = h.shape[0], h.shape[1], C.shape[0]
    x = torch.zeros(B, n, dtype=h.dtype)
    s = torch.clamp(x @ C.T - d, min=1.0)
    z = torch.ones(B, m, dtype=h.dtype)
    eye = torch.eye(n, dtype=h.dtype)
    for _ in range(max_iter):
        rd = (H @ x.unsqueeze(-1)).squeeze(-1) + h - z @ C
        rp = x @ C.T - s - d
        mu = (s * z).sum(1, keepdim=True) / m
        # per sample: converged samples stop moving (and their systems are not factorized)
        worst = torch.maximum(torch.maximum(rd.abs().max(1).values, rp.abs().max(1).values), (s * z).abs().max(1).values)
        done = (worst <= tol).unsqueeze(1)
        if bool(done.all()):
            break
        K = H + C.T @ ((z / s).unsqueeze(-1) * C)
        K = torch.where(done.unsqueeze(2), eye, K)
        L = torch.linalg.cholesky(K)

        def direction(rc):
            rhs = (-rd - ((rc + z * rp) / s) @ C).unsqueeze(-1)
            dx = torch.cholesky_solve(rhs, L).squeeze(-1)
            dz = -(rc + z * (dx @ C.T + rp)) / s
            ds = dx @ C.T + rp
            return dx, ds, dz

        def step(v, dv):
            ratio = torch.where(dv < 0, -v / dv, torch.full_like(v, math.inf))
            return torch.clamp(ratio.min(1, keepdim=True).values, max=1.0)

        dx, ds, dz = direction(s * z)
        a_p, a_d = step(s, ds), step(z, dz)
        mu_aff = ((s + a_p * ds) * (z + a_d * dz)).sum(1, keepdim=True) / m
        sigma = (mu_aff / mu) ** 3
        dx, ds, dz = direction(s * z + ds * dz - sigma * mu)
        a_p, a_d = 0.99 * step(s, ds), 0.99 * step(z, dz)
        a = torch.where(done, torch.zeros_like(a_p), torch.minimum(a_p, a_d))
        x, s, z = x + a * dx, s + a * ds, z + a * dz
    else:
        raise RuntimeError(f"reference interior point: {int((~done).sum())} samples not at {tol} after {max_iter} iterations")
    return x, z, s


class ReferenceQp(torch.autograd.Function):
    """x*(H, h, d) of min ½xᵀHx + hᵀx s.t. Cx ≥ d, batched and dense; backward by OptNet's
    implicit differentiation of Hx + h − Cᵀz = 0, diag(z)(Cx − d) = 0."""

    tol = 1e-9  # the interior point's stopping tolerance (set by the caller)

    @staticmethod
    def forward(ctx, H, h, d, C):
        with torch.no_grad():
            x, z, s = ipm_reference(H, h, C, d, tol=ReferenceQp.tol)
        ctx.save_for_backward(H, C, x, z, s)
        return x

    @staticmethod
    def backward(ctx, gx):
        H, C, x, z, s = ctx.saved_tensors
        B, n, m = x.shape[0], x.shape[1], C.shape[0]
        J_T = torch.zeros(B, n + m, n + m, dtype=x.dtype)  # Jᵀ of F = (Hx + h − Cᵀz, z∘(Cx − d))
        J_T[:, :n, :n] = H
        J_T[:, :n, n:] = C.T.unsqueeze(0) * z.unsqueeze(1)
        J_T[:, n:, :n] = -C
        J_T[:, n:, n:] = torch.diag_embed(s)
        rhs = torch.cat([gx, torch.zeros(B, m, dtype=x.dtype)], 1)
        ab = torch.linalg.solve(J_T, rhs)
        a, b = ab[:, :n], ab[:, n:]
        dh = -a
        dd = b * z
        dH = -0.5 * (a.unsqueeze(2) * x.unsqueeze(1) + x.unsqueeze(2) * a.unsqueeze(1))
        if ctx.needs_input_grad[0] and H.shape[0] == 1:
            dH = dH.sum(0, keepdim=True)
        return dH, dh, dd, None


def timed(fn, min_seconds=0.3, repeats=3):
    fn()  # warm-up (first setup and analysis)
    calls = 1
    while True:
        t0 = time.perf_counter()
        for _ in range(calls):
            fn()
        if time.perf_counter() - t0 >= min_seconds / 3 or calls >= 1 << 16:
            break
        calls *= 2
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(calls):
            fn()
        best = min(best, (time.perf_counter() - t0) / calls)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csv", help="write the table as CSV here")
    ap.add_argument("--batches", default="1,64,1024")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--engines", default="dense,sparse")
    args = ap.parse_args()
    H, G = relaxed_block_qp()
    Hu = sp.csc_matrix(np.triu(H))
    xl = np.concatenate([np.full(3, -np.inf), np.zeros(6)])
    C = torch.tensor(np.vstack([G, np.eye(9)[3:]]))  # rows, then the bounds s, t ≥ 0
    w = torch.tensor(np.linspace(-1.0, 1.0, 9))
    rows = []
    for B in (int(b) for b in args.batches.split(",")):
        h_np, l_np = samples(B, np.random.default_rng(B))
        for threads in (int(t) for t in args.threads.split(",")):
            torch.set_num_threads(threads)
            for engine in args.engines.split(","):
                tight = QpLayer(Hu, G=sp.csc_matrix(G), threads=threads, engine=engine, eps_abs=AGREE_TOL)
                layer = QpLayer(Hu, G=sp.csc_matrix(G), threads=threads, engine=engine, eps_abs=1e-9)
                Hv = torch.tensor(layer.P_pattern.data, requires_grad=True)
                h = torch.tensor(h_np, requires_grad=True)
                l = torch.tensor(l_np, requires_grad=True)
                xl_t = torch.tensor(xl)
                Hd = torch.tensor(H).unsqueeze(0).requires_grad_(True)
                d_pad = torch.zeros(B, 6, dtype=torch.float64)

                def run_lcprelax(qp_layer=layer):
                    Hv.grad = h.grad = l.grad = None
                    x = qp_layer(h, P=Hv, l=l, xl=xl_t)
                    (x * w).sum().backward()
                    return x

                def run_reference():
                    Hd.grad = h.grad = l.grad = None
                    d = torch.cat([l, d_pad], 1)
                    x = ReferenceQp.apply(Hd, h, d, C)
                    (x * w).sum().backward()
                    return x

                ReferenceQp.tol = AGREE_TOL
                x1 = run_lcprelax(tight).detach()
                gh1, gl1 = h.grad.clone(), l.grad.clone()
                x2 = run_reference().detach()
                gh2, gl2 = h.grad.clone(), l.grad.clone()
                ReferenceQp.tol = 1e-9
                agree_x = (x1 - x2).abs().max().item()
                scale = max(gh2.abs().max().item(), gl2.abs().max().item())
                per_sample = torch.maximum((gh1 - gh2).abs().max(1).values, (gl1 - gl2).abs().max(1).values) / scale
                agree_g = per_sample.median().item()
                degenerate = int((per_sample > 1e-6).sum().item())  # weakly active constraints: one-sided
                t1, t2 = timed(run_lcprelax) / B, timed(run_reference) / B
                rows.append((B, threads, engine, t1, t2, t2 / t1, agree_x, agree_g, degenerate))
                print(f"B={B:5d} threads={threads} engine={engine:6s}: lcprelax {t1 * 1e6:9.2f} us/sample, reference {t2 * 1e6:9.2f} "
                      f"us/sample, reference/lcprelax {t2 / t1:6.2f}, |dx| {agree_x:.1e}, median |dgrad|/|grad| {agree_g:.1e} "
                      f"({degenerate} of {B} samples above 1e-6)",
                      flush=True)
    if args.csv:
        with open(args.csv, "w") as f:
            f.write("batch,threads,engine,lcprelax_us_per_sample,reference_us_per_sample,reference_over_lcprelax,"
                    "max_abs_x_difference_at_1e-11,median_gradient_difference_relative_at_1e-11,samples_gradient_difference_above_1e-6\n")
            for r in rows:
                f.write(f"{r[0]},{r[1]},{r[2]},{r[3] * 1e6:.3f},{r[4] * 1e6:.3f},{r[5]:.3f},{r[6]:.2e},{r[7]:.2e},{r[8]}\n")


if __name__ == "__main__":
    main()
