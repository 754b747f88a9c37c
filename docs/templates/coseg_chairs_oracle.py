#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Consistency check and oracle ceiling of the COSEG chair subset (docs/part_templates.md).

  python3 docs/templates/coseg_chairs_oracle.py $SHAPESTRUCT_DATA/coseg_subset/res/chairs

For every shape it prints the area fraction and the area-weighted mean face-centroid position (per axis, as a
fraction of the shape's bounding box; +Y is up) of each ground-truth label. The semantic part of a label is read
from its height: on 3-label shapes the highest label is the back, the middle one the seat, the lowest the legs;
on 2-label shapes (stools: no back) the upper one is the seat, the lower one the legs. It then scores the
"oracle" labeling that gives every face its semantic part (back / seat / legs) under the protocol of
run_template_coseg: ONE one-to-one mapping of predicted to ground-truth labels for the whole class, accuracy by
area, every shape weighted equally. That is the best score any semantically perfect, class-consistent labeling
can reach on this subset. Pure Python (no numpy); reads the data in place, copies nothing.
"""
import itertools
import os
import sys

# The OFF reader the check scripts share (scripts/off_mesh.py).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'scripts'))
from off_mesh import read_off, triangle_area  # noqa: E402


def main(root):
    shapes = sorted((f[:-4] for f in os.listdir(os.path.join(root, 'shapes')) if f.endswith('.off')),
                    key=lambda s: (len(s), s))
    table = {}
    for st in shapes:
        V, F = read_off(os.path.join(root, 'shapes', st + '.off'))
        gt = [int(x) for x in open(os.path.join(root, 'gt', st + '.seg')).read().split()]
        lo = [min(v[k] for v in V) for k in range(3)]
        hi = [max(v[k] for v in V) for k in range(3)]
        acc = {}
        for f, g in zip(F, gt):
            a = triangle_area(V[f[0]], V[f[1]], V[f[2]])
            s = acc.setdefault(g, [0.0, [0.0, 0.0, 0.0]])
            s[0] += a
            for k in range(3):
                s[1][k] += a * sum(V[i][k] for i in f) / len(f)
        total = sum(s[0] for s in acc.values())
        rows = []
        for g, (a, c) in sorted(acc.items()):
            rows.append((g, a / total, [(c[k] / a - lo[k]) / (hi[k] - lo[k]) for k in range(3)]))
        by_height = sorted(rows, key=lambda r: r[2][1])
        names = ['legs', 'seat', 'back'] if len(rows) == 3 else ['legs', 'seat']
        sem = {r[0]: n for r, n in zip(by_height, names)}
        table[st] = (rows, sem)
        print(f'{st:>4}: ' + '  '.join(f'label {g} = {sem[g]:4s} area {a:.3f} mean y {c[1]:.2f}' for g, a, c in rows))
    best = None
    for perm in itertools.permutations(sorted({g for rows, _ in table.values() for g, _, _ in rows})[:3]):
        m = dict(zip(['back', 'seat', 'legs'], perm))
        per = {st: sum(a for g, a, _ in rows if m[sem[g]] == g) for st, (rows, sem) in table.items()}
        score = sum(per.values()) / len(per)
        if best is None or score > best[0]:
            best = (score, m, per)
    score, m, per = best
    print(f'best single mapping: {m}')
    print(f'oracle ceiling (area, one mapping for the class, shapes weighted equally): {100 * score:.2f} %')
    print('shapes below 100 % under that mapping: ' +
          ', '.join(f'{st} {100 * v:.1f} %' for st, v in per.items() if v < 0.999))


if __name__ == '__main__':
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    main(sys.argv[1])
