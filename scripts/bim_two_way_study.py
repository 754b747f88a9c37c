#!/usr/bin/env python3
"""Scores the two-way confidence rule of blended_matcher_options::both_directions offline.

Usage: scripts/bim_two_way_study.py SET_groups.csv [SET_groups.csv ...]

Reads the per-group files of `run_bim_benchmark --both-directions --groups`: every forward blended map of every
pair with its integrated confidence, its error against the truth (raw and with the symmetry, unrefined), whether it
was the forward selection, its mean cycle error with every reverse map (`cycle_errors`) and the reverse maps'
confidences (`reverse_confidences`). For the forward selection and for the rule at several agreements and margins
it prints, per file, the pooled fraction of feature points within 0.25 and the mean error, raw and with flips, the
flipped pairs and how many pairs the rule changed (the pairs too, with -v). The library's default is agreement 0.07,
margin 0.02. The maps are the unrefined blended maps, so the figures are not the refined ones of the pairs file;
docs/blended_maps.md has the table this prints. The files were written with `--both-directions` on the runner of
commit 513b23b and the columns of 68d26aa; the cycle errors do not depend on the rule, so any rule scores exactly.
"""
import sys

from bim_selection_study import load  # the per-group file, grouped by pair


def values(row, key):
    return [float(x) for x in row[key].split(";")] if row[key] else []


def two_way(group, reverse_confidences, agreement):
    """Confidence plus that of the most confident reverse map within `agreement` of its inverse; None without."""
    near = [h for h, e in enumerate(values(group, "cycle_errors")) if e <= agreement]
    if not near:
        return None
    return float(group["confidence_integral"]) + max(reverse_confidences[h] for h in near)


def choose(groups, agreement, margin):
    """The library's rule (blended_matcher::reconciled_selection)."""
    selected = next(g for g in groups if g["forward_selected"] == "1")
    if margin is None:
        return selected
    reverse_confidences = values(groups[0], "reverse_confidences")
    kept = two_way(selected, reverse_confidences, agreement)
    if kept is None:
        return selected
    best, best_value = selected, kept
    for g in groups:
        v = two_way(g, reverse_confidences, agreement)
        if v is not None and v > best_value:
            best, best_value = g, v
    return best if best_value > kept + margin else selected


def score(path, agreement, margin, verbose):
    raw_within = flip_within = raw_mean = flip_mean = points = flipped = 0
    changed = []
    for key, groups in load(path).items():
        g = choose(groups, agreement, margin)
        n = int(g["points"])
        raw, sym = float(g["mean"]), float(g["mean_sym"])
        raw_within += float(g["w025"]) * n
        flip_within += (float(g["w025_sym"]) if sym < raw else float(g["w025"])) * n
        raw_mean += raw * n
        flip_mean += min(raw, sym) * n
        points += n
        flipped += sym < raw
        selected = next(x for x in groups if x["forward_selected"] == "1")
        if g is not selected:
            changed.append(f"    {key[0]} -> {key[1]}: map {selected['group']} -> {g['group']}, "
                           f"mean {float(selected['mean']):.3f} -> {raw:.3f}")
    rule = "forward selection" if margin is None else f"two-way, agreement {agreement}, margin {margin}"
    print(f"{path.split('/')[-1]:28s} {rule:38s} within 0.25 {raw_within / points:.4f} mean {raw_mean / points:.4f}"
          f" | with flips {flip_within / points:.4f} {flip_mean / points:.4f} | flipped {flipped}"
          f" | changed {len(changed)}")
    if verbose:
        print("\n".join(changed))


def main():
    verbose = "-v" in sys.argv
    for path in [a for a in sys.argv[1:] if a != "-v"]:
        score(path, 0.07, None, False)
        for agreement in (0.05, 0.06, 0.07, 0.08, 0.1, 0.2):
            for margin in (0.0, 0.005, 0.01, 0.02, 0.03):
                score(path, agreement, margin, verbose)


if __name__ == "__main__":
    main()
