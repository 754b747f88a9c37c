#!/usr/bin/env python3
"""Label transfer through `shapestruct fuzzy-map` on COSEG chairs: a second route to the runner's coseg_labels.csv.

usage: coseg_label_check.py SHAPESTRUCT CHAIRS_DIR FUZZY_OUT TARGET:SOURCE [...] [--refined [--no-axis-scales]]

CHAIRS_DIR is coseg_subset/res/chairs (shapes/N.off, gt/N.seg), FUZZY_OUT what `shapestruct fuzzy` made of a folder
of those shapes. For each TARGET:SOURCE the tool writes the dense vertex map target -> source; every source vertex
takes the label with the most incident face area there, every target face the majority over its three vertices'
images, and the score is the target's area labelled as its ground truth says. The runner labels each face through
its centroid's nearest sample instead, so the two agree to the part borders, not digit for digit.
"""
import os

from label_transfer import check_arguments, fuzzy_vertex_map, read_seg, transferred_face_labels
from off_mesh import face_area, read_off


def main():
    a = check_arguments("the COSEG chairs folder (its shapes/ and gt/)")
    all_scores = []
    for t, s in a.pairs:
        image = fuzzy_vertex_map(a.tool, a.fuzzy_out, t, s, a.refined, not a.no_axis_scales)
        VT, FT = read_off(os.path.join(a.data, "shapes", t + ".off"))
        VS, FS = read_off(os.path.join(a.data, "shapes", s + ".off"))
        LT = read_seg(os.path.join(a.data, "gt", t + ".seg"))
        LS = read_seg(os.path.join(a.data, "gt", s + ".seg"))
        labels = transferred_face_labels(VS, FS, LS, FT, image)
        right = total = 0.0
        for fi, f in enumerate(FT):
            area = face_area(VT, f)
            total += area
            right += area * (labels[fi] == LT[fi])
        print(f"target {t} from {s}: {right / total:.4f}")
        all_scores.append(right / total)
    print(f"mean over {len(all_scores)} pairs: {sum(all_scores) / len(all_scores):.4f}")


if __name__ == "__main__":
    main()
