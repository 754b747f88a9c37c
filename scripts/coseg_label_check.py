#!/usr/bin/env python3
"""Label transfer through `shapestruct fuzzy-map` on COSEG chairs: a second route to the runner's coseg_labels.csv.

usage: coseg_label_check.py SHAPESTRUCT CHAIRS_DIR FUZZY_OUT TARGET:SOURCE [...] [--refined]

CHAIRS_DIR is coseg_subset/res/chairs (shapes/N.off, gt/N.seg), FUZZY_OUT what `shapestruct fuzzy` made of a folder
of those shapes. For each TARGET:SOURCE the tool writes the dense vertex map target -> source; every source vertex
takes the label with the most incident face area there, every target face the majority over its three vertices'
images, and the score is the target's area labelled as its ground truth says. The runner labels each face through
its centroid's nearest sample instead, so the two agree to the part borders, not digit for digit.
"""
import argparse
import collections
import os
import subprocess
import tempfile

from off_mesh import face_area, read_off


def read_seg(path):
    return [int(line) for line in open(path) if line.strip()]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("tool")
    ap.add_argument("chairs")
    ap.add_argument("fuzzy_out")
    ap.add_argument("pairs", nargs="+", help="TARGET:SOURCE shape ids")
    ap.add_argument("--refined", action="store_true", help="pass --refined to fuzzy-map")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        for pair in a.pairs:
            t, s = pair.split(":")
            out = os.path.join(tmp, "t_s.map")
            subprocess.run([a.tool, "fuzzy-map", a.fuzzy_out, t, s, "-o", out] + (["--refined"] if a.refined else []),
                           check=True, capture_output=True)
            image = [int(line) for line in open(out)]
            VT, FT = read_off(os.path.join(a.chairs, "shapes", t + ".off"))
            VS, FS = read_off(os.path.join(a.chairs, "shapes", s + ".off"))
            LT = read_seg(os.path.join(a.chairs, "gt", t + ".seg"))
            LS = read_seg(os.path.join(a.chairs, "gt", s + ".seg"))
            at_vertex = collections.defaultdict(collections.Counter)
            for fi, f in enumerate(FS):
                area = face_area(VS, f)
                for v in f:
                    at_vertex[v][LS[fi]] += area
            label = {v: c.most_common(1)[0][0] for v, c in at_vertex.items()}
            right = total = 0.0
            for fi, f in enumerate(FT):
                votes = collections.Counter(label.get(image[v], -1) for v in f)
                area = face_area(VT, f)
                total += area
                right += area * (votes.most_common(1)[0][0] == LT[fi])
            print(f"target {t} from {s}: {right / total:.4f}")


if __name__ == "__main__":
    main()
