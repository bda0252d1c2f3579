"""Learning losses with gradients: lcprelax.BlockObjective (learn/block_losses.hpp) and
lcprelax.SceneObjective (learn/scene_objective.hpp). Gradients are checked against central
differences of the loss at points where it is smooth (no sample at its stick/slip boundary)."""
import numpy as np
import pytest

import lcprelax


@pytest.fixture(scope="module")
def block_data():
    return lcprelax.generate_block_data(0.1, samples=100, seed=2)


def central_difference(objective, theta, rel=1e-6):
    g = np.zeros(len(theta))
    for i in range(len(theta)):
        h = rel * abs(theta[i])
        e = np.zeros(len(theta))
        e[i] = h
        g[i] = (objective.evaluate(theta + e)[0] - objective.evaluate(theta - e)[0]) / (2 * h)
    return g


def test_generated_block_data_follow_the_model(block_data):
    v, u, vn = block_data["v"], block_data["u"], block_data["v_next"]
    assert v.shape == u.shape == vn.shape == (100,)
    assert block_data["mass"] == 1.0 and block_data["mg"] == 1.0
    vstar = v + u  # m = 1
    s = 0.1  # μ mg / m
    expected = np.where(np.abs(vstar) <= s, 0.0, vstar - np.sign(vstar) * s)
    np.testing.assert_allclose(vn, expected, atol=1e-12)
    assert np.sum(np.abs(vstar) <= s) == 50  # half stick


@pytest.mark.parametrize("method", ["hard", "relaxed", "convex"])
def test_block_gradient_matches_central_differences(block_data, method):
    o = lcprelax.BlockObjective(method, **block_data, qp=dict(eps_abs=1e-12), threads=2)
    assert o.parameter_names == ["mu"] and o.method == method and o.num_samples == 100 == len(o)
    for mu in [0.05, 0.2]:
        loss, grad = o.evaluate([mu])
        assert loss > 0 and grad.shape == (1,)
        np.testing.assert_allclose(grad, central_difference(o, np.array([mu])), rtol=1e-5)
        assert np.sign(grad[0]) == np.sign(mu - 0.1)  # towards the truth


def test_block_hard_loss_is_exact_at_the_truth(block_data):
    for method in ["hard", "convex"]:
        loss, grad = lcprelax.BlockObjective(method, **block_data, qp=dict(eps_abs=1e-12)).evaluate([0.1])
        assert loss < 1e-12 and abs(grad[0]) < 1e-5


def test_block_hard_gradient_is_zero_where_everything_sticks(block_data):
    # every sample sticks for μ > slip_max·μ_true = 0.9: the hard gradient is exactly 0
    loss, grad = lcprelax.BlockObjective("hard", **block_data).evaluate([2.0])
    assert loss > 0 and grad[0] == 0.0
    _, grad_relaxed = lcprelax.BlockObjective("relaxed", **block_data).evaluate([2.0])
    assert grad_relaxed[0] > 0


def test_block_mass_and_mg_gradients(block_data):
    o = lcprelax.BlockObjective("relaxed", **block_data, learn_mass=True, learn_mg=True, qp=dict(eps_abs=1e-12))
    assert o.parameter_names == ["mu", "mass", "mg"]
    theta = np.array([0.2, 1.3, 0.8])
    _, grad = o.evaluate(theta)
    np.testing.assert_allclose(grad, central_difference(o, theta), rtol=1e-5)
    np.testing.assert_allclose(o.lower_bounds, 1e-8)


def test_block_reductions_and_samples(block_data):
    o = lcprelax.BlockObjective("relaxed", **block_data)
    mean, gmean = o.evaluate([0.3])
    total, gsum = o.evaluate([0.3], reduction="sum")
    assert total == pytest.approx(100 * mean) and gsum == pytest.approx(100 * gmean)
    parts = [o.evaluate([0.3], samples=[i], reduction="sum")[0] for i in range(100)]
    assert sum(parts) == pytest.approx(total, rel=1e-10)
    # one thread and two give the same bits (fixed-order sums)
    one = lcprelax.BlockObjective("relaxed", **block_data, threads=1).evaluate([0.3])
    assert one[0] == mean and np.array_equal(one[1], gmean)


def test_relaxed_gradient_descent_finds_the_true_mu(block_data):
    o = lcprelax.BlockObjective("relaxed", **block_data)
    mu = 0.5  # 5x too high; every step in log μ
    first, _ = o.evaluate([mu])
    for _ in range(60):
        loss, grad = o.evaluate([mu])
        mu *= np.exp(-50.0 * mu * grad[0])
    assert loss < first / 100
    assert mu == pytest.approx(0.1, rel=0.01)


def test_relaxed_settings_change_the_loss(block_data):
    base, _ = lcprelax.BlockObjective("relaxed", **block_data).evaluate([0.3])
    heavier, _ = lcprelax.BlockObjective("relaxed", **block_data, relaxed=dict(a1=2.0)).evaluate([0.3])
    assert heavier != base


def test_block_bad_input(block_data):
    d = dict(block_data)
    with pytest.raises(lcprelax.InputError, match="unknown method"):
        lcprelax.BlockObjective("soft", **d)
    with pytest.raises(lcprelax.InputError, match="u has length 3"):
        lcprelax.BlockObjective("hard", d["v"], d["u"][:3], d["v_next"])
    bad = d["v"].copy()
    bad[4] = np.nan
    with pytest.raises(lcprelax.InputError, match="sample 4"):
        lcprelax.BlockObjective("hard", bad, d["u"], d["v_next"])
    with pytest.raises(lcprelax.InputError, match="mass"):
        lcprelax.BlockObjective("hard", d["v"], d["u"], d["v_next"], mass=0.0)
    with pytest.raises(TypeError, match="unexpected keyword argument 'b1'"):
        lcprelax.BlockObjective("relaxed", **d, relaxed=dict(b1=1.0))
    with pytest.raises(lcprelax.InputError, match="relaxed"):
        lcprelax.BlockObjective("relaxed", **d, relaxed=dict(a1=-1.0))
    with pytest.raises(TypeError):
        lcprelax.BlockObjective("relaxed", **d, learn_rate=1)
    o = lcprelax.BlockObjective("relaxed", **d)
    with pytest.raises(lcprelax.InputError, match="theta has length 2"):
        o.evaluate([0.1, 0.2])
    with pytest.raises(lcprelax.InputError, match="mu"):
        o.evaluate([-0.1])
    with pytest.raises(lcprelax.InputError, match="mu"):
        o.evaluate([np.nan])
    with pytest.raises(lcprelax.InputError, match="samples"):
        o.evaluate([0.1], samples=[100])
    with pytest.raises(lcprelax.InputError, match="reduction"):
        o.evaluate([0.1], reduction="max")
    with pytest.raises(lcprelax.InputError, match="slip_max"):
        lcprelax.generate_block_data(0.1, slip_max=0.5)


@pytest.fixture(scope="module")
def stack():
    return lcprelax.box_stack_scene(boxes=2, size=0.1, mu=0.5)


# The relaxed and convex losses' QPs at 1e-12: their adjoint gradients are as accurate as the
# solves (at the default 1e-8 the convex inertia derivative, 100× smaller than μ's, is 27%
# off its central difference on this stack).
TIGHT_QP = dict(eps_abs=1e-12)


@pytest.mark.parametrize("method,kw", [("hard", {}), ("convex", dict(qp=TIGHT_QP)),
                                       ("relaxed", dict(relaxed_warm_center=False, qp=TIGHT_QP))])
def test_scene_gradient_matches_central_differences(stack, method, kw):
    o = lcprelax.SceneObjective(stack, method=method, learn=["mu", "mass", "inertia"], steps=30, **kw)
    assert o.parameter_names == ["mu", "class0.mass", "class0.inertia"]
    np.testing.assert_allclose(o.true_values[:2], [0.5, 1000 * 0.1 * 0.1])
    assert o.dataset["transitions"] == 30 == o.num_samples and o.dataset["bodies"] == 2
    theta = o.perturbed_values(0.2)
    assert np.all(theta != o.true_values)
    loss, grad = o.evaluate(theta)
    assert loss > 0
    # relative per parameter, with a floor of 1e-6 of the largest (a derivative that is zero
    # up to the solves' roundoff, e.g. the relaxed loss's inertia here, is compared absolutely)
    np.testing.assert_allclose(grad, central_difference(o, theta, rel=1e-5), rtol=1e-3,
                               atol=1e-6 * np.abs(grad).max())


def test_scene_loss_is_smallest_at_the_truth(stack):
    o = lcprelax.SceneObjective(stack, method="hard", learn="mu,mass", steps=30)
    at_truth, _ = o.evaluate(o.true_values)
    off, grad = o.evaluate(o.perturbed_values(0.2))
    assert at_truth < 1e-10 < off
    # a step against the gradient lowers the loss
    theta = o.perturbed_values(0.2)
    step = theta - 1e-2 * theta * np.sign(grad)
    assert o.evaluate(step)[0] < off


def test_scene_release_of_open_contacts_reaches_the_convex_loss():
    # A falling pile has contacts that stay open under phase 1: with them released, the data
    # and the loss's model differ from the held ones, so does the loss at the same theta.
    pile = lcprelax.pile_scene(bodies=10, seed=1, model="convex")
    losses = []
    for release in (False, True):
        o = lcprelax.SceneObjective(pile, method="convex", learn="mu", steps=30, release_open_contacts=release)
        losses.append(o.evaluate(o.perturbed_values(0.1))[0])
    assert losses[0] != losses[1]
    with pytest.raises(lcprelax.InputError, match="release_open_contacts"):
        lcprelax.SceneObjective(pile, method="relaxed", steps=5, release_open_contacts=True)


def test_scene_bad_input(stack):
    with pytest.raises(lcprelax.InputError, match="learn"):
        lcprelax.SceneObjective(stack, learn="mu,colour", steps=5)
    with pytest.raises(lcprelax.InputError):
        lcprelax.SceneObjective(stack, method="soft", steps=5)
    with pytest.raises(lcprelax.InputError, match="steps"):
        lcprelax.SceneObjective(stack, steps=0)
    with pytest.raises(lcprelax.InputError, match="invalid JSON"):
        lcprelax.SceneObjective("{oops", steps=5)
    with pytest.raises(TypeError, match="learn"):
        lcprelax.SceneObjective(stack, learn=3, steps=5)
    o = lcprelax.SceneObjective(stack, learn="mu", steps=5)
    with pytest.raises(lcprelax.InputError, match="theta has length 2"):
        o.evaluate([0.5, 1.0])


@pytest.mark.parametrize("method,kw", [("hard", {}), ("convex", dict(qp=TIGHT_QP)),
                                       ("relaxed", dict(relaxed_warm_center=False, qp=TIGHT_QP))])
def test_scene_softness_gradient_matches_central_differences(stack, method, kw):
    # The friction table's normal compliance and erp (docs/cli.md, --learn softness): after μ,
    # true 0 (a rigid scene); at nonzero values the gradient matches central differences.
    o = lcprelax.SceneObjective(stack, method=method, learn="mu,softness", steps=30, **kw)
    assert o.parameter_names == ["mu", "compliance", "erp"]
    np.testing.assert_array_equal(o.true_values[1:], 0.0)
    theta = np.array([0.45, 0.02, 0.3])
    loss, grad = o.evaluate(theta)
    assert loss > 0 and grad[1] != 0
    np.testing.assert_allclose(grad, central_difference(o, theta, rel=1e-5), rtol=1e-4,
                               atol=1e-6 * np.abs(grad).max())


def test_scene_lcp_block_is_learned_by_the_hard_loss(stack):
    # The lcp model's per-contact LCP correction (docs/cli.md, --learn block_tied): its 7
    # entries after μ, true 0; the hard loss's gradient in them matches central differences
    # at a small nonzero correction; the other losses refuse it.
    o = lcprelax.SceneObjective(stack, method="hard", learn="mu,block_tied", steps=30)
    assert o.parameter_names == ["mu", "lcp_block.Wnn", "lcp_block.Wnt", "lcp_block.Wtn", "lcp_block.Wtt",
                                 "lcp_block.mu", "lcp_block.qn", "lcp_block.qt"]
    np.testing.assert_array_equal(o.true_values[1:], 0.0)
    theta = o.true_values.copy()
    theta[0] = 0.4
    theta[1:] = [0.02, 0.003, -0.002, 0.015, 0.01, 0.004, -0.003]
    loss, grad = o.evaluate(theta)
    assert loss > 0 and np.all(grad[1:] != 0)
    np.testing.assert_allclose(grad, central_difference(o, theta, rel=1e-5), rtol=1e-4,
                               atol=1e-6 * np.abs(grad).max())
    for method in ("relaxed", "convex"):
        with pytest.raises(lcprelax.InputError, match="hard loss only"):
            lcprelax.SceneObjective(stack, method=method, learn="mu,block", steps=5)
