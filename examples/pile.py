"""Example: drop a pile of random convex polygons into a container and simulate it with
lcprelax.Simulator (the Python side of examples/pile.cpp, with a generated scene).

Units are SI: positions in m, angles in rad, velocities in m/s and rad/s, time in s, forces
in N and torques in N·m. Poses and velocities are (nbodies, 3) arrays, rows (x, y, θ) and
(vx, vy, ω), static bodies included (Simulator.is_static says which). Contact normals point
from body b to body a; a gap φ < 0 is a penetration.

1. lcprelax.pile_scene() writes the scene JSON of 30 polygons above the ground between two
   walls (no two shapes touch initially); the Simulator steps it with the LCP contact model
   (Stewart–Trinkle, Lemke) at Δt = 10 ms for 150 steps (1.5 s).
2. From step 100 on, the topmost body is pushed towards the container's middle with three
   times its friction limit μ·m·g (applied forces are per body, (fx, fy, torque)).
Exit status 1 if an island's contact solve fails, a body leaves the container, the largest
penetration of the settled pile (last 50 steps) exceeds 1 mm, or the pushed body does not
move in the push's direction. (While the pile falls, impacts within one 10 ms step
penetrate a few mm before the post-stabilization pushes the bodies apart: printed.)
Run:  PYTHONPATH=build/python python3 examples/pile.py
"""
import sys

import numpy as np

import lcprelax

sim = lcprelax.Simulator(lcprelax.pile_scene(bodies=30, seed=4, model="lcp"), threads=1)
n = sim.poses.shape[0]
dynamic = ~np.asarray(sim.is_static)
print(f"{n} bodies ({int(dynamic.sum())} dynamic), dt = {sim.settings['dt']} s, model {sim.settings['model']}")

failed, drop_penetration, settled_penetration = 0, 0.0, 0.0
push = np.zeros((n, 3))
top = x_before_push = direction = None
for step in range(150):
    if step == 100:
        top = int(np.argmax(np.where(dynamic, sim.poses[:, 1], -np.inf)))
        x_before_push = sim.poses[top, 0]
        direction = -np.sign(x_before_push) or 1.0
        mu, g = 0.5, -sim.gravity[1]  # pile_scene's default μ; gravity in m/s² (along −y)
        push[top] = (direction * 3.0 * mu * sim.masses[top] * g, 0.0, 0.0)  # N, N, N·m
    stats = sim.step(push if step >= 100 else None)
    failed += stats.failed_islands
    if step < 100:
        drop_penetration = max(drop_penetration, stats.max_penetration)
    else:
        settled_penetration = max(settled_penetration, stats.max_penetration)
    if step % 25 == 0 or step == 149:
        print(f"t = {sim.time:5.2f} s: {stats.contacts:3d} contacts in {stats.islands} islands, "
              f"penetration {stats.max_penetration * 1e3:.3f} mm, kinetic energy {sim.kinetic_energy:.4f} J")

poses = sim.poses[dynamic]
inside = bool(np.all(poses[:, 1] > -1e-3)) and bool(np.all(np.abs(poses[:, 0]) < 10.0))
moved = (sim.poses[top, 0] - x_before_push) * direction
contacts = sim.contacts
print(f"last step: {len(contacts['gap'])} contacts, smallest gap {np.min(contacts['gap']) * 1e3:.3f} mm; "
      f"largest penetration while falling {drop_penetration * 1e3:.2f} mm, settled {settled_penetration * 1e3:.3f} mm; "
      f"the pushed body (mass {sim.masses[top]:.2f} kg) moved {moved * 1e3:.1f} mm along the push")
ok = failed == 0 and inside and settled_penetration <= 1e-3 and moved > 0.0
print("OK" if ok else f"FAILED (failed islands {failed}, inside {inside}, settled penetration {settled_penetration:.2e} m)")
sys.exit(0 if ok else 1)
