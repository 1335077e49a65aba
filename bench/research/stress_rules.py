"""Stress components and displacement of the agents from their sigma along the load (research prototype).

Arrays are indexed [i, j]: i across the load (x), j along it counted from the rigid face (j = 0 next to the
base), so the load enters at j = ny - 1. h is the agent size [m]."""
import numpy as np


def smooth_rows(F, width):
    """Local quadratic (Savitzky-Golay-like) fit along j of every column of F (shape (..., ny)) with a Gaussian
    window of half-width width[j] rows (an array): the value of the fit at j. Edges use the one-sided data."""
    ny = F.shape[-1]
    out = np.empty_like(F)
    jj = np.arange(ny)
    for j in range(ny):
        s = max(width[j], 1e-9)
        d = jj - j
        w = np.exp(-0.5 * (d / s) ** 2)
        w[np.abs(d) > 3 * s + 1] = 0
        V = np.stack([np.ones(ny), d, d * d], 1)
        A = V.T @ (w[:, None] * V)
        coef = np.linalg.lstsq(A, (V * w[:, None]).T @ F.reshape(-1, ny).T, rcond=None)[0]
        out.reshape(-1, ny)[:, j] = coef[0]
    return out


def fit_derivs(F, width):
    """The same local quadratic fit; returns value, first and second derivative along j (per row)."""
    ny = F.shape[-1]
    Fr = F.reshape(-1, ny)
    v = np.empty_like(Fr); d1 = np.empty_like(Fr); d2 = np.empty_like(Fr)
    jj = np.arange(ny)
    for j in range(ny):
        s = max(width[j], 1e-9)
        d = jj - j
        w = np.exp(-0.5 * (d / s) ** 2)
        V = np.stack([np.ones(ny), d, d * d], 1)
        A = V.T @ (w[:, None] * V)
        coef = np.linalg.solve(A + 1e-12 * np.eye(3), (V * w[:, None]).T @ Fr.T)
        v[:, j], d1[:, j], d2[:, j] = coef[0], coef[1], 2 * coef[2]
    return v.reshape(F.shape), d1.reshape(F.shape), d2.reshape(F.shape)


def equilibrium_recovery(sy, h, width0=2.0, grow=0.25, base_rows=0, nu=0.3):
    """tau_xy and sigma_x from sigma_y by the two equilibrium equations, each row scanned from its free side.
    Q_j(x) = int_0^x sigma_y dx (the row's force left of x), M_j(x) = int_0^x (x - xi) sigma_y dxi (its moment):
    tau = -dQ/dy, sigma_x = d2M/dy2, both taken from a local quadratic fit over rows whose window grows with
    the depth below the loaded face (width0 + grow * depth rows). Values at the vertical faces; agent = mean."""
    nx, ny = sy.shape
    Q = np.concatenate([np.zeros((1, ny)), np.cumsum(sy, 0) * h], 0)          # at faces 0..nx
    xc = (np.arange(nx) + 0.5) * h
    xf = np.arange(nx + 1) * h
    M = np.array([np.sum(np.clip(xf[k] - xc, 0, None)[:, None] * sy * h * (xc[:, None] < xf[k]), 0) for k in range(nx + 1)])
    depth = (ny - 1 - np.arange(ny)).astype(float)
    width = width0 + grow * depth
    _, dQ, _ = fit_derivs(Q, width)
    _, _, d2M = fit_derivs(M, width)
    # d/dy with y up: rows j increase upward, so d/dy = d/dj / h.
    tau_f = -dQ / h
    sx_f = d2M / h ** 2
    tau = 0.5 * (tau_f[:-1] + tau_f[1:])
    sx = 0.5 * (sx_f[:-1] + sx_f[1:])
    if base_rows > 0:
        # The bonded base holds eps_x = 0: sigma_x = nu sigma_y there (plane stress); blend over base_rows.
        for j in range(min(base_rows, ny)):
            t = (j + 0.5) / base_rows
            sx[:, j] = t * sx[:, j] + (1 - t) * nu * sy[:, j]
    return sx, tau


def von_mises(sx, sy, txy, nu=0.3, plane="stress"):
    sz = nu * (sx + sy) if plane == "strain" else 0.0 * sx
    return np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3 * txy ** 2)


def strains(sx, sy, txy, E, nu, plane="stress"):
    if plane == "strain":
        E, nu = E / (1 - nu ** 2), nu / (1 - nu)
    G = E / (2 * (1 + nu))
    return (sx - nu * sy) / E, (sy - nu * sx) / E, txy / G


def displacement_from_base(ex, ey, gxy, h):
    """Nodes (nx+1, ny+1): u_y = int eps_y dy up each column from the base (u = 0 there); u_x = int (gamma_xy -
    du_y/dx) dy up each node line from the base. Each agent passes its column's value to the one above: a march
    from the rigid face, as the existing u_y. Agent strains go to nodes by averaging the agents around an edge."""
    nx, ny = ex.shape
    # u_y on vertical node lines: each column integrates, nodes average their two columns.
    col = np.concatenate([np.zeros((nx, 1)), np.cumsum(ey, 1) * h], 1)       # (nx, ny+1)
    uy = np.zeros((nx + 1, ny + 1))
    uy[:-1] += col; uy[1:] += col
    uy[1:-1] /= 2
    # du_y/dx at each agent (centre), from its two node lines, at mid-height of the agent.
    uyc = 0.5 * (uy[:, :-1] + uy[:, 1:])                                       # node lines at agent mid-heights
    duy_dx = (uyc[1:] - uyc[:-1]) / h                                          # (nx, ny)
    slope = gxy - duy_dx                                                       # du_x/dy per agent
    colx = np.concatenate([np.zeros((nx, 1)), np.cumsum(slope, 1) * h], 1)
    ux = np.zeros((nx + 1, ny + 1))
    ux[:-1] += colx; ux[1:] += colx
    ux[1:-1] /= 2
    return np.stack([ux, uy], 2)


def rel_l2(a, b, mask=None):
    if mask is not None:
        a, b = a[mask], b[mask]
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


def ddy(F, h, width):
    """d/dy (y up, rows j upward) of F[i, j] from a local quadratic fit over rows."""
    _, d1, _ = fit_derivs(F, width)
    return d1 / h


def ddx(F, h):
    """d/dx at agent centres: central differences inside, one-sided at the sides."""
    return np.gradient(F, h, axis=0)


def scan_sx(dtau_dy, h, close="linear"):
    """Horizontal equilibrium d sigma_x/dx = -d tau/dy, scanned along each row from the left free side
    (sigma_x = 0 there); what is left at the right free side is removed by a linear tie across the row."""
    nx, ny = dtau_dy.shape
    faces = np.concatenate([np.zeros((1, ny)), -np.cumsum(dtau_dy, 0) * h], 0)
    if close == "linear":
        faces -= np.linspace(0, 1, nx + 1)[:, None] * faces[-1][None, :]
    return 0.5 * (faces[:-1] + faces[1:])


def base_layer(sy, h, nu, ell, with_sy=False, taper=True):
    """The bonded rigid base holds eps_x = 0: sigma_x = nu sigma_y on it (plane stress), fading linearly to 0 at
    height ell above it and, near a free side, as 1 - exp(-d / y) (d the distance to the side, y the height).
    tau_xy (and optionally sigma_y) of that layer from equilibrium integrated down from its top (zero there)."""
    nx, ny = sy.shape
    x = (np.arange(nx) + 0.5) * h
    y = (np.arange(ny) + 0.5) * h
    X, Y = np.meshgrid(x, y, indexing="ij")
    dside = np.minimum(X, nx * h - X)
    e = 1 - np.exp(-dside / Y) if taper else np.ones_like(X)
    phi = np.clip(1 - Y / ell, 0, None)
    sx_b = nu * sy * phi * e
    dsx = np.gradient(sx_b, h, axis=0)
    # tau(y) = int_y^top dsx/dx dy': cumulative from the top row down (agent centre: half its own row).
    c = np.cumsum(dsx[:, ::-1], 1)[:, ::-1] * h - 0.5 * dsx * h
    tau_b = c
    sy_b = np.zeros_like(sy)
    if with_sy:
        dt = np.gradient(tau_b, h, axis=0)
        sy_b = np.cumsum(dt[:, ::-1], 1)[:, ::-1] * h - 0.5 * dt * h
    return sx_b, tau_b, sy_b


def displacement_from_load_line(ex, ey, gxy, h, i0):
    """u_y as displacement_from_base; u_x: the march up from the base along the node line i0 (the load line),
    then eps_x integrated outward along each row of nodes from it (the existing datum, now not held at 0)."""
    u = displacement_from_base(ex, ey, gxy, h)
    nx, ny = ex.shape
    # eps_x at horizontal node lines: mean of the agents above and below the line.
    exn = np.concatenate([ex[:, :1], 0.5 * (ex[:, 1:] + ex[:, :-1]), ex[:, -1:]], 1)   # (nx, ny+1)
    line = np.concatenate([np.zeros((1, ny + 1)), np.cumsum(exn, 0) * h], 0)           # (nx+1, ny+1)
    ux = line - line[i0][None, :] + u[i0, :, 0][None, :]
    return np.stack([ux, u[..., 1]], 2)


def displacement_rows(ex, ey, gxy, h):
    """u_y as displacement_from_base; u_x along each row of nodes: eps_x integrated along the row, its constant
    the mean over the row of the marches up from the base (every column's u_x = int (gamma - du_y/dx) dy)."""
    u = displacement_from_base(ex, ey, gxy, h)
    nx, ny = ex.shape
    exn = np.concatenate([ex[:, :1], 0.5 * (ex[:, 1:] + ex[:, :-1]), ex[:, -1:]], 1)
    line = np.concatenate([np.zeros((1, ny + 1)), np.cumsum(exn, 0) * h], 0)
    const = np.mean(u[..., 0] - line, axis=0)
    return np.stack([line + const[None, :], u[..., 1]], 2)
