#!/usr/bin/env python3
"""Merge several runs of bench/runners/bim_benchmark.cpp on the same set into one result.

A long set (SHREC'07 has 218 pairs) can be run in pieces, e.g. on two machines or across sessions:

    run_bim_benchmark --set shrec --limit 84 --out part1/
    run_bim_benchmark --set shrec --offset 84 --out part2/
    scripts/merge_bim_runs.py shrec part1 part2 --out merged/

Writes merged/<set>_pairs.csv (rows of all parts, in order), merged/<set>_errors.tsv (the pooled per-sample
errors), merged/<set>_curves.dat (same thresholds as the runner; plot with plot_bim_curves.gnuplot) and prints the
pooled summary the runner prints. Scores are pooled per point, as the benchmark's curves are, so the merged figure
is exactly what one run over all the pairs would give. A pair present in two parts is an error, not silently
counted twice.
"""
import argparse
import csv
import os
import statistics
import sys


def summarize(errors):
    n = len(errors)
    if n == 0:
        return None
    return {
        "w005": sum(e <= 0.05 for e in errors) / n,
        "w010": sum(e <= 0.10 for e in errors) / n,
        "w025": sum(e <= 0.25 for e in errors) / n,
        "mean": sum(errors) / n,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("set", help="scape | tosca | shrec | humans | animals")
    ap.add_argument("parts", nargs="+", help="output folders of the runner")
    ap.add_argument("--out", required=True, help="folder for the merged files (created; must not be a part)")
    args = ap.parse_args()

    out = os.path.abspath(args.out)
    if any(os.path.abspath(p) == out for p in args.parts):
        sys.exit("merge_bim_runs: --out must differ from the parts (their files would be overwritten)")
    header, rows, seen = None, [], {}
    errors = {("ours", "raw"): [], ("ours", "flip"): [], ("stored", "raw"): [], ("stored", "flip"): []}
    for part in args.parts:
        pairs_path = os.path.join(part, args.set + "_pairs.csv")
        errors_path = os.path.join(part, args.set + "_errors.tsv")
        for p in (pairs_path, errors_path):
            if not os.path.isfile(p):
                sys.exit(f"merge_bim_runs: {p}: missing (is {part} an output folder of the '{args.set}' run?)")
        with open(pairs_path, newline="") as f:
            reader = csv.reader(f)
            h = next(reader)
            if header is None:
                header = h
            elif h != header:
                sys.exit(f"merge_bim_runs: {pairs_path}: columns differ from the first part's")
            for line, row in enumerate(reader, start=2):
                key = (row[0], row[1])
                if key in seen:
                    sys.exit(f"merge_bim_runs: {pairs_path}:{line}: pair {key[0]}->{key[1]} already in {seen[key]}")
                seen[key] = f"{pairs_path}:{line}"
                rows.append(row)
        with open(errors_path) as f:
            for line, text in enumerate(f, start=1):
                if text.startswith("#") or not text.strip():
                    continue
                fields = text.split("\t")
                if len(fields) != 3 or (fields[0], fields[1]) not in errors:
                    sys.exit(f"merge_bim_runs: {errors_path}:{line}: expected 'method<TAB>kind<TAB>error'")
                errors[(fields[0], fields[1])].append(float(fields[2]))

    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, args.set + "_pairs.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)
    with open(os.path.join(out, args.set + "_errors.tsv"), "w") as f:
        f.write("# method\tkind\terror\n")
        for (method, kind), values in errors.items():
            for e in values:
                f.write(f"{method}\t{kind}\t{e!r}\n")
    status = header.index("status")
    done = [r for r in rows if r[status] == "ok"]
    curves = {k: sorted(v) for k, v in errors.items()}
    with open(os.path.join(out, args.set + "_curves.dat"), "w") as f:
        f.write(f"# D ours_raw ours_flip stored_raw stored_flip  ({len(done)} pairs)\n")
        for k in range(51):
            d = 0.005 * k
            fr = []
            for key in (("ours", "raw"), ("ours", "flip"), ("stored", "raw"), ("stored", "flip")):
                v = curves[key]
                fr.append(sum(e <= d for e in v) / len(v) if v else 0.0)
            f.write(f"{d:g} " + " ".join(f"{x:g}" for x in fr) + "\n")

    times = [float(r[header.index("time_total")]) for r in done]
    def flips(raw_column, flip_column):
        # The docs' rule: a pair is flipped when its error with flips is below 0.8 x its raw error.
        i, j = header.index(raw_column), header.index(flip_column)
        return sum(1 for r in done if float(r[i]) >= 0 and float(r[j]) >= 0 and float(r[j]) < 0.8 * float(r[i]))

    print(f"{args.set}: {len(done)} pairs ran, {len(rows) - len(done)} failed; flipped pairs (with-flip error below "
          f"0.8 x raw): ours {flips('mean', 'mean_flip')}, stored {flips('stored_mean', 'stored_mean_flip')}")
    for label, m in (("shapestruct", "ours"), ("stored (same pairs)", "stored")):
        raw, flip = summarize(errors[(m, "raw")]), summarize(errors[(m, "flip")])
        if raw is None:
            continue
        print(f"  {label}: <=0.05 {raw['w005']:.3f} <=0.10 {raw['w010']:.3f} <=0.25 {raw['w025']:.3f} "
              f"mean {raw['mean']:.4f} | with flips <=0.25 {flip['w025']:.3f} mean {flip['mean']:.4f}")
    if times:
        print(f"  median time per pair {statistics.median(times):.2f} s (times are only comparable within one run)")


if __name__ == "__main__":
    main()
