#!/usr/bin/env python3
"""What the consistent map would score under other fuzzy_min_gain margins, max_fuzzy_distortion_ratio limits and
fuzzy_min_distance thresholds, from one run of run_fuzzy_benchmark.

Usage: scripts/fuzzy_min_gain_study.py SET_pairs.csv SET_choices.csv [MARGINS] [--ratios R1,R2] [--distances D1,D2]
       [--vts DIR]

Both files come from the same run (the same f). Where the refined fuzzy map was chosen but would not lead the best
blended map by the margin, the consistent map is the blended maps' own choice (the consistent_blended_only rows),
so every margin at or above the run's own is scored exactly; likewise every distortion limit (--ratios) below the
run's own and every distance threshold (--distances) above it, from the choices file's distortion and distance
columns. Pairs are weighted by their number of evaluation
points (the `points` column; for SHREC'07 files written before that column, the smaller of the two shapes' .vts
counts, read from --vts DIR, the benchmark's watertight_shrec07/Corrs).
"""
import argparse
import collections
import csv
import os


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("pairs")
    ap.add_argument("choices")
    ap.add_argument("margins", nargs="?", default="0,0.02,0.05,0.1,0.15,0.2,0.3,0.5")
    ap.add_argument("--ratios", default="", help="max_fuzzy_distortion_ratio limits to score, e.g. 1,1.25,1.5")
    ap.add_argument("--distances", default="", help="fuzzy_min_distance thresholds to score, e.g. 0.02,0.05")
    ap.add_argument("--vts", default=os.path.join(os.environ.get("SHAPESTRUCT_DATA", ""), "watertight_shrec07", "Corrs"))
    args = ap.parse_args()

    def key(row):
        return (row.get("class", ""), row["source"], row["target"])

    methods = collections.defaultdict(dict)
    for row in csv.DictReader(open(args.pairs)):
        methods[key(row)][row["method"]] = row
    choices = {key(row): row for row in csv.DictReader(open(args.choices))}

    def vts_count(shape):
        with open(os.path.join(args.vts, shape + ".vts")) as f:
            return sum(1 for line in f if line.strip())

    def weight(k, row):
        return int(row["points"]) if row.get("points") else min(vts_count(k[1]), vts_count(k[2]))

    def pooled(pick):
        total = within = mean = w005 = w010 = flips = 0.0
        flipped = 0
        for k, rows in methods.items():
            row = rows[pick(k)]
            w = weight(k, row)
            total += w
            within += w * float(row["w025"])
            mean += w * float(row["mean"])
            flipped += int(row["flipped"])
            if row.get("w005"):
                w005 += w * float(row["w005"])
                w010 += w * float(row["w010"])
                flips += w * float(row["w025_flip"])
        text = f"within 0.25 {within / total:.4f}, mean {mean / total:.4f}, flipped pairs {flipped}"
        if w005:
            text += f", within 0.05 {w005 / total:.4f}, within 0.10 {w010 / total:.4f}, with flips {flips / total:.4f}"
        return text

    def report(label, fuzzy_kept):
        """Scores the rule that keeps the run's fuzzy choice of a pair only where fuzzy_kept(choice row) holds."""
        def pick(k):
            c = choices[k]
            if c["chosen"] != "fuzzy" or fuzzy_kept(c):
                return "consistent_blended"
            return "consistent_blended_only"
        chosen = sum(1 for k in methods if choices[k]["chosen"] == "fuzzy" and pick(k) == "consistent_blended")
        print(f"{label}: {pooled(pick)}; fuzzy map chosen on {chosen} pairs")

    def values(text):
        return [float(v) for v in text.split(",") if v]

    print("blended maps only:", pooled(lambda k: "consistent_blended_only"))
    for margin in values(args.margins):
        report(f"fuzzy_min_gain {margin}", lambda c, margin=margin:
               float(c["fuzzy_consistency"]) > (1 + margin) * float(c["best_blended_consistency"]))
    for ratio in values(args.ratios):
        report(f"max_fuzzy_distortion_ratio {ratio}", lambda c, ratio=ratio:
               float(c["most_consistent_distortion"]) < 0
               or float(c["fuzzy_distortion"]) <= ratio * float(c["most_consistent_distortion"]))
    for threshold in values(args.distances):
        report(f"fuzzy_min_distance {threshold}", lambda c, threshold=threshold:
               float(c["fuzzy_distance"]) < 0 or float(c["fuzzy_distance"]) >= threshold)

if __name__ == "__main__":
    main()
