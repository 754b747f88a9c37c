#!/usr/bin/env python3
"""Landmark error of `shapestruct fuzzy-map` on a generated collection: a second route to the runner's figures.

usage: generated_landmark_check.py SHAPESTRUCT GENERATED_DIR FUZZY_OUT [--pairs N] [--seed S]
       [--refined [--no-axis-scales]]

GENERATED_DIR is what `shapestruct generate` wrote (OFF meshes and .pts landmarks), FUZZY_OUT what `shapestruct
fuzzy` made of it. For N random ordered pairs (A, B) the tool writes the dense vertex map A -> B; each landmark of
A goes through its nearest vertex of A and that vertex's image to a vertex of B, and its error is the distance to
B's landmark of the same name over B's bounding-box diagonal. The runner maps sample to sample, this vertex to
vertex, so the two agree to about the sample spacing, not digit for digit.
"""
import argparse
import json
import math
import os
import random

from label_transfer import fuzzy_vertex_map
from off_mesh import read_off


def read_landmarks(path):
    out = {}
    with open(path) as f:
        for line in f:
            parts = line.split()
            if len(parts) == 4:
                out[parts[0]] = tuple(float(v) for v in parts[1:])
    return out


def nearest(vertices, x):
    return min(range(len(vertices)), key=lambda v: sum((vertices[v][d] - x[d]) ** 2 for d in range(3)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("tool")
    ap.add_argument("generated")
    ap.add_argument("fuzzy_out")
    ap.add_argument("--pairs", type=int, default=40)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--refined", action="store_true", help="pass --refined to fuzzy-map")
    ap.add_argument("--no-axis-scales", action="store_true", help="with --refined: pass --no-axis-scales too")
    a = ap.parse_args()
    shapes = json.load(open(os.path.join(a.generated, "collection.json")))["shapes"]
    names = [os.path.splitext(s["mesh"])[0] for s in shapes]
    rng = random.Random(a.seed)
    errors = []
    for _ in range(a.pairs):
        i, j = rng.sample(range(len(names)), 2)
        image = fuzzy_vertex_map(a.tool, a.fuzzy_out, names[i], names[j], a.refined, not a.no_axis_scales)
        va = read_off(os.path.join(a.generated, shapes[i]["mesh"]))[0]
        vb = read_off(os.path.join(a.generated, shapes[j]["mesh"]))[0]
        la = read_landmarks(os.path.join(a.generated, shapes[i]["pts"]))
        lb = read_landmarks(os.path.join(a.generated, shapes[j]["pts"]))
        diag = math.dist([min(v[d] for v in vb) for d in range(3)], [max(v[d] for v in vb) for d in range(3)])
        for name, x in la.items():
            if name in lb:
                errors.append(math.dist(vb[image[nearest(va, x)]], lb[name]) / diag)
    n = len(errors)
    within = lambda t: sum(e <= t for e in errors) / n
    print(f"{a.pairs} pairs, {n} landmarks: within 0.05 {within(0.05):.3f}, 0.10 {within(0.10):.3f}, "
          f"0.25 {within(0.25):.3f}, mean {sum(errors) / n:.4f}")


if __name__ == "__main__":
    main()
