"""PyTorch layers over lcprelax's solvers: QpLayer, LcpLayer and RelaxedLcpLoss.

Each layer is a :class:`torch.nn.Module` whose forward pass solves a batch of problems
with one sparsity pattern in C++ (OpenMP over the samples, the GIL released) and whose
backward pass is the solvers' adjoint, reusing each sample's final factorization (QP) or
basis (LCP): no second solve. Conventions are the C++ ones (docs/python.md):

* ``QpLayer``: ``x* = argmin ½xᵀPx + qᵀx  s.t.  Ax = b,  l ≤ Gx ≤ u,  xl ≤ x ≤ xu``, P given
  as its UPPER triangle. Multipliers: ``Px + q + Aᵀy + Gᵀz + z_bounds = 0``, z > 0 where an
  upper side is active, z < 0 where a lower side is.
* ``LcpLayer``: ``z*`` with ``w = Mz + q,  0 ≤ z ⊥ w ≥ 0`` (Lemke).
* ``RelaxedLcpLoss``: the relaxed LCP loss of Parmar, Halm & Posa (IROS 2021), one value per
  sample, gradient by the envelope theorem (learn/relaxed_lcp.hpp).

Data: the sparsity patterns are fixed when a layer is built (scipy.sparse matrices); the
matrix VALUES passed to ``forward`` are tensors over the pattern's stored entries in the
order of the layer's ``*_pattern`` CSC matrices (``layer.P_pattern.data`` order: column by
column, rows sorted, duplicates summed). Every tensor argument is float64 on the CPU, of
shape ``(k,)`` (shared by the batch; its gradient is summed over the batch) or ``(B, k)``
(one row per sample). Without any batched argument B = 1 and the outputs have no batch
dimension (with one, even of size 1, they keep it). Another dtype or device is a TypeError:
convert with ``.double().cpu()``.

A sample that ends without a solution raises :class:`lcprelax.SolveError` in forward,
naming the sample and its status (never NaN silently). Gradients exist where the solution
map is differentiable (strict complementarity); at a weakly active constraint the dense
engine gives the mean of the one-sided derivatives, the sparse one its last iterate's
interpolation (docs/python.md, "Engine"). If the layer solved another batch between a forward and its
backward, backward first re-solves the saved inputs (results are deterministic, so this
gives the same factorization; it costs one more solve).
"""
from __future__ import annotations

import numpy as np
import torch

from . import _lcprelax

__all__ = ["QpLayer", "LcpLayer", "RelaxedLcpLoss", "SolveError"]


class SolveError(RuntimeError):
    """A sample of a batch ended without a solution (its status is in the message)."""


def _as_numpy(t, name):
    """Tensor (float64, CPU) or None → NumPy view (no copy when contiguous)."""
    if t is None:
        return None
    if not isinstance(t, torch.Tensor):
        raise TypeError(f"{name} must be a torch.Tensor, got {type(t).__name__}")
    if t.dtype != torch.float64:
        raise TypeError(f"{name} must be float64, got {t.dtype} (use .double())")
    if t.device.type != "cpu":
        raise TypeError(f"{name} is on {t.device}; lcprelax layers run on the CPU (use .cpu())")
    if t.dim() not in (1, 2):
        raise ValueError(f"{name} must have shape (k,) or (B, k), got {tuple(t.shape)}")
    return t.detach().contiguous().numpy()


def _batched(tensors):
    """Whether any argument has a batch dimension (then the outputs keep theirs, even B = 1)."""
    return any(t is not None and t.dim() == 2 for t in tensors)


def _check(status, has_solution, what):
    bad = [k for k, ok in enumerate(has_solution) if not ok]
    if bad:
        k = bad[0]
        raise SolveError(f"{what}: sample {k} ended with status '{status[k]}' "
                         f"({len(bad)} of {len(status)} samples without a solution)")


def _grad_for(inp, g):
    """Gradient array g (B, k) for input tensor inp ((k,), (1, k) or (B, k)); None if inp is."""
    if inp is None or not inp.requires_grad:
        return None
    g = torch.from_numpy(np.ascontiguousarray(g))
    if inp.dim() == 1:
        return g.sum(dim=0)
    if inp.shape[0] == 1:
        return g.sum(dim=0, keepdim=True)
    return g


def _save_inputs(ctx, inputs):
    """Saves the (optional) input tensors for backward; None entries are remembered as such."""
    ctx.save_for_backward(*[t if t is not None else torch.empty(0) for t in inputs])
    ctx.given = [t is not None for t in inputs]


def _saved_inputs(ctx):
    return [t if given else None for t, given in zip(ctx.saved_tensors, ctx.given)]


_QP_INPUTS = ("q", "P", "A", "b", "G", "l", "u", "xl", "xu")


class _QpFunction(torch.autograd.Function):
    @staticmethod
    def forward(ctx, layer, *inputs):
        arrays = {name: _as_numpy(t, name) for name, t in zip(_QP_INPUTS, inputs)}
        r = layer.engine.solve(**arrays)
        _check(r.status, r.has_solution, "QpLayer")
        ctx.layer, ctx.generation = layer, r.generation
        ctx.arrays = arrays
        _save_inputs(ctx, inputs)
        x, y, z = (torch.from_numpy(a) for a in (r.x, r.y, r.z))
        return x, y, z

    @staticmethod
    def backward(ctx, dx, dy, dz):
        layer = ctx.layer
        if layer.engine.generation != ctx.generation:
            layer.engine.solve(**ctx.arrays)  # another batch was solved since: redo this one
        g = layer.engine.backward(dx.contiguous().numpy(), dy.contiguous().numpy(), dz.contiguous().numpy())
        saved = _saved_inputs(ctx)
        return (None,) + tuple(_grad_for(t, g[name]) for name, t in zip(_QP_INPUTS, saved))


class QpLayer(torch.nn.Module):
    """Differentiable batch of sparse QPs with a fixed pattern (see the module docstring).

    ``QpLayer(P, A=None, G=None, *, threads=0, **settings)``: P (upper triangle), A, G are
    scipy.sparse patterns (their values are the defaults of ``forward``); settings are
    QpSettings keywords (``eps_abs=1e-9`` ...) and ``engine="auto"|"dense"|"sparse"`` (auto:
    the dense active-set/interior-point solver for small problems, QpSolver otherwise;
    ``layer.engine.engine`` says which). ``forward(q, P=None, A=None, b=None, G=None,
    l=None, u=None, xl=None, xu=None)`` returns x, or (x, y, z) with ``multipliers=True``.
    """

    def __init__(self, P, A=None, G=None, *, threads=0, multipliers=False, **settings):
        super().__init__()
        self.engine = _lcprelax.QpBatch(P, A, G, threads=threads, **settings)
        self.multipliers = multipliers
        self.P_pattern, self.A_pattern, self.G_pattern = (
            self.engine.P_pattern, self.engine.A_pattern, self.engine.G_pattern)

    def forward(self, q, P=None, A=None, b=None, G=None, l=None, u=None, xl=None, xu=None):
        inputs = (q, P, A, b, G, l, u, xl, xu)
        x, y, z = _QpFunction.apply(self, *inputs)
        if not _batched(inputs):
            x, y, z = x[0], y[0], z[0]
        return (x, y, z) if self.multipliers else x


class _LcpFunction(torch.autograd.Function):
    @staticmethod
    def forward(ctx, layer, q, M):
        arrays = {"q": _as_numpy(q, "q"), "M": _as_numpy(M, "M")}
        r = layer.engine.solve(**arrays)
        _check(r.status, r.has_solution, "LcpLayer")
        ctx.layer, ctx.generation, ctx.arrays = layer, r.generation, arrays
        _save_inputs(ctx, (q, M))
        return torch.from_numpy(r.z)

    @staticmethod
    def backward(ctx, dz):
        layer = ctx.layer
        if layer.engine.generation != ctx.generation:
            layer.engine.solve(**ctx.arrays)
        g = layer.engine.backward(dz.contiguous().numpy())
        q, M = _saved_inputs(ctx)
        return None, _grad_for(q, g["q"]), _grad_for(M, g["M"])


class LcpLayer(torch.nn.Module):
    """Differentiable batch of LCPs solved by Lemke: ``forward(q, M=None)`` returns z.

    ``LcpLayer(M, *, threads=0, **settings)``: M's pattern (scipy.sparse n×n; its values are
    the default of ``forward``'s M), LemkeSettings keywords.
    """

    def __init__(self, M, *, threads=0, **settings):
        super().__init__()
        self.engine = _lcprelax.LemkeBatch(M, threads=threads, **settings)
        self.M_pattern = self.engine.M_pattern

    def forward(self, q, M=None):
        z = _LcpFunction.apply(self, q, M)
        return z if _batched((q, M)) else z[0]


_RELAXED_INPUTS = ("q", "target", "M", "P", "p", "E", "e")


class _RelaxedFunction(torch.autograd.Function):
    @staticmethod
    def forward(ctx, layer, *inputs):
        arrays = {name: _as_numpy(t, name) for name, t in zip(_RELAXED_INPUTS, inputs)}
        r = layer.engine.evaluate(**arrays)
        _check(r.status, r.solved, "RelaxedLcpLoss")
        ctx.grads = r.gradient
        _save_inputs(ctx, inputs)
        return torch.from_numpy(r.cost)

    @staticmethod
    def backward(ctx, dc):
        w = dc.detach().numpy()[:, None]
        saved = _saved_inputs(ctx)
        return (None,) + tuple(_grad_for(t, w * ctx.grads[name]) for name, t in zip(_RELAXED_INPUTS, saved))


class RelaxedLcpLoss(torch.nn.Module):
    """The relaxed LCP loss per sample: ``forward(q, target, M=None, P=None, p=None, E=None,
    e=None)`` returns c of shape (B,) (a scalar without batched inputs).

    ``RelaxedLcpLoss(M, P, E=None, *, threads=0, qp=None, **settings)``: patterns of M (n×n),
    P (k×n; the prediction x̂ = Pλ + p of the next state), E (r×n, max dissipation); settings
    a1..a5, soft_nonnegativity, soft_lambdas, l1_softness, max_dissipation, regularization,
    nonconvex; ``qp`` a dict of QpSettings keywords.
    """

    def __init__(self, M, P, E=None, *, threads=0, qp=None, **settings):
        super().__init__()
        self.engine = _lcprelax.RelaxedLcpBatch(M, P, E, threads=threads, qp=qp, **settings)
        self.M_pattern, self.P_pattern, self.E_pattern = (
            self.engine.M_pattern, self.engine.P_pattern, self.engine.E_pattern)

    def forward(self, q, target, M=None, P=None, p=None, E=None, e=None):
        inputs = (q, target, M, P, p, E, e)
        c = _RelaxedFunction.apply(self, *inputs)
        return c if _batched(inputs) else c[0]
