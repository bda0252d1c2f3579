"""lcprelax.PolygonObjective (learn/polygon_objective.hpp): one polygon thrown onto the
ground, the hard, relaxed and convex losses and their gradients in μ, mass, inertia, the
vertices and the ground, against central differences (the losses' QPs at 1e-12 so that the
adjoint gradients are as accurate as the differences); a descent step lowers the loss; bad
input raises clear errors."""
import numpy as np
import pytest

import lcprelax

TIGHT = dict(eps_abs=1e-12)


def central_difference(objective, theta, rel=1e-5):
    g = np.zeros(len(theta))
    for i in range(len(theta)):
        h = rel * max(abs(theta[i]), 1e-2)  # ground height and angle are 0 at the truth
        e = np.zeros(len(theta))
        e[i] = h
        g[i] = (objective.evaluate(theta + e)[0] - objective.evaluate(theta - e)[0]) / (2 * h)
    return g


@pytest.mark.parametrize("method,kw", [("hard", {}), ("convex", dict(qp=TIGHT)),
                                       ("relaxed", dict(relaxed_warm_center=False, qp=TIGHT))])
def test_polygon_gradient_matches_central_differences(method, kw):
    o = lcprelax.PolygonObjective(method, learn="mu,mass,inertia,ground", samples=60, **kw)
    assert o.parameter_names == ["mu", "mass", "inertia", "ground_height", "ground_angle"]
    assert o.dataset["transitions"] == 60 == o.num_samples
    np.testing.assert_allclose(o.true_values[:3], [0.4, 1.5, 0.06])
    theta = o.perturbed_values(0.2)
    loss, grad = o.evaluate(theta)
    assert loss > 0 and np.all(grad[:3] != 0)
    np.testing.assert_allclose(grad, central_difference(o, theta), rtol=1e-4, atol=1e-6 * np.abs(grad).max())


def test_polygon_vertex_gradient_matches_central_differences():
    o = lcprelax.PolygonObjective("convex", learn="vertices", samples=40, qp=TIGHT)
    assert o.parameter_names[:2] == ["vertex0.x", "vertex0.y"] and len(o.parameter_names) == 8
    theta = o.perturbed_values(0.1, seed=3)
    loss, grad = o.evaluate(theta)
    np.testing.assert_allclose(grad, central_difference(o, theta), rtol=1e-3, atol=1e-6 * np.abs(grad).max())


def test_polygon_loss_is_zero_at_the_truth_and_a_step_against_the_gradient_lowers_it():
    o = lcprelax.PolygonObjective("hard", learn="mu,mass,inertia", samples=60)
    assert o.evaluate(o.true_values)[0] < 1e-12
    theta = o.perturbed_values(0.2)
    loss, grad = o.evaluate(theta)
    step = theta - 1e-3 * grad / np.abs(grad).max() * theta
    assert o.evaluate(step)[0] < loss


def test_polygon_threads_give_the_same_bits():
    a = lcprelax.PolygonObjective("relaxed", samples=40, threads=1, relaxed_warm_center=False)
    b = lcprelax.PolygonObjective("relaxed", samples=40, threads=2, relaxed_warm_center=False)
    theta = a.perturbed_values(0.2)
    la, ga = a.evaluate(theta)
    lb, gb = b.evaluate(theta)
    assert la == lb and np.array_equal(ga, gb)


def test_polygon_bad_input():
    with pytest.raises(lcprelax.InputError, match="learn"):
        lcprelax.PolygonObjective("hard", learn="mu,colour")
    with pytest.raises(lcprelax.InputError, match="SceneObjective only"):
        lcprelax.PolygonObjective("hard", learn="mu,gap")
    with pytest.raises(lcprelax.InputError):
        lcprelax.PolygonObjective("soft")
    with pytest.raises(lcprelax.InputError, match="samples"):
        lcprelax.PolygonObjective("hard", samples=0)
    with pytest.raises(lcprelax.InputError):
        lcprelax.PolygonObjective("hard", data_model="newton")
    with pytest.raises(TypeError, match="unexpected keyword argument 'eps'"):
        lcprelax.PolygonObjective("convex", qp=dict(eps=1e-9))
    o = lcprelax.PolygonObjective("hard", learn="mu", samples=10)
    with pytest.raises(lcprelax.InputError, match="mu"):
        o.evaluate([-0.5])
    with pytest.raises(lcprelax.InputError, match="fraction"):
        o.perturbed_values(1.5)
