#!/usr/bin/env python3
"""Sweeps the threshold of the distortion-adaptive selection on refined maps, from two measured runs.

Usage: scripts/bim_gate_sweep.py CONFIDENCE_pairs.csv RANK_SUM_pairs.csv [THRESHOLD ...]

Both files are `run_bim_benchmark` per-pair outputs of one list: one run selecting by integrated confidence,
one by the rank sum of confidence and distortion (`--selection confidence|confidence-distortion`). Per pair,
blended_selection::distortion_adaptive makes the first run's choice when that run's selected blended map has
geodesic distortion (column blended_distortion) at most the threshold, else the second's; the rest of the
pipeline (blending, refinement, scoring) is the same, so the pair's row is that run's row. Prints, per
threshold, the pairs switched and the per-pair averages of within 0.25, mean error, the same with flips, and
the flipped pairs. (The runner's summary pools the errors of all pairs; the per-pair averages differ slightly
where pairs have different numbers of feature points.)
"""
import csv
import sys


def load(path):
    return {(r["source"], r["target"]): r for r in csv.DictReader(open(path)) if r["status"] == "ok"}


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    by_confidence, by_rank_sum = load(sys.argv[1]), load(sys.argv[2])
    thresholds = [float(t) for t in sys.argv[3:]] or [0.03, 0.04, 0.045, 0.05, 0.055, 0.06, 0.07]
    pairs = [k for k in by_confidence if k in by_rank_sum]
    print(f"{len(pairs)} pairs in both files")
    columns = ["w025", "mean", "w025_flip", "mean_flip"]

    def line(label, rows, switched):
        averages = [sum(float(r[c]) for r in rows) / len(rows) for c in columns]
        flipped = sum(int(r["flipped"]) for r in rows)
        print(f"{label:<22} switched {switched:3d}   within 0.25 {averages[0]:.3f}  mean {averages[1]:.4f}   "
              f"with flips {averages[2]:.3f}  {averages[3]:.4f}   flipped {flipped}")

    line("confidence", [by_confidence[k] for k in pairs], 0)
    for t in thresholds:
        rows, switched = [], 0
        for k in pairs:
            use_rank_sum = float(by_confidence[k]["blended_distortion"]) > t
            switched += use_rank_sum
            rows.append(by_rank_sum[k] if use_rank_sum else by_confidence[k])
        line(f"adaptive, {t}", rows, switched)
    line("rank sum", [by_rank_sum[k] for k in pairs], len(pairs))
    stored = [by_confidence[k] for k in pairs]
    averages = [sum(float(r["stored_" + c]) for r in stored) / len(stored) for c in columns]
    print(f"{'stored original':<22}                within 0.25 {averages[0]:.3f}  mean {averages[1]:.4f}   "
          f"with flips {averages[2]:.3f}  {averages[3]:.4f}")


if __name__ == "__main__":
    main()
