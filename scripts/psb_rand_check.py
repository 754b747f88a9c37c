#!/usr/bin/env python3
"""Label transfer through `shapestruct fuzzy-map` on PSB, scored by the area-weighted Rand index: a second route to
the runner's psb_labels.csv (or psb_free_labels.csv).

usage: psb_rand_check.py SHAPESTRUCT PSB_DIR FUZZY_OUT TARGET:SOURCE [...] [--refined [--no-axis-scales]]

PSB_DIR is the benchmark's `psb/data` (off/N.off, seg/Benchmark/N/N_k.seg), FUZZY_OUT what `shapestruct fuzzy`
made of a folder of some of those meshes. For each TARGET:SOURCE the source's first human segmentation (N_0.seg)
is carried to the target through the tool's dense vertex map (as scripts/coseg_label_check.py carries it) and
scored against each of the target's human segmentations: the weighted fraction of unordered face pairs on which
the two agree (both in one segment, or both split), each pair weighted by the product of the two faces' areas,
averaged over the humans. The runner labels each face through its centroid's nearest sample instead, so the two
agree to the part borders, not digit for digit.
"""
import collections
import glob
import itertools
import os
import random

from label_transfer import check_arguments, fuzzy_vertex_map, read_seg, transferred_face_labels
from off_mesh import face_area, read_off


def rand_index(a, b, w):
    """Sum over unordered pairs i < j of w_i w_j [a agrees with b on (i, j)], over the sum of w_i w_j. Pairs in one
    segment of a labeling are counted per segment: sum_{i<j in g} w_i w_j = ((sum_g w)^2 - sum_g w^2) / 2."""
    def same_pairs(keys):
        total, squares = collections.defaultdict(float), collections.defaultdict(float)
        for k, wi in zip(keys, w):
            total[k] += wi
            squares[k] += wi * wi
        return sum((total[k] ** 2 - squares[k]) / 2 for k in total)
    all_pairs = same_pairs([0] * len(w))
    same_a, same_b, same_both = same_pairs(a), same_pairs(b), same_pairs(list(zip(a, b)))
    return (same_both + (all_pairs - same_a - same_b + same_both)) / all_pairs


def brute_force_rand_index(a, b, w):
    num = den = 0.0
    for i, j in itertools.combinations(range(len(w)), 2):
        den += w[i] * w[j]
        num += w[i] * w[j] * ((a[i] == a[j]) == (b[i] == b[j]))
    return num / den


def main():
    a = check_arguments("the PSB data folder (its off/ and seg/Benchmark/)")
    rng = random.Random(1)  # the pair-count identity checked against the definition on a small random case
    x, y, w = ([rng.randrange(3) for _ in range(40)], [rng.randrange(4) for _ in range(40)], [rng.random() for _ in range(40)])
    assert abs(rand_index(x, y, w) - brute_force_rand_index(x, y, w)) < 1e-12
    all_scores = []
    for t, s in a.pairs:
        image = fuzzy_vertex_map(a.tool, a.fuzzy_out, t, s, a.refined, not a.no_axis_scales)
        VT, FT = read_off(os.path.join(a.data, "off", t + ".off"))
        VS, FS = read_off(os.path.join(a.data, "off", s + ".off"))
        LS = read_seg(os.path.join(a.data, "seg", "Benchmark", s, s + "_0.seg"))
        labels = transferred_face_labels(VS, FS, LS, FT, image)
        area = [face_area(VT, f) for f in FT]
        humans = sorted(glob.glob(os.path.join(a.data, "seg", "Benchmark", t, t + "_*.seg")))
        scores = [rand_index(labels, read_seg(h), area) for h in humans]
        print(f"target {t} from {s}: {sum(scores) / len(scores):.4f} (mean over {len(scores)} human segmentations)")
        all_scores.append(sum(scores) / len(scores))
    print(f"mean over {len(all_scores)} pairs: {sum(all_scores) / len(all_scores):.4f}")


if __name__ == "__main__":
    main()
