#!/usr/bin/env python3
"""Issue 40, 3D lateral stresses: where block3d's sigma_x / sigma_z error lives and what limits it.

Reads, per case NAME, base_NAME/cells.csv (`workbench compare` of the directional rule set, FEM
fields and the far mask) and nl_NAME/agent_cells.csv (`workbench agent` of the same case with
agent.base_layer_3d=0: the agents without the local base layer). Prints far-field relative L2 of
sigma_x, sigma_z, tau_xy, tau_yz, tau_xz and von Mises (far and body) for:
  shipped       the directional rule set as it is (tie from the packets' shears + local layer)
  tie(FEM)      the tie scan fed FEM's own three shears (the tie's ceiling: it is not the limit)
  pot           tau_xy, tau_yz = grad phi per horizontal layer, Laplacian phi = -d sigma_y / dy
                (the agents' sigma_y; zero flux at free sides; DCT); ties read them and the packets'
                tau_xz; + the local layer and its shear
  pot+FEM txz   the same with FEM's tau_xz (what a right tau_xz would give)
  pot+ray txz   pot, tau_xz = tau_xy tau_yz / sigma_y (a single ray's identity, |sigma_y| floored
                at 5 % of its largest)
  pot+Bous txz  pot, tau_xz Boussinesq's of the patch load plus its four images across the sides
  pot+Airy txz  pot, tau_xz of a plane-stress Airy function per layer loaded by the potential
                shears' d/dy as a body force (cosine transforms: free edges only roughly)
  memb          shipped + Boussinesq's (1 - 2 nu) in-plane part of the patch load (closed form)
  FEM y<H/4     shipped, FEM's own fields below a quarter of the height (an oracle: what a perfect
                base layer could win); FEM y>H/2: above half the height (the load's field)
Usage: lateral3d.py DIR NAME:W:H:D:XC:h:lw ...  (metres; the load 2 N, nu 0.3)
"""
import csv, sys
import numpy as np
from scipy.fft import dctn, idctn

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

def tie(txy, txz, h, l, o):
    """sigma_l: d s/dl = -d t_ly/dy - d t_lo/do scanned from the lower end, the rest out linearly."""
    d = np.moveaxis(-np.gradient(txy, h, axis=1) - np.gradient(txz, h, axis=o), l, 0)
    n = d.shape[0]
    faces = np.concatenate([np.zeros((1,) + d.shape[1:]), np.cumsum(h*d, axis=0)])
    faces -= faces[-1][None] * (np.arange(n + 1) / n).reshape((-1,) + (1,)*(d.ndim - 1))
    return np.moveaxis(0.5*(faces[:-1] + faces[1:]), 0, l)

def potential_shears(sy, h):
    src = -np.gradient(sy, h, axis=1)
    nx, ny, nz = sy.shape
    lam = -((2 - 2*np.cos(np.pi*np.arange(nx)/nx))[:, None] + (2 - 2*np.cos(np.pi*np.arange(nz)/nz))[None, :]) / h**2
    lam[0, 0] = 1
    txy, tyz = np.zeros_like(sy), np.zeros_like(sy)
    for j in range(ny):
        s = dctn(src[:, j, :], type=2, norm='ortho'); s[0, 0] = 0
        phi = idctn(s/lam, type=2, norm='ortho')
        fx = np.zeros((nx + 1, nz)); fx[1:-1] = np.diff(phi, axis=0)/h
        fz = np.zeros((nx, nz + 1)); fz[:, 1:-1] = np.diff(phi, axis=1)/h
        txy[:, j, :] = 0.5*(fx[1:] + fx[:-1]); tyz[:, j, :] = 0.5*(fz[:, 1:] + fz[:, :-1])
    return txy, tyz

def membrane(X, Y, Z, xc, zc, H, P, nu, lw, sub=4):
    out = np.zeros((3, X.size)); offs = (np.arange(sub) + 0.5)/sub*lw - lw/2
    for ox in offs:
        for oz in offs:
            a = X - xc - ox; b = Z - zc - oz; d = np.maximum(H - Y, 1e-12)
            r2 = np.maximum(a*a + b*b, 1e-18); rho = np.sqrt(r2 + d*d)
            k = P/sub**2/(2*np.pi)*(1 - 2*nu)/r2
            out += k*np.array([(1 - d/rho)*(a*a - b*b)/r2 + d*b*b/rho**3, (1 - d/rho)*(b*b - a*a)/r2 + d*a*a/rho**3,
                               (1 - d/rho)*a*b/r2 - a*b*d/rho**3])
    return out

def inv_laplacian(src, h):
    nx, nz = src.shape
    lam = -((2 - 2*np.cos(np.pi*np.arange(nx)/nx))[:, None] + (2 - 2*np.cos(np.pi*np.arange(nz)/nz))[None, :]) / h**2
    lam[0, 0] = 1
    s = dctn(src, type=2, norm='ortho'); s[0, 0] = 0
    return idctn(s/lam, type=2, norm='ortho')

def airy_txz(txy, tyz, h, nu=0.3):
    """Per layer: the shears' d/dy is a body force grad psi; Lap Phi = (1 - nu) psi; tau_xz = -Phi_xz."""
    div = np.gradient(np.gradient(txy, h, axis=1), h, axis=0) + np.gradient(np.gradient(tyz, h, axis=1), h, axis=2)
    out = np.zeros_like(txy)
    for j in range(txy.shape[1]):
        Phi = (1 - nu)*inv_laplacian(inv_laplacian(div[:, j, :], h), h)
        out[:, j, :] = -np.gradient(np.gradient(Phi, h, axis=0), h, axis=1)
    return out

NAMES = ['sigma_x', 'sigma_y', 'sigma_z', 'tau_xy', 'tau_yz', 'tau_xz']
SHOWN = ['sigma_x', 'sigma_z', 'tau_xy', 'tau_yz', 'tau_xz']
def boussinesq_txz(X, Y, Z, xc, zc, H, P, nu, lw, sub=4):
    """tau_xz of Boussinesq's patch load on the top face (block frame: y up)."""
    out = np.zeros(X.size); offs = (np.arange(sub) + 0.5)/sub*lw - lw/2
    for ox in offs:
        for oz in offs:
            a = X - xc - ox; b = Z - zc - oz; d = np.maximum(H - Y, 1e-12)
            r2 = np.maximum(a*a + b*b, 1e-18); rho = np.sqrt(r2 + d*d); k = P/sub**2/(2*np.pi)
            out += k*((1 - 2*nu)/r2*((1 - d/rho)*a*b/r2 - a*b*d/rho**3) - 3*a*b*d/rho**5)
    return out

def main(folder, specs):
    print(f"{'case':10s} {'variant':13s} " + ' '.join(f'{n:>8s}' for n in SHOWN) + '   vm far  vm body')
    for spec in specs:
        name, W, H, D, xc, h, lw = spec.split(':'); W, H, D, xc, h, lw = map(float, (W, H, D, xc, h, lw))
        B = read(f'{folder}/base_{name}/cells.csv'); N = read(f'{folder}/nl_{name}/agent_cells.csv')
        far, body = B['far'] > 0.5, np.isfinite(B['fem_sigma_x'])
        g, back = to_grid(B, h)
        fem = {n: B['fem_' + n] for n in NAMES}
        ag = {n: B['agent_' + n] for n in NAMES}
        layer = {n: B['agent_' + n] - N[n] for n in NAMES}
        G = {n: g(v) for n, v in fem.items()}
        variants = {'shipped': ag}
        v = dict(ag); v['sigma_x'] = back(tie(G['tau_xy'], G['tau_xz'], h, 0, 2)); v['sigma_z'] = back(tie(G['tau_yz'], G['tau_xz'], h, 2, 0))
        variants['tie(FEM)'] = v
        txy, tyz = potential_shears(g(N['sigma_y']), h)
        sy = g(N['sigma_y']); floor = 0.05*np.nanmax(np.abs(sy))
        bous = boussinesq_txz(B['x'], B['y'], B['z'], xc, D/2, H, 2.0, 0.3, lw)
        for x2, z2 in [(-xc, D/2), (2*W - xc, D/2), (xc, -D/2), (xc, 1.5*D)]:
            bous += boussinesq_txz(B['x'], B['y'], B['z'], x2, z2, H, 2.0, 0.3, lw)
        for label, txz in [('pot', g(N['tau_xz'])), ('pot+FEM txz', G['tau_xz']),
                           ('pot+ray txz', txy*tyz/np.where(np.abs(sy) > floor, sy, -floor)), ('pot+Bous txz', g(bous)), ('pot+Airy txz', airy_txz(txy, tyz, h))]:
            v = dict(ag); v['tau_xz'] = back(txz)
            v['tau_xy'], v['tau_yz'] = back(txy) + layer['tau_xy'], back(tyz) + layer['tau_yz']
            v['sigma_x'] = back(tie(txy, txz, h, 0, 2)) + layer['sigma_x']
            v['sigma_z'] = back(tie(tyz, txz, h, 2, 0)) + layer['sigma_z']
            variants[label] = v
        M = membrane(B['x'], B['y'], B['z'], xc, D/2, H, 2.0, 0.3, lw)
        v = dict(ag); v['sigma_x'] = ag['sigma_x'] + M[0]; v['sigma_z'] = ag['sigma_z'] + M[1]; v['tau_xz'] = ag['tau_xz'] + M[2]
        variants['memb'] = v
        variants['FEM y<H/4'] = {n: np.where(B['y'] < H/4, fem[n], ag[n]) for n in NAMES}
        variants['FEM y>H/2'] = {n: np.where(B['y'] >= H/2, fem[n], ag[n]) for n in NAMES}
        vmf = von_mises([fem[n] for n in NAMES])
        for label, v in variants.items():
            vm = von_mises([v[n] for n in NAMES])
            print(f'{name:10s} {label:13s} ' + ' '.join(f'{rel(v[n], fem[n], far):8.3f}' for n in SHOWN)
                  + f'   {rel(vm, vmf, far):6.3f}  {rel(vm, vmf, body):6.3f}')

if __name__ == '__main__':
    main(sys.argv[1], sys.argv[2:])
