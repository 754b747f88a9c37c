#!/usr/bin/env python3
"""Scores selection rules for blended maps offline, from the per-group files of `run_bim_benchmark --groups`.

Usage: scripts/bim_selection_study.py SET_groups.csv [SET_groups.csv ...]

Every group of every pair carries its integrated confidence, geodesic distortion, area score and its mean error
against the truth (raw and with the symmetry). For each rule this prints, per file, the mean over pairs of the
selected group's mean error and the number of pairs whose selected map is flipped (error with the symmetry below
0.8 x the raw one). The maps are the unrefined blended maps; docs/blended_maps.md has the table this prints.
"""
import collections
import csv
import sys


def load(path):
    pairs = collections.OrderedDict()
    for row in csv.DictReader(open(path)):
        pairs.setdefault((row["source"], row["target"]), []).append(row)
    return pairs


def value(group, key):
    return float(group[key])


def confidence(g):
    return value(g, "confidence_integral")


def distortion(g):
    return value(g, "geodesic_distortion")


def area(g):
    return value(g, "score")


def by_confidence_within(ratio):
    """Only the maps within `ratio` x the lowest distortion, then the most confident (ties: area)."""
    def rule(groups):
        lowest = min(distortion(g) for g in groups)
        kept = [g for g in groups if distortion(g) <= ratio * lowest]
        return max(kept, key=lambda g: (confidence(g), area(g)))
    return rule


def linear(weight):
    return lambda groups: max(groups, key=lambda g: (confidence(g) - weight * distortion(g), area(g)))


def rank_sum(measures, tolerance=1.0):
    """Lowest sum of ranks (0 = best) by each measure, as blended_matcher ranks: a stable sort, ties in order;
    ties of the sum go to the higher area score. With tolerance t > 1, a group ranks behind another by distortion
    only when its distortion exceeds t times the other's."""
    def rule(groups):
        n = len(groups)
        total = [0] * n
        for measure in measures:
            if measure == "distortion" and tolerance > 1:
                for i in range(n):
                    total[i] += sum(tolerance * distortion(groups[h]) < distortion(groups[i]) for h in range(n))
                continue
            key = {"confidence": confidence, "area": area, "distortion": lambda g: -distortion(g)}[measure]
            order = sorted(range(n), key=lambda i: -key(groups[i]))
            for rank, i in enumerate(order):
                total[i] += rank
        best = 0
        for i in range(1, n):
            if total[i] < total[best] or (total[i] == total[best] and area(groups[i]) > area(groups[best])):
                best = i
        return groups[best]
    return rule


def eigen_weight(g):
    return value(g, "eigen_weight")


def distortion_gated(threshold, inner):
    """blended_selection::distortion_adaptive: confidence alone unless the most confident map's distortion
    exceeds `threshold`, then `inner`."""
    most_confident = by_confidence_within(float("inf"))

    def rule(groups):
        chosen = most_confident(groups)
        return inner(groups) if distortion(chosen) > threshold else chosen
    return rule


RULES = [
    ("integrated confidence (the chapter's)", by_confidence_within(float("inf"))),
    ("within 1.05 x the lowest distortion, then confidence", by_confidence_within(1.05)),
    ("within 1.3 x the lowest distortion, then confidence", by_confidence_within(1.3)),
    ("confidence - 3 x distortion", linear(3.0)),
    ("rank by confidence + rank by distortion", rank_sum(["confidence", "distortion"])),
    ("the same, distortions within 10 % tied", rank_sum(["confidence", "distortion"], tolerance=1.1)),
    ("rank by confidence + rank by area", rank_sum(["area", "confidence"])),
] + [
    (f"confidence, the rank sum above {t} distortion", distortion_gated(t, rank_sum(["confidence", "distortion"])))
    for t in (0.045, 0.05, 0.055, 0.06)
] + [
    ("largest eigen-weight (ties: area)", lambda groups: max(groups, key=lambda g: (eigen_weight(g), area(g)))),
    ("best group (oracle)", lambda groups: min(groups, key=lambda g: value(g, "mean"))),
]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    sets = [(path, load(path)) for path in sys.argv[1:]]
    print("rule".ljust(54) + "".join(f"{p.split('/')[-1][:-4] + f' ({len(s)})':>26}" for p, s in sets))
    for name, rule in RULES:
        cells = []
        for _, pairs in sets:
            errors, flipped = [], 0
            for groups in pairs.values():
                g = rule(groups)
                errors.append(value(g, "mean"))
                flipped += value(g, "mean_sym") < 0.8 * value(g, "mean")
            cells.append(f"{sum(errors) / len(errors):.4f} ({flipped} flipped)")
        print(name.ljust(54) + "".join(f"{c:>26}" for c in cells))


if __name__ == "__main__":
    main()
