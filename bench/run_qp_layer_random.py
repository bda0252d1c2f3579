#!/usr/bin/env python3
"""The QP layer's engines on random strictly convex QPs of several sizes (beyond the relaxed
block QP of run_qp_layer.py): min ½xᵀHx + hᵀx s.t. Cx ≥ d, H = BᵀB/n + 0.1·I (B Gaussian),
C Gaussian (m×n), per sample h Gaussian and d = C x₀ − U(0, 1) (x₀ Gaussian: feasible with
a strict interior), batch 1,024, eps_abs = 1e-9.

Columns: solve + backward per sample of lcprelax.QpBatch with engine "dense" (DenseQpSolver)
and "sparse" (QpSolver), 1 thread, best of 3; then QpLayer (dense engine) forward + backward
against run_qp_layer.py's dense batched PyTorch reference (Mehrotra interior point, OptNet
backward) on `--threads` threads, with their largest |Δx| and median relative gradient
difference. Sizes with 3n + 2m above DenseQpSolver's limit are skipped.

Usage: PYTHONPATH=build/python python3 bench/run_qp_layer_random.py [--threads 2] > bench/results/qp_layer_random.txt
"""
import argparse
import os
import sys
import time

import numpy as np
import scipy.sparse as sp
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_qp_layer as ref  # noqa: E402  (the reference and the timer)

import lcprelax  # noqa: E402
from lcprelax.torch import QpLayer  # noqa: E402

SIZES = ((5, 5), (9, 12), (15, 20), (20, 10), (25, 25))
B = 1024


def problem(n, m):
    rng = np.random.default_rng(n * 100 + m)
    Bm = rng.standard_normal((n, n))
    H = Bm.T @ Bm / n + 0.1 * np.eye(n)
    C = rng.standard_normal((m, n))
    h = rng.standard_normal((B, n))
    d = rng.standard_normal((B, n)) @ C.T - rng.uniform(0, 1, (B, m))
    return H, C, h, d


def engine_times(H, C, h, d):
    out = {}
    for engine in ("dense", "sparse"):
        b = lcprelax.QpBatch(sp.csc_matrix(np.triu(H)), None, sp.csc_matrix(C), threads=1, engine=engine, eps_abs=1e-9)
        b.solve(h, l=d)
        best = float("inf")
        for _ in range(3):
            t = time.perf_counter()
            r = b.solve(h, l=d)
            b.backward(np.ones_like(h))
            best = min(best, time.perf_counter() - t)
        assert set(r.status) == {"solved"}, set(r.status)
        out[engine] = best / B * 1e6
    return out


def layer_vs_reference(H, C, h, d, threads):
    n = H.shape[0]
    layer = QpLayer(sp.csc_matrix(np.triu(H)), G=sp.csc_matrix(C), threads=threads, eps_abs=1e-9)
    ht, dt = torch.tensor(h, requires_grad=True), torch.tensor(d, requires_grad=True)
    Hd, Ct, w = torch.tensor(H).unsqueeze(0), torch.tensor(C), torch.tensor(np.linspace(-1, 1, n))

    def run_layer():
        ht.grad = dt.grad = None
        x = layer(ht, l=dt)
        (x * w).sum().backward()
        return x

    def run_reference():
        ht.grad = dt.grad = None
        x = ref.ReferenceQp.apply(Hd, ht, dt, Ct)
        (x * w).sum().backward()
        return x

    ref.ReferenceQp.tol = 1e-9
    x1 = run_layer().detach()
    g1 = ht.grad.clone()
    try:
        x2 = run_reference().detach()
    except RuntimeError as e:  # the reference's batched Cholesky can break down near the end
        return None, str(e).split("(")[0].strip()
    g2 = ht.grad.clone()
    t1, t2 = ref.timed(run_layer) / B, ref.timed(run_reference) / B
    dg = ((g1 - g2).abs().max(1).values / g2.abs().max()).median().item()
    return (t1 * 1e6, t2 * 1e6, (x1 - x2).abs().max().item(), dg), None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    torch.set_num_threads(a.threads)
    print(f"# batch {B}, eps_abs 1e-9; engines: 1 thread; layer vs reference: {a.threads} threads; µs per sample")
    print("  n   m  3n+2m |  dense  sparse  sparse/dense |  layer  reference  reference/layer  |dx|     median |dg|/|g|")
    for n, m in SIZES:
        H, C, h, d = problem(n, m)
        e = engine_times(H, C, h, d)
        head = f"{n:3d} {m:3d} {3 * n + 2 * m:6d} | {e['dense']:6.2f} {e['sparse']:7.2f} {e['sparse'] / e['dense']:13.1f} | "
        vs, failure = layer_vs_reference(H, C, h, d, a.threads)
        if failure:
            print(head + f"reference failed: {failure}", flush=True)
            continue
        t1, t2, dx, dg = vs
        print(head + f"{t1:6.2f} {t2:10.2f} {t2 / t1:16.1f}  {dx:.1e}  {dg:.1e}", flush=True)


if __name__ == "__main__":
    main()
