"""lcprelax.Simulator and the scene generators against the C++ semantics
(models/simulator.hpp, scenes/scene_json.hpp, scenes/pile_scene.hpp)."""
import json
import math

import numpy as np
import pytest

import lcprelax

BOX = {
    "name": "box",
    "dt": 0.01,
    "bodies": [{"vertices": [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]], "density": 1000,
                "position": [0, 0.5]}],
    "half_planes": [{"normal": [0, 1], "offset": 0}],
}


def box_text(**changes):
    scene = json.loads(json.dumps(BOX))
    scene.update(changes)
    return json.dumps(scene)


def test_box_rests_on_the_ground(data_dir):
    s = lcprelax.Simulator(data_dir / "scenes" / "box_on_ground.json")
    assert s.num_bodies == 1 and s.name == "box on ground" and s.scene_steps == 200
    energy0 = s.kinetic_energy + s.potential_energy
    for _ in range(100):
        st = s.step()
        assert st.failed_islands == 0
        assert st.max_penetration < 1e-3
    assert s.steps_taken == 100
    assert s.time == pytest.approx(1.0)
    assert s.poses.shape == (1, 3) and s.velocities.shape == (1, 3)
    np.testing.assert_allclose(s.poses[0], [0.0, 0.5, 0.0], atol=1e-3)
    assert np.abs(s.velocities).max() < 1e-6
    assert s.kinetic_energy + s.potential_energy <= energy0 + 1e-6
    assert s.potential_energy == pytest.approx(1000 * 9.81 * 0.5, rel=1e-3)  # -m g.x, m = 1000 kg
    c = s.contacts
    assert len(c["gap"]) == 2 and st.contacts == 2
    assert list(c["body_a"]) == [0, 0] and list(c["body_b"]) == [-1, -1]
    assert c["static_kind"] == ["half_plane", "half_plane"]
    np.testing.assert_allclose(c["normal"], [[0, 1], [0, 1]])
    assert np.all(np.abs(c["gap"]) < 1e-3)
    np.testing.assert_allclose(c["mu"], 0.5)


def test_free_fall_matches_symplectic_euler():
    s = lcprelax.Simulator(box_text(half_planes=[]), dt=0.02)
    for _ in range(5):
        st = s.step()
        assert st.contacts == 0
    # v_k = -g k dt, y_k = y0 - g dt^2 k(k+1)/2
    assert s.velocities[0, 1] == pytest.approx(-9.81 * 0.1)
    assert s.poses[0, 1] == pytest.approx(0.5 - 9.81 * 0.02**2 * 15)


def test_applied_force_moves_the_body_its_way():
    s = lcprelax.Simulator(box_text(), model="convex")
    mass = s.masses[0]
    pushed = np.array([[0.9 * mass * 9.81 * 0.5 + 5000.0, 0.0, 0.0]])  # above μmg: slides
    for _ in range(10):
        s.step(pushed)
    assert s.poses[0, 0] > 1e-3 and s.velocities[0, 0] > 0
    s2 = lcprelax.Simulator(box_text())
    for _ in range(10):
        s2.step(-pushed)
    assert s2.poses[0, 0] < -1e-3
    # a small push (below friction) does not move it
    s3 = lcprelax.Simulator(box_text())
    for _ in range(10):
        s3.step(np.array([[0.1 * mass * 9.81 * 0.5, 0.0, 0.0]]))
    assert abs(s3.poses[0, 0]) < 1e-6


def test_incline_slides_or_sticks():
    angle = 0.3
    slide = lcprelax.Simulator(lcprelax.incline_scene(angle=angle, mu=0.1))
    stick = lcprelax.Simulator(lcprelax.incline_scene(angle=angle, mu=0.5))
    for _ in range(50):
        slide.step(), stick.step()
    assert slide.poses[0, 0] < -0.05  # down the slope (towards -x for angle > 0)
    assert abs(stick.poses[0, 0] - (-math.sin(angle) * 0.5)) < 1e-3


def test_static_bodies_are_rows_and_do_not_move():
    scene = box_text(bodies=BOX["bodies"] + [{"vertices": [[-2, -1], [2, -1], [2, 0], [-2, 0]], "static": True}],
                     half_planes=[])
    s = lcprelax.Simulator(scene)
    assert list(s.is_static) == [False, True] and s.masses[1] == 0
    before = s.poses[1].copy()
    for _ in range(20):
        s.step(np.zeros((2, 3)))
    np.testing.assert_array_equal(s.poses[1], before)
    assert abs(s.poses[0, 1] - 0.5) < 1e-3  # rests on the static slab


def test_settings_overrides_and_dict():
    s = lcprelax.Simulator(box_text(), model="convex", dt=0.005, threads=1, warm_start=False,
                           convex_rho=1e-4, qp=dict(eps_abs=1e-10), lemke=dict(max_pivots=100))
    d = s.settings
    assert d["model"] == "convex" and d["dt"] == 0.005 and d["threads"] == 1
    assert d["warm_start"] is False and d["convex_rho"] == 1e-4
    assert d["qp"]["eps_abs"] == 1e-10 and d["lemke"]["max_pivots"] == 100
    assert d["convex_release_open_contacts"] is False
    s.step()
    assert s.time == pytest.approx(0.005)
    r = lcprelax.Simulator(box_text(), model="convex", convex_release_open_contacts=True)
    assert r.settings["convex_release_open_contacts"] is True


def test_pile_scene_is_deterministic_and_runs():
    a = lcprelax.pile_scene(bodies=12, seed=3, mu=0.4)
    assert a == lcprelax.pile_scene(bodies=12, seed=3, mu=0.4)
    assert a != lcprelax.pile_scene(bodies=12, seed=4, mu=0.4)
    scene = json.loads(a)
    assert len(scene["bodies"]) == 12 and scene["friction"]["default"] == 0.4
    s = lcprelax.Simulator(a, threads=2)
    for _ in range(30):
        st = s.step()
        assert st.failed_islands == 0
    assert s.poses.shape == (12, 3)
    assert np.all(s.poses[:, 1] > 0)  # above the ground


def test_box_stack_and_pyramid_rest():
    for text, n in [(lcprelax.box_stack_scene(boxes=3, size=0.2), 3), (lcprelax.pyramid_scene(base=2, size=0.2), 3)]:
        s = lcprelax.Simulator(text)
        y0 = s.poses[:, 1].copy()
        for _ in range(30):
            st = s.step()
            assert st.max_penetration < 1e-3
        assert s.num_bodies == n
        np.testing.assert_allclose(s.poses[:, 1], y0, atol=2e-3)


def test_bad_input():
    with pytest.raises(lcprelax.InputError, match="invalid JSON"):
        lcprelax.Simulator("{not json")
    with pytest.raises(lcprelax.InputError, match="densty"):
        lcprelax.Simulator('{"bodies": [{"vertices": [[0,0],[1,0],[0,1]], "densty": 1}]}')
    with pytest.raises(lcprelax.InputError, match="no_such_file"):
        lcprelax.Simulator("no_such_file.json")
    with pytest.raises(TypeError, match="scene"):
        lcprelax.Simulator(3)
    with pytest.raises(TypeError, match="unexpected keyword argument 'time_step'"):
        lcprelax.Simulator(box_text(), time_step=0.1)
    with pytest.raises(lcprelax.InputError, match="dt"):
        lcprelax.Simulator(box_text(), dt=-1.0)
    with pytest.raises(lcprelax.InputError, match="model"):
        lcprelax.Simulator(box_text(), model="soft")
    with pytest.raises(TypeError, match="threads"):
        lcprelax.Simulator(box_text(), threads=1.5)
    with pytest.raises(TypeError, match="qp"):
        lcprelax.Simulator(box_text(), qp=3)
    with pytest.raises(TypeError, match="unexpected keyword argument 'eps'"):
        lcprelax.Simulator(box_text(), qp=dict(eps=1))
    s = lcprelax.Simulator(box_text())
    with pytest.raises(lcprelax.InputError, match=r"shape \(1, 3\)"):
        s.step(np.zeros(3))
    with pytest.raises(lcprelax.InputError, match=r"shape \(1, 3\)"):
        s.step(np.zeros((2, 3)))
    with pytest.raises(lcprelax.InputError, match="not finite"):
        s.step(np.array([[np.nan, 0.0, 0.0]]))
    with pytest.raises(TypeError, match="applied"):
        s.step("force")
    assert s.steps_taken == 0  # nothing happened
    with pytest.raises(lcprelax.InputError, match="bodies"):
        lcprelax.pile_scene(bodies=0)
    with pytest.raises(lcprelax.InputError):
        lcprelax.pile_scene(min_size=0.2, max_size=0.1)
    with pytest.raises(lcprelax.InputError, match="contact model"):
        lcprelax.pile_scene(model="soft")
    with pytest.raises(TypeError):
        lcprelax.pile_scene(3)  # keyword-only


def test_warm_start_state_continues_a_pile():
    # A scene file's "warm_start" (docs/formats.md) is the state a saved run's next step starts
    # from: a copy of a 12-body pile with it steps on exactly as the original, a copy without
    # it starts cold; bad entries are InputErrors naming the entry.
    original = lcprelax.Simulator(lcprelax.pile_scene(bodies=12, seed=2), model="lcp", threads=1)
    for _ in range(60):
        original.step()
    state = original.warm_start_state
    assert len(state) > 10 and all(len(e) == 8 and e[7] in (0, 1) for e in state)
    scene = json.loads(lcprelax.pile_scene(bodies=12, seed=2))
    for body, pose, vel in zip(scene["bodies"], original.poses, original.velocities):
        # the generator's vertices are centred on their centroid: position is the pose
        body["position"], body["angle"] = [pose[0], pose[1]], pose[2]
        body["velocity"], body["angular_velocity"] = [vel[0], vel[1]], vel[2]
    scene["model"] = "lcp"
    warm = lcprelax.Simulator(json.dumps(dict(scene, warm_start=[list(e) for e in state])), threads=1)
    cold = lcprelax.Simulator(json.dumps(scene), threads=1)
    assert warm.warm_start_state == state and cold.warm_start_state == []
    a, b, c = original.step(), warm.step(), cold.step()
    assert b.work == a.work and b.warm_started_islands == a.warm_started_islands
    assert c.work > b.work
    np.testing.assert_allclose(warm.poses, original.poses, rtol=0, atol=1e-12)
    bad = dict(scene, warm_start=[[0, -1, 1, 0, 0, 2, 0]])
    with pytest.raises(lcprelax.InputError, match=r"warm_start\[0\]\[5\]"):
        lcprelax.Simulator(json.dumps(bad))


def test_results_are_copies():
    s = lcprelax.Simulator(box_text(half_planes=[]))
    p = s.poses
    p[0, 0] = 99.0
    assert s.poses[0, 0] == 0.0
    st = s.step()
    with pytest.raises(AttributeError):
        st.contacts = 3
