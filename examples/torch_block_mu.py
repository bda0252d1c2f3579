"""Example: learn the friction coefficient μ of the 1-D block with PyTorch, through
lcprelax.torch's LcpLayer (the "hard" loss) and RelaxedLcpLoss (the relaxed loss).

The block (models/block1d.hpp; Parmar, Halm & Posa, IROS 2021) slides on the ground and is
pushed: one step maps the velocity v (m/s) and push u (N·s) to v⁺ = v* + λ/m, v* = v + u/m,
with the Coulomb friction impulse |λ| ≤ μ·mg (mg: the weight impulse of one step, N·s).
As an LCP in z = (λ⁺, λ⁻, γ):  M = [[1/m, −1/m, 1], [−1/m, 1/m, 1], [−1, −1, 0]],
q = (v*, −v*, μ·mg), and the prediction is v⁺ = v* + (λ⁺ − λ⁻)/m, i.e. P = [1/m, −1/m, 0],
p = v*. Here m = 1 kg, mg = 1 N·s, true μ = 0.3; 200 transitions, 1% noise.

1. From μ = 3 (ten times too high) every transition sticks in the model (|v*| < 3 m/s), and
   the hard loss mean (v⁺(μ) − v̄)², differentiated through Lemke (LcpLayer), has a gradient
   of exactly 0 in μ, whatever the data say (the paper's point).
2. The relaxed loss (RelaxedLcpLoss: the prediction error moved into a softened QP whose
   complementarity term prices the misfit, γ·μmg with γ ≥ |v⁺|) has a nonzero gradient
   from every sample with 2|v̄| + |v*| > μmg/m; Adam on log μ over the full batch recovers μ.
Exit status 1 unless the hard gradient is exactly 0, the relaxed one points towards the
truth, and the learned μ is within 2% of it.
Run:  PYTHONPATH=build/python python3 examples/torch_block_mu.py
"""
import sys

import numpy as np
import scipy.sparse as sp
import torch

from lcprelax.torch import LcpLayer, RelaxedLcpLoss

TRUE_MU, INITIAL_MU, SAMPLES = 0.3, 3.0, 200

# Data: half of the transitions stick under the true μ (|v*| < μ·mg/m = 0.3 m/s), half
# slide (|v*| up to 2.5 m/s, below the initial guess's sticking limit 3 m/s); random directions.
rng = np.random.default_rng(7)
speed = np.where(np.arange(SAMPLES) % 2 == 0, rng.uniform(0.0, TRUE_MU, SAMPLES), rng.uniform(TRUE_MU, 2.5, SAMPLES))
v_star = speed * rng.choice([-1.0, 1.0], SAMPLES)
v_next = v_star - np.sign(v_star) * np.minimum(np.abs(v_star), TRUE_MU * 1.0)
v_next += 0.01 * np.sqrt(np.mean(v_next**2)) * rng.standard_normal(SAMPLES)
print(f"{SAMPLES} transitions, {np.sum(np.abs(v_star) <= TRUE_MU)} stick under the true block")

M = sp.csc_matrix(np.array([[1.0, -1.0, 1.0], [-1.0, 1.0, 1.0], [-1.0, -1.0, 0.0]]))
P = sp.csc_matrix(np.array([[1.0, -1.0, 0.0]]))
vs = torch.tensor(v_star)
target = torch.tensor(v_next)[:, None]


def lcp_q(mu):
    """(B, 3): q = (v*, −v*, μ·mg) with mg = 1; differentiable in μ."""
    return torch.stack([vs, -vs, mu.expand(SAMPLES)], dim=1)


log_mu = torch.tensor(np.log(INITIAL_MU), requires_grad=True)

# Step 1: the hard loss through Lemke.
lcp = LcpLayer(M)
z = lcp(lcp_q(log_mu.exp()))
hard = ((vs + z[:, 0] - z[:, 1] - target[:, 0]) ** 2).mean()
hard.backward()
hard_grad = log_mu.grad.item()
log_mu.grad = None

# Step 2: the relaxed loss, same data, trained with Adam.
relaxed = RelaxedLcpLoss(M, P, threads=0)
loss = relaxed(lcp_q(log_mu.exp()), target, p=vs[:, None]).mean()
loss.backward()
relaxed_grad = log_mu.grad.item()
print(f"at mu = {INITIAL_MU}: hard loss {hard.item():.4f} dloss/dlog(mu) = {hard_grad:.3g}; "
      f"relaxed loss {loss.item():.4f} dloss/dlog(mu) = {relaxed_grad:.3g}")

optimizer = torch.optim.Adam([log_mu], lr=0.05)
for epoch in range(600):
    optimizer.zero_grad()
    loss = relaxed(lcp_q(log_mu.exp()), target, p=vs[:, None]).mean()
    loss.backward()
    optimizer.step()
mu = log_mu.exp().item()
error = abs(mu - TRUE_MU) / TRUE_MU
print(f"learned mu {mu:.5f} (true {TRUE_MU}, relative error {error:.2e}) after 600 Adam steps")
ok = hard_grad == 0.0 and relaxed_grad > 0.0 and error <= 0.02
print("OK" if ok else "FAILED")
sys.exit(0 if ok else 1)
