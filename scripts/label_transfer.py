"""Part labels carried through a dense vertex map, for the check scripts beside this file (they import it)."""
import argparse
import collections
import os
import subprocess
import tempfile

from off_mesh import face_area


def check_arguments(data_help):
    """The check scripts' common command line: the tool, a data folder, a `fuzzy` output folder, TARGET:SOURCE
    pairs, --refined and --no-axis-scales; returns the parsed arguments, with `pairs` as (target, source) tuples."""
    ap = argparse.ArgumentParser()
    ap.add_argument("tool", help="the shapestruct executable")
    ap.add_argument("data", help=data_help)
    ap.add_argument("fuzzy_out", help="the output folder of `shapestruct fuzzy` on those shapes")
    ap.add_argument("pairs", nargs="+", help="TARGET:SOURCE shape ids")
    ap.add_argument("--refined", action="store_true", help="pass --refined to fuzzy-map")
    ap.add_argument("--no-axis-scales", action="store_true", help="with --refined: pass --no-axis-scales too")
    a = ap.parse_args()
    a.pairs = [tuple(pair.split(":", 1)) for pair in a.pairs]
    return a


def read_seg(path):
    """One integer label per face, per line."""
    return [int(line) for line in open(path) if line.strip()]


def fuzzy_vertex_map(tool, fuzzy_out, a, b, refined, axis_scales=True):
    """The image on shape b of every vertex of shape a, from `shapestruct fuzzy-map` on a `fuzzy` output folder
    (with `refined`, by one scale for all axes unless `axis_scales`)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "a_b.map")
        command = [tool, "fuzzy-map", fuzzy_out, a, b, "-o", out]
        if refined:
            command += ["--refined"] + ([] if axis_scales else ["--no-axis-scales"])
        subprocess.run(command, check=True, capture_output=True)
        return [int(line) for line in open(out)]


def transferred_face_labels(source_verts, source_faces, source_labels, target_faces, image):
    """Every source vertex takes the label with the most incident face area there, every target face the majority
    over its corners' images (image: target vertex -> source vertex); -1 where no label reaches."""
    at_vertex = collections.defaultdict(collections.Counter)
    for fi, f in enumerate(source_faces):
        area = face_area(source_verts, f)
        for v in f:
            at_vertex[v][source_labels[fi]] += area
    label = {v: c.most_common(1)[0][0] for v, c in at_vertex.items()}
    return [collections.Counter(label.get(image[v], -1) for v in f).most_common(1)[0][0] for f in target_faces]
