#!/usr/bin/env python3
"""Issue 40, block3d's sigma_x / sigma_z (session block21): the tie's ceiling under its fitted window,
the top face's (1 - 2 nu) tau_xz with and without the free sides, and tau_xz from the agents' own
x-line balance. Nothing here is fitted: every variant is a stated rule, measured on every block.

Reads, per case NAME, DIR/base_NAME/cells.csv (`workbench compare`, directional rule set) and
DIR/nl_NAME/agent_cells.csv (`workbench agent` with agent.base_layer_3d=0: the agents without the
local layer; the layer is the difference). Recomputes the ties in numpy as agent/src/stress_components.cc
does (derivatives from the Gaussian-weighted quadratic fit over window_length = 5 mm, the row's
leftover taken out linearly) and checks that against the shipped fields (column "check").
Variants (far-field relative L2 of sigma_x, sigma_z, tau_xz, von Mises; von Mises in the body):
  shipped          the directional rule set as it is
  FEM shears w5    the ties fed FEM's three shears through the shipped 5 mm fit (the ties' ceiling)
  FEM shears cd    the same with centred differences (the ceiling docs/agent-model.md quoted)
  FEM tau_xz       the agents' tau_xy, tau_yz with FEM's tau_xz (what a right tau_xz gives), w5 / w2.5
  leftover |s|     the x-line's leftover taken out in proportion to |source| instead of linearly
  +memb            Boussinesq's (1 - 2 nu) in-plane tau_xz of the patch (half-space) added to the
                   agents' tau_xz before the ties read it
  +memb flamant    the same with each free side's traction removed per layer by Flamant's
                   half-plane answer (plane stress, one pass over the four sides)
  balance          tau_xz from the agents' x-line balance: per layer, Q(y, z) = int tau_xz dx obeys
                   dQ/dz = -int d tau_xy/dy dx (Q = 0 at z = 0 and D); what the agents' tau_xz lacks of
                   Q is spread along x like |d tau_xy / dy|
  balance+memb     balance of (agents' + memb) tau_xz
  balance+memb w3/w2.5  the same with the ties' window 3 / 2.5 mm
  bous             Boussinesq's whole tau_xz of the patch (half-space: ray and (1 - 2 nu) parts) in
                   place of the agents'; bous w2.5 the same with the ties' window 2.5 mm;
                   balance(bous) w2.5 its x-line balance as above
Boussinesq's horizontal shear carries 2 (1 - d/rho) a b / r^2 in its (1 - 2 nu) bracket (checked here
by equilibrium, `check_boussinesq`); the prototype of commit 9c00065 had 1 there (its "Boussinesq"
numbers in docs/agent-model.md are with that factor).
Usage: lateral3d_balance.py DIR NAME:W:H:D:XC:h:lw ...  (metres; the load 2 N, nu 0.3)
"""
import csv, sys
import numpy as np

NAMES = ['sigma_x', 'sigma_y', 'sigma_z', 'tau_xy', 'tau_yz', 'tau_xz']

def read(path):
    with open(path) as f:
        r = csv.reader(f); head = next(r)
        a = np.array([[float(v) if v else np.nan for v in row] for row in r])
    return {h.split(' ')[0]: a[:, i] for i, h in enumerate(head)}

def rel(a, f, m): return np.sqrt(np.sum((a[m] - f[m])**2) / np.sum(f[m]**2))

def von_mises(s):
    sx, sy, sz, txy, tyz, txz = s
    return np.sqrt(0.5*((sx-sy)**2 + (sy-sz)**2 + (sz-sx)**2) + 3*(txy**2 + tyz**2 + txz**2))

def to_grid(B, h):
    """Box grids only (every slot an agent)."""
    i = [np.round(B[k]/h - 0.5).astype(int) for k in 'xyz']
    shape = tuple(v.max() + 1 for v in i)
    def g(v):
        a = np.full(shape, np.nan); a[i[0], i[1], i[2]] = v; return a
    return g, (lambda a: a[i[0], i[1], i[2]])

# --- the C++ fit (SlopeFit): per entry a Gaussian-weighted quadratic over 4 windows each way
_fits = {}
def fit_matrix(count, window):
    if (count, window) in _fits: return _fits[(count, window)]
    reach = max(1, int(np.ceil(4*window))); A = np.zeros((count, count))
    if count == 2: A[:] = [[-1, 1], [-1, 1]]
    elif count > 2:
        for j in range(count):
            first, last = max(0, j - reach), min(count - 1, j + reach)
            d = np.arange(first, last + 1) - j; w = np.exp(-0.5*(d/window)**2)
            P = np.stack([np.ones(len(d)), d, d*d], 1); M = (P*w[:, None]).T @ P
            if np.linalg.matrix_rank(M) < 3:
                lo, hi = max(0, j - 1), min(count - 1, j + 1); A[j, lo] -= 1/(hi - lo); A[j, hi] += 1/(hi - lo)
            else: A[j, first:last + 1] = w*(P @ np.linalg.inv(M)[1])
    _fits[(count, window)] = A
    return A

def derivative(field, h, axis, window):
    if window == 0: return np.gradient(field, h, axis=axis)
    A = fit_matrix(field.shape[axis], window/h)
    return np.moveaxis(np.tensordot(A, np.moveaxis(field, axis, 0), axes=(1, 0)), 0, axis)/h

def tie(t_ly, t_lo, h, l, o, window=5e-3, leftover='linear'):
    """sigma_l: d s/dl = -d t_ly/dy - d t_lo/do scanned from the lower end; the leftover taken out."""
    d = np.moveaxis(-derivative(t_ly, h, 1, window) - derivative(t_lo, h, o, window), l, 0)
    n = d.shape[0]; shape = (-1,) + (1,)*(d.ndim - 1)
    faces = np.concatenate([np.zeros((1,) + d.shape[1:]), np.cumsum(h*d, axis=0)])
    if leftover == 'linear': weight = (np.arange(n + 1)/n).reshape(shape)
    else:
        cum = np.concatenate([np.zeros((1,) + d.shape[1:]), np.cumsum(np.abs(d), axis=0)])
        weight = cum/np.maximum(cum[-1][None], 1e-300)
    faces = faces - faces[-1][None]*weight
    return np.moveaxis(0.5*(faces[:-1] + faces[1:]), 0, l)

# --- Boussinesq's (1 - 2 nu) in-plane part of a patch load on the top face (block frame, y up)
def membrane(X, Y, Z, xc, zc, H, P, nu, lw, sub=4):
    out = np.zeros((3, X.size)); offs = (np.arange(sub) + 0.5)/sub*lw - lw/2
    for ox in offs:
        for oz in offs:
            a = X - xc - ox; b = Z - zc - oz; d = np.maximum(H - Y, 1e-12)
            r2 = np.maximum(a*a + b*b, 1e-18); rho = np.sqrt(r2 + d*d)
            k = P/sub**2/(2*np.pi)*(1 - 2*nu)/r2
            out += k*np.array([(1 - d/rho)*(a*a - b*b)/r2 + d*b*b/rho**3, (1 - d/rho)*(b*b - a*a)/r2 + d*a*a/rho**3,
                               2*(1 - d/rho)*a*b/r2 - a*b*d/rho**3])
    return out

def boussinesq_txz(X, Y, Z, xc, zc, H, P, nu, lw, sub=4):
    """tau_xz of Boussinesq's patch load on the top face (block frame: y up), both parts."""
    return membrane(X, Y, Z, xc, zc, H, P, nu, lw, sub)[2] + ray_txz(X, Y, Z, xc, zc, H, P, lw, sub)

def ray_txz(X, Y, Z, xc, zc, H, P, lw, sub=4):
    out = np.zeros(X.size); offs = (np.arange(sub) + 0.5)/sub*lw - lw/2
    for ox in offs:
        for oz in offs:
            a = X - xc - ox; b = Z - zc - oz; d = np.maximum(H - Y, 1e-12); rho = np.sqrt(a*a + b*b + d*d)
            out += -3*P/sub**2/(2*np.pi)*a*b*d/rho**5
    return out

def check_boussinesq(nu=0.3, p=(7e-3, 9e-3, 4e-3), e=1e-7):
    """d sigma_x/dx + d tau_xy/dy + d tau_xz/dz of Boussinesq's field (y up, depth d = H - y) at p."""
    def field(x, y, z):
        X, Y, Z = (np.array([v]) for v in (x, y, z))
        sx, _, txz = membrane(X, Y, Z, 0.0, 0.0, 0.0, 1.0, nu, 1e-9, sub=1)
        d = -y; rho = np.sqrt(x*x + z*z + d*d); k = 1/(2*np.pi)
        return sx[0] - 3*k*x*x*d/rho**5, 3*k*x*d*d/rho**5, txz[0] - 3*k*x*z*d/rho**5  # tau_xy = -tau_x,depth
    x, y, z = p[0], -p[1], p[2]
    return ((field(x + e, y, z)[0] - field(x - e, y, z)[0]) + (field(x, y + e, z)[1] - field(x, y - e, z)[1])
            + (field(x, y, z + e)[2] - field(x, y, z - e)[2]))/(2*e) * (x*x + z*z + y*y)**1.5

def flamant(X, Z, side, W, D, tn, tt, s):
    """(sxx, szz, txz) in the half-plane inside `side` from forces per length tn (into it), tt (along
    it) at points s along the side: sigma_rr = -2 (tn cos + tt sin) / (pi r)."""
    if side in ('x0', 'xW'): n = X[..., None] if side == 'x0' else W - X[..., None]; t = Z[..., None] - s
    else: n = Z[..., None] if side == 'z0' else D - Z[..., None]; t = X[..., None] - s
    r2 = np.maximum(n*n + t*t, 1e-14); srr = -2*(tn*n + tt*t)/(np.pi*r2)
    snn, stt, snt = (srr*n*n/r2).sum(-1), (srr*t*t/r2).sum(-1), (srr*n*t/r2).sum(-1)
    sg = 1 if side in ('x0', 'z0') else -1
    return (snn, stt, sg*snt) if side in ('x0', 'xW') else (stt, snn, sg*snt)

def membrane_free_sides(X, Y, Z, W, H, D, xc, lw, nu=0.3, P=2.0, ds=2.5e-4):
    M = membrane(X, Y, Z, xc, D/2, H, P, nu, lw); out = [M[0].copy(), M[1].copy(), M[2].copy()]
    for y in np.unique(Y):
        sel = Y == y
        for side in ('x0', 'xW', 'z0', 'zD'):
            along_z = side in ('x0', 'xW')
            s = np.arange(ds/2, D if along_z else W, ds)
            fixed = np.full_like(s, {'x0': 0.0, 'xW': W, 'z0': 0.0, 'zD': D}[side])
            m = membrane(fixed, np.full_like(s, y), s, xc, D/2, H, P, nu, lw) if along_z else \
                membrane(s, np.full_like(s, y), fixed, xc, D/2, H, P, nu, lw)
            sg = 1 if side in ('x0', 'z0') else -1
            c = flamant(X[sel], Z[sel], side, W, D, (m[0] if along_z else m[1])*ds, sg*m[2]*ds, s)
            for i in range(3): out[i][sel] += c[i]
    return out

def balanced_txz(txy, txz, h, window=5e-3):
    """The agents' x-line balance: Q(y, z) = int tau_xz dx with dQ/dz = -int d tau_xy/dy dx."""
    s = derivative(txy, h, 1, window); R = s.sum(0)*h
    Q = -(np.cumsum(R, axis=1) - 0.5*R)*h
    nz = R.shape[1]; Q = Q + (R.sum(1)*h)[:, None]*((np.arange(nz) + 0.5)/nz)[None, :]
    w = np.abs(s); w = w/np.maximum(w.sum(0)[None], 1e-300)
    return txz + w*(Q - txz.sum(0)*h)[None]/h

def main(folder, specs):
    cols = ['sigma_x', 'sigma_z', 'tau_xz']
    print(f'Boussinesq equilibrium residual (x r^3, should be ~0): {check_boussinesq():.1e}')
    print(f"{'case':9s} {'variant':20s} " + ' '.join(f'{n:>8s}' for n in cols) + '   vm far  vm body')
    for spec in specs:
        name, W, H, D, xc, h, lw = spec.split(':'); W, H, D, xc, h, lw = map(float, (W, H, D, xc, h, lw))
        B = read(f'{folder}/base_{name}/cells.csv'); N = read(f'{folder}/nl_{name}/agent_cells.csv')
        g, back = to_grid(B, h)
        fem = {n: g(B['fem_' + n]) for n in NAMES}; ag = {n: g(B['agent_' + n]) for n in NAMES}
        lay = {n: g(B['agent_' + n] - N[n]) for n in NAMES}
        far = g(B['far']) > 0.5; body = np.isfinite(fem['sigma_x'])
        X, Y, Z = B['x'], B['y'], B['z']
        txy0, tyz0 = ag['tau_xy'] - lay['tau_xy'], ag['tau_yz'] - lay['tau_yz']  # what the ties read
        memb = g(membrane(X, Y, Z, xc, D/2, H, 2.0, 0.3, lw)[2])
        memb_free = g(membrane_free_sides(X, Y, Z, W, H, D, xc, lw)[2])
        def fields(txz, window=5e-3, leftover='linear', txy=txy0, tyz=tyz0, layer=True):
            v = dict(ag); v['tau_xz'] = txz
            v['sigma_x'] = tie(txy, txz, h, 0, 2, window, leftover) + (lay['sigma_x'] if layer else 0)
            v['sigma_z'] = tie(tyz, txz, h, 2, 0, window, leftover) + (lay['sigma_z'] if layer else 0)
            return v
        check = fields(ag['tau_xz'])
        variants = {'shipped': ag,
                    'FEM shears w5': fields(fem['tau_xz'], txy=fem['tau_xy'], tyz=fem['tau_yz'], layer=False),
                    'FEM shears cd': fields(fem['tau_xz'], 0, txy=fem['tau_xy'], tyz=fem['tau_yz'], layer=False),
                    'FEM tau_xz w5': fields(fem['tau_xz']),
                    'FEM tau_xz w2.5': fields(fem['tau_xz'], 2.5e-3),
                    'leftover |s|': fields(ag['tau_xz'], leftover='source'),
                    '+memb': fields(ag['tau_xz'] + memb),
                    '+memb flamant': fields(ag['tau_xz'] + memb_free),
                    'balance': fields(balanced_txz(txy0, ag['tau_xz'], h)),
                    'balance+memb': fields(balanced_txz(txy0, ag['tau_xz'] + memb, h))}
        for w in (3e-3, 2.5e-3):
            variants[f'balance+memb w{w*1e3:g}'] = fields(balanced_txz(txy0, ag['tau_xz'] + memb, h, w), w)
        bous = g(boussinesq_txz(X, Y, Z, xc, D/2, H, 2.0, 0.3, lw))
        variants['bous'] = fields(bous)
        variants['bous w2.5'] = fields(bous, 2.5e-3)
        variants['balance(bous) w2.5'] = fields(balanced_txz(txy0, bous, h, 2.5e-3), 2.5e-3)
        vmf = von_mises([fem[n] for n in NAMES])
        print(f'{name:9s} check (recomputed - shipped): sigma_x {rel(check["sigma_x"], ag["sigma_x"], far):.1e}, '
              f'sigma_z {rel(check["sigma_z"], ag["sigma_z"], far):.1e}')
        for label, v in variants.items():
            vm = von_mises([v[n] for n in NAMES])
            print(f'{name:9s} {label:20s} ' + ' '.join(f'{rel(v[n], fem[n], far):8.3f}' for n in cols)
                  + f'   {rel(vm, vmf, far):6.3f}  {rel(vm, vmf, body):6.3f}')

if __name__ == '__main__':
    main(sys.argv[1], sys.argv[2:])
