"""Issue 40, a load near a side: shear candidates scored offline on the comparisons plates.sh wrote.

Each candidate is a shear field tau (the packets' and the row balance's, no closed form) and a
sigma_y; sigma_x is the tie of that tau (fields.tie, the C++ scan: reproduced to 1e-7 of the
fields) plus the half-plane layer's sigma_x of the run whose force it uses (the run with the
closed forms less the one without: the tie is linear), tau_xy adds the layer's shear, von Mises
from the three. Far-field rel. L2 against FEM as summary.json's (reproduced to 1e-4).

  side   the default: the side rule's force and shear
  image  near_side = image
  B      image force; tau the side run's between the nearer side and the load, the image's beyond
  C      side force; tau = its force's own vertical equilibrium, -int_0^x d sigma_y / dy dx
  E      image force; tau its force's equilibrium
  F      image force; tau the side force's equilibrium between the nearer side and the load, the
         image force's beyond (a splice at the load column)
  G      force b(d) side + (1 - b(d)) image per row (both carry the load, both balanced: so does the
         blend), b = exp(-2 d / W) (d the row's depth below the loaded face, W the body's width);
         tau its force's equilibrium. The layer's sigma_x and shear are the image run's (its base
         force differs from the blend's by b(H) of the side's: e^-2 on a square plate)
  H      G's force with the same blend of the two runs' own shears (the packets' and the row
         balance's): what a march depositing b(d) of each direction on its side path and 1 - b(d)
         on its image path gives (every step is linear in the deposits)
  G*     G with b = exp(-d / W), exp(-4.21 d / W) (Papkovich-Fadle's slowest mode of a strip),
         exp(-d / (4 a)) (a: the load's distance to the nearer side), exp(-d / (W - a))
Candidate D (the near half's packets deposit their shear along the side rule's paths, their force
as the image's) needs the march: candidate_d.patch (NEAR21_D=1 with near_side = image).

Usage: /usr/bin/python3 candidates.py OUT   (OUT: plates.sh's folder)
"""
import json, os, sys
import numpy as np
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fields import read, rel_l2, d_dy, tie

WINDOW_LENGTH = 0.005  # m, the directional default (window_length)
PLATES = 'x10 x20 x30 x40 x50 x100 w300x30 tall wide mm2x100 mm2x50 dplate patch60 nu01 nu045'.split()


def von_mises(sx, sy, t):
    return np.sqrt(sx * sx - sx * sy + sy * sy + 3 * t * t)


def load(runs, n):
    return {'s': read(f'{runs}/side/{n}'), 'i': read(f'{runs}/image/i_{n}'),
            'Ls': read(f'{runs}/cf/L_{n}'), 'Li': read(f'{runs}/cf/Li_{n}')}


BLENDS = {'G': lambda d, a, W: np.exp(-2 * d / W), 'G d/W': lambda d, a, W: np.exp(-d / W),
          'G 4.21d/W': lambda d, a, W: np.exp(-4.21 * d / W), 'G d/4a': lambda d, a, W: np.exp(-d / (4 * a)),
          'G d/(W-a)': lambda d, a, W: np.exp(-d / (W - a))}


def blended(d, rule, xl):
    """Candidate G's force (with and without the closed forms) and its equilibrium shear."""
    h = d['s']['h']; x = d['s']['x']
    depth = d['s']['y'].max() + h / 2 - d['s']['y']
    W = x[-1].max() + x[-1].min()
    b = rule(depth, min(xl, W - xl), W)
    g = dict(d); g['i'] = dict(d['i'])
    g['i']['agent_sigma_y'] = b * d['s']['agent_sigma_y'] + (1 - b) * d['i']['agent_sigma_y']
    return g, eq_shear(b * d['Ls']['agent_sigma_y'] + (1 - b) * d['Li']['agent_sigma_y'], h)


def score(d, tau_pb, force, label):
    """sigma_x, sigma_y, tau_xy, von Mises far rel. L2 of a candidate (force: 's' or 'i')."""
    f = d['s']; h = f['h']; far = f['far']
    full, cf = d[force], d['L' + force]
    layer_sx = full['agent_sigma_x'] - cf['agent_sigma_x']
    layer_tau = full['agent_tau_xy'] - cf['agent_tau_xy']
    sy = full['agent_sigma_y']
    sx = tie(tau_pb, h, WINDOW_LENGTH / h) + layer_sx
    tau = tau_pb + layer_tau
    e = [rel_l2(sx, f['fem_sigma_x'], far), rel_l2(sy, f['fem_sigma_y'], far), rel_l2(tau, f['fem_tau_xy'], far),
         rel_l2(von_mises(sx, sy, tau), f['fem_von_mises'], far)]
    print(' %-10s sx %.3f sy %.3f tau %.3f vm %.3f' % (label, *e))
    return e


def eq_shear(sy, h):
    """tau of sigma_y's vertical equilibrium, free at x = 0: -int_0^x d sigma_y / dy dx (rest out linearly)."""
    ds = d_dy(sy, h, WINDOW_LENGTH / h)
    faces = np.zeros((sy.shape[0], sy.shape[1] + 1))
    faces[:, 1:] = -h * np.cumsum(ds, axis=1)
    faces -= faces[:, -1:] * np.arange(sy.shape[1] + 1)[None, :] / sy.shape[1]
    return 0.5 * (faces[:, :-1] + faces[:, 1:])


def near_mask(d):
    """1 between the nearer side and the load (the top row's largest FEM |sigma_y|); 0 if centred."""
    s = d['s']; x = s['x']
    xl = x[-1][np.argmax(np.abs(s['fem_sigma_y'][-1]))]
    W = x[-1].max() + x[-1].min()
    if abs(xl - W / 2) < 0.6 * s['h']: return np.zeros_like(x), xl
    return ((x < xl) if xl < W / 2 else (x > xl)).astype(float), xl


def main(out):
    runs = os.path.join(out, 'runs')
    rows = {}
    for n in PLATES:
        d = load(runs, n); h = d['s']['h']; w, xl = near_mask(d)
        ts, ti = d['Ls']['agent_tau_xy'], d['Li']['agent_tau_xy']
        es, ei = eq_shear(d['Ls']['agent_sigma_y'], h), eq_shear(d['Li']['agent_sigma_y'], h)
        print(n, 'load at %.1f mm' % (xl * 1000))
        rows[n] = {'side': score(d, ts, 's', 'side'), 'image': score(d, ti, 'i', 'image'),
                   'B': score(d, w * ts + (1 - w) * ti, 'i', 'B'), 'C': score(d, es, 's', 'C'),
                   'E': score(d, ei, 'i', 'E'), 'F': score(d, w * es + (1 - w) * ei, 'i', 'F')}
        for name, rule in BLENDS.items():
            g, tau = blended(d, rule, xl)
            rows[n][name] = score(g, tau, 'i', name)
        g, _ = blended(d, BLENDS['G'], xl)
        x = d['s']['x']; depth = d['s']['y'].max() + h / 2 - d['s']['y']; W = x[-1].max() + x[-1].min()
        b = BLENDS['G'](depth, min(xl, W - xl), W)
        rows[n]['H'] = score(g, b * ts + (1 - b) * ti, 'i', 'H')
    json.dump(rows, open(os.path.join(out, 'candidates.json'), 'w'), indent=1)


if __name__ == '__main__':
    main(sys.argv[1])
