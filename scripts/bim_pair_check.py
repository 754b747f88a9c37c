#!/usr/bin/env python3
"""Scores one dense vertex map at the benchmark's feature points, independently of the C++ runners.

Usage: scripts/bim_pair_check.py TARGET.off MAP SOURCE.vts TARGET.vts

MAP is what `shapestruct match SRC TGT -o MAP` writes (one 0-based target vertex per source vertex). The
feature points are SHREC'07's .vts files (first column: the 0-based vertex; the k-th point of the source
corresponds to the k-th of the target). The error of a point is the geodesic distance on the target between
its image and its true image, divided by sqrt(area of the target) (the benchmark's scale); geodesics are
shortest paths along the target's edges (Dijkstra, pure Python). Prints the mean error and the fraction within
0.25, as `run_bim_benchmark` does, so that one of its figures can be checked by a second route.
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


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def norm(a):
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    verts, faces = read_off(sys.argv[1])
    image = read_vertex_column(sys.argv[2])
    source_points = read_vertex_column(sys.argv[3])
    target_points = read_vertex_column(sys.argv[4])
    if len(source_points) != len(target_points):
        sys.exit("the two .vts files list different numbers of points")
    area = sum(face_area(verts, f) for f in faces)
    neighbours = [dict() for _ in verts]
    for f in faces:
        for k in range(len(f)):
            i, j = f[k], f[(k + 1) % len(f)]
            d = norm(sub(verts[i], verts[j]))
            neighbours[i][j] = d
            neighbours[j][i] = d
    errors = []
    for s, t in zip(source_points, target_points):
        goal = image[s]
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
        errors.append(dist[goal] / math.sqrt(area))
    mean = sum(errors) / len(errors)
    within = sum(e <= 0.25 for e in errors) / len(errors)
    print(f"{len(errors)} points: mean {mean:.4f}, within 0.25 {within:.4f}")


if __name__ == "__main__":
    main()
