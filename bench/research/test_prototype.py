#!/usr/bin/python3
"""Checks of the prototype's pieces against closed forms (plain asserts; /usr/bin/python3 test_prototype.py)."""
import numpy as np
import agent_stress_prototype as p

k = dict(p.DEFAULTS)
nx, ny, h, t = 40, 40, 0.005, 0.002

# 1. A uniform sigma_y (the far field of a load that fills the width) has no shear and no sigma_x.
sy = np.full((nx, ny), -5000.0)
tau = p.shear_from_sigma_y(sy, h, 1.0)
d1, _ = p.fit_d1(tau, 1.0)
sx = p.scan_sigma_x(d1 / h, h)
assert np.abs(tau).max() < 1e-9 * 5000 and np.abs(sx).max() < 1e-8 * 5000  # round-off of 1000 N/m sums

# 2. sigma_y growing linearly with depth, c (H - y), across a row from x = 0: vertical equilibrium gives
#    tau = c x exactly (d tau/dx = -d sigma_y/dy = c), scanned from the left free side.
c = 1e5
y = (np.arange(ny) + 0.5) * h
sy = np.tile(c * (ny * h - y), (nx, 1))
tau = p.shear_from_sigma_y(sy, h, 2.0)
x = (np.arange(nx) + 0.5) * h
assert np.allclose(tau, c * x[:, None], rtol=1e-9, atol=1e-6), np.abs(tau - c * x[:, None]).max()

# 3. The deposit carries the whole load through every row (force conserved, no threshold, no loss).
for force in (2.0, -2.0):
    sy, tau_p, bal = p.turning_transfer(nx, ny, h, 0.1, force, t, k)
    rows = -sy.sum(0) * h * t
    assert np.allclose(rows, force, rtol=1e-9), rows[:3]
    assert np.allclose(bal.sum(0), 0, atol=1e-9)

# 4. Linearity: a pull gives the push's fields negated, exactly (up to round-off).
g = dict(nx=nx, ny=ny, h=h, x0=0.1, thick=t, E=206e9, nu=0.3, strain=False, E_eff=206e9, nu_eff=0.3, force=2.0)
a = p.turning_rule(g, k)
b = p.turning_rule(dict(g, force=-2.0), k)
for u, v in zip(a, b):
    assert np.allclose(u, -v, rtol=1e-12, atol=1e-12 * np.abs(u).max())

# 5. A centred load: sigma_x and sigma_y symmetric about the load line, tau antisymmetric.
sx, sy, tau = a
assert np.allclose(sx, sx[::-1], atol=1e-9 * np.abs(sx).max())
assert np.allclose(sy, sy[::-1], atol=1e-9 * np.abs(sy).max())
assert np.allclose(tau, -tau[::-1], atol=1e-9 * np.abs(tau).max())

# 6. The tie closes every row at both free sides: a uniform d tau/dy across a row (a row shear that is not
#    balanced) is taken out entirely by the linear tie, leaving sigma_x = 0.
q = 7.0
sx = p.scan_sigma_x(np.full((nx, ny), q), h)
assert np.abs(sx).max() < 1e-9

# 7. The displacement march holds u = 0 on the base and, for a uniform compression sigma_y = -p,
#    gives u_y = -p y / E and u_x = nu p (x - x_mean) / E (row constant: the mean of the marches = 0).
pr = 5000.0
u = p.displacement(np.zeros((nx, ny)), np.full((nx, ny), -pr), np.zeros((nx, ny)), g)
yn = np.arange(ny + 1) * h
xn = np.arange(nx + 1) * h
assert np.allclose(u[:, :, 1], -pr * yn[None, :] / 206e9, rtol=1e-9, atol=1e-20)
assert np.allclose(u[:, 1:, 0], 0.3 * pr * (xn - xn.mean())[:, None] / 206e9, rtol=1e-9, atol=1e-20)
assert np.all(u[:, 0, :] == 0)
print("test_prototype: all checks passed")
