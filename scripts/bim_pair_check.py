#!/usr/bin/env python3
"""Scores one dense vertex map at the benchmark's feature points, independently of the C++ runners.

Usage: scripts/bim_pair_check.py TARGET.off MAP SOURCE.vts TARGET.vts
       scripts/bim_pair_check.py TARGET.off MAP SOURCE.pid TARGET.pid SOURCE.info TARGET.info TARGET.sym.info

MAP is what `shapestruct match SRC TGT -o MAP` writes (one 0-based target vertex per source vertex). The
feature points' first column is the 0-based vertex. With two point files (SHREC'07's .vts) the k-th point of the
source corresponds to the k-th of the target. With the names too (the cross-set lists humans and animals: SCAPE's
and TOSCA's .pid with their .info, "k: name" per line), a source point corresponds to the target point of the same
name (trimmed, lower case), and "with flips" scores each image also against the target point's partner under the
target class's symmetry (.sym.info: one orbit per line), and the pair keeps whichever of the two truths gives
the lower mean error, as the runner does. The error of a point is the geodesic distance on the target between
its image and its true image, divided by sqrt(area of the target) (the benchmark's scale); geodesics are shortest
paths along the target's edges (Dijkstra, pure Python). Prints the mean error and the fraction within 0.25, as `run_bim_benchmark` does, so that
one of its figures can be checked by a second route.
"""
import heapq
import math
import sys

from off_mesh import face_area, read_off


def read_vertex_column(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.strip():
                out.append(int(float(line.split()[0])))
    return out


def read_names(path):
    """index -> name of a .info file ("k: name" per line; blank lines skipped)."""
    names = {}
    with open(path) as f:
        for line in f:
            if line.strip():
                k, name = line.split(":", 1)
                names[int(k)] = name.strip().lower()
    return names


def read_symmetry(path, n):
    """The permutation of a .sym.info file: each line an orbit a -> b -> ... -> a."""
    perm = list(range(n))
    with open(path) as f:
        for line in f:
            orbit = [int(x) for x in line.split()]
            for k in range(len(orbit) if len(orbit) > 1 else 0):
                perm[orbit[k]] = orbit[(k + 1) % len(orbit)]
    return perm


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def norm(a):
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def main():
    if len(sys.argv) not in (5, 8):
        sys.exit(__doc__)
    verts, faces = read_off(sys.argv[1])
    image = read_vertex_column(sys.argv[2])
    source_points = read_vertex_column(sys.argv[3])
    target_points = read_vertex_column(sys.argv[4])
    symmetric_points = None
    if len(sys.argv) == 8:
        source_names, target_names = read_names(sys.argv[5]), read_names(sys.argv[6])
        symmetry = read_symmetry(sys.argv[7], len(target_points))
        index_of = {name: j for j, name in target_names.items() if name and j < len(target_points)}
        matched = [(k, index_of[name]) for k, name in sorted(source_names.items())
                   if k < len(source_points) and name in index_of]
        symmetric_points = [target_points[symmetry[j]] for _, j in matched]
        source_points = [source_points[k] for k, _ in matched]
        target_points = [target_points[j] for _, j in matched]
    elif len(source_points) != len(target_points):
        sys.exit("the two .vts files list different numbers of points")
    area = sum(face_area(verts, f) for f in faces)
    neighbours = [dict() for _ in verts]
    for f in faces:
        for k in range(len(f)):
            i, j = f[k], f[(k + 1) % len(f)]
            d = norm(sub(verts[i], verts[j]))
            neighbours[i][j] = d
            neighbours[j][i] = d

    def geodesic(t, goal):
        dist = {t: 0.0}
        heap = [(0.0, t)]
        while heap:
            d, v = heapq.heappop(heap)
            if v == goal:
                break
            if d > dist[v]:
                continue
            for w, l in neighbours[v].items():
                if d + l < dist.get(w, math.inf):
                    dist[w] = d + l
                    heapq.heappush(heap, (d + l, w))
        return dist[goal] / math.sqrt(area)

    errors = [geodesic(t, image[s]) for s, t in zip(source_points, target_points)]

    def report(label, values):
        mean = sum(values) / len(values)
        within = sum(e <= 0.25 for e in values) / len(values)
        print(f"{label}{len(values)} points: mean {mean:.4f}, within 0.25 {within:.4f}")

    report("", errors)
    if symmetric_points is not None:
        mirrored = [geodesic(t, image[s]) for s, t in zip(source_points, symmetric_points)]
        report("with flips: ", mirrored if sum(mirrored) < sum(errors) else errors)


if __name__ == "__main__":
    main()
