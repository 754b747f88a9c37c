#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Independent mesh counts to cross-check `shapestruct inspect` (check_mesh) on real data.

Pure python3 (no numpy): parses OFF, PLY (ascii and binary) and OBJ itself, triangulates polygons the way
shapestruct's readers count them (a k-gon with k distinct consecutive corners gives k - 2 triangles; a
3-corner face is kept as it is), and counts with its own algorithms (dicts and breadth-first searches, no
union-find) the same quantities check_mesh reports, using the definitions documented on mesh_report:

  vertices, faces, edges (distinct unordered pairs of topological faces, i.e. faces with 3 distinct in-range
  indices), boundary edges (1 face), non-manifold edges (> 2 faces), inconsistently oriented edges (2 faces
  traversing it the same way), non-manifold vertices (link graph with > 1 connected piece), components
  (vertices linked by faces; an unreferenced vertex is its own component), boundary loops (connected pieces
  of the boundary-edge graph), Euler characteristic V - E + F, genus sum over components of
  (2 - chi_c - b_c) / 2 (-1 when a component is non-manifold or non-orientable), duplicate vertices (exactly
  equal positions), degenerate faces (repeated index, or area <= 1e-14 * bbox diagonal^2), unreferenced
  vertices, repeated-index faces.

Usage:
  independent_mesh_count.py FILE|DIR...                       print the counts as JSON lines
  independent_mesh_count.py --compare BUILD/examples/shapestruct --root $SHAPESTRUCT_DATA DIR...
      runs `shapestruct inspect --json` on the same files and prints a per-data-set agreement table,
      every disagreement, and the notable meshes (boundary, non-manifold, genus > 0, several components).
  --jobs N  parse with N processes (default 1; the machine's cores are shared)
"""

import argparse
import collections
import json
import math
import os
import struct
import subprocess
import sys

MESH_EXTENSIONS = {".off", ".obj", ".ply", ".stl"}
DEGENERATE_AREA_EPSILON = 1e-14  # same documented default as check_mesh_options


class ParseError(Exception):
    pass


# ------------------------------------------------------------------------------------------------ parsers

def _triangulate(corners, out):
    """Appends the triangles of one polygon (see the module docstring for the rule)."""
    if len(corners) == 3:
        out.append((corners[0], corners[1], corners[2]))
        return
    ring = []
    for c in corners:
        if not ring or ring[-1] != c:
            ring.append(c)
    while len(ring) > 1 and ring[0] == ring[-1]:
        ring.pop()
    if len(ring) < 3:
        return
    # Which diagonals are used does not change any count compared here (V, F, E, boundary, components).
    for i in range(1, len(ring) - 1):
        out.append((ring[0], ring[i], ring[i + 1]))


def _strips(indices, out):
    """Triangles of a triangle strip list with -1 restarts: triangle j of a strip s is (s[j], s[j+1], s[j+2]),
    with the first two swapped for odd j to keep one orientation; triangles repeating a vertex (the usual
    strip joints) are skipped, as shapestruct's reader does."""
    strip = []
    for v in list(indices) + [-1]:
        if v >= 0:
            strip.append(v)
            continue
        for j in range(len(strip) - 2):
            t = (strip[j], strip[j + 1], strip[j + 2]) if j % 2 == 0 else (strip[j + 1], strip[j], strip[j + 2])
            if len(set(t)) == 3:
                out.append(t)
        strip = []


def _content_lines(text):
    for raw in text.splitlines():
        line = raw.split("#", 1)[0].strip()
        if line:
            yield line


def parse_off(path):
    with open(path, "r", encoding="latin-1") as fh:
        lines = _content_lines(fh.read())
    first = next(lines).split()
    head = first[0]
    if not head.endswith("OFF"):
        raise ParseError("not an OFF file")
    counts = first[1:]
    while len(counts) < 3:
        counts += next(lines).split()
    nv, nf = int(counts[0]), int(counts[1])
    positions = []
    for _ in range(nv):
        t = next(lines).split()
        positions.append((float(t[0]), float(t[1]), float(t[2])))
    faces = []
    for _ in range(nf):
        t = next(lines).split()
        k = int(t[0])
        _triangulate([int(x) for x in t[1:1 + k]], faces)
    return positions, faces


_PLY_TYPES = {
    "char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h", "ushort": "H",
    "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I", "float": "f", "float32": "f",
    "double": "d", "float64": "d",
}


def parse_ply(path):
    with open(path, "rb") as fh:
        data = fh.read()
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise ParseError("not a PLY file")
    body_start = data.index(b"\n", end) + 1
    header = data[:end].decode("latin-1").splitlines()
    fmt = None
    elements = []  # (name, count, [(prop name, type, list count type or None)])
    for line in header:
        t = line.split()
        if not t:
            continue
        if t[0] == "format":
            fmt = t[1]
        elif t[0] == "element":
            elements.append((t[1], int(t[2]), []))
        elif t[0] == "property":
            if t[1] == "list":
                elements[-1][2].append((t[4], _PLY_TYPES[t[3]], _PLY_TYPES[t[2]]))
            else:
                elements[-1][2].append((t[2], _PLY_TYPES[t[1]], None))
    positions, faces = [], []
    if fmt == "ascii":
        tokens = data[body_start:].split()
        pos = 0
        for name, count, props in elements:
            for _ in range(count):
                rec = {}
                for pname, ptype, ltype in props:
                    if ltype is None:
                        rec[pname] = tokens[pos]
                        pos += 1
                    else:
                        n = int(float(tokens[pos]))
                        rec[pname] = [int(float(x)) for x in tokens[pos + 1:pos + 1 + n]]
                        pos += 1 + n
                if name == "vertex":
                    positions.append((float(rec["x"]), float(rec["y"]), float(rec["z"])))
                elif name == "face":
                    _triangulate(rec.get("vertex_indices", rec.get("vertex_index", [])), faces)
                elif name == "tristrips":
                    _strips(rec.get("vertex_indices", rec.get("vertex_index", [])), faces)
        return positions, faces
    order = "<" if fmt == "binary_little_endian" else ">"
    pos = body_start
    for name, count, props in elements:
        fixed = all(ltype is None for _, _, ltype in props)
        if fixed:
            rec_fmt = order + "".join(ptype for _, ptype, _ in props)
            size = struct.calcsize(rec_fmt)
            if name == "vertex":
                names = [p[0] for p in props]
                ix, iy, iz = names.index("x"), names.index("y"), names.index("z")
                for rec in struct.iter_unpack(rec_fmt, data[pos:pos + size * count]):
                    positions.append((float(rec[ix]), float(rec[iy]), float(rec[iz])))
            pos += size * count
            continue
        for _ in range(count):
            for pname, ptype, ltype in props:
                if ltype is None:
                    pos += struct.calcsize(ptype)
                    continue
                (n,) = struct.unpack_from(order + ltype, data, pos)
                pos += struct.calcsize(ltype)
                vals = struct.unpack_from(order + ptype * n, data, pos)
                pos += struct.calcsize(ptype) * n
                if name == "face" and pname in ("vertex_indices", "vertex_index"):
                    _triangulate(list(vals), faces)
                elif name == "tristrips" and pname in ("vertex_indices", "vertex_index"):
                    _strips(vals, faces)
    return positions, faces


def parse_obj(path):
    positions, faces = [], []
    with open(path, "r", encoding="latin-1") as fh:
        for raw in fh:
            t = raw.split()
            if not t:
                continue
            if t[0] == "v":
                positions.append((float(t[1]), float(t[2]), float(t[3])))
            elif t[0] == "f":
                corners = []
                for c in t[1:]:
                    i = int(c.split("/")[0])
                    corners.append(i - 1 if i > 0 else len(positions) + i)
                _triangulate(corners, faces)
    return positions, faces


def parse_stl(path):
    with open(path, "rb") as fh:
        data = fh.read()
    tris = []
    if len(data) >= 84 and len(data) == 84 + 50 * struct.unpack_from("<I", data, 80)[0]:
        n = struct.unpack_from("<I", data, 80)[0]
        for i in range(n):
            v = struct.unpack_from("<12f", data, 84 + 50 * i)
            tris.append((v[3:6], v[6:9], v[9:12]))
    else:
        cur = []
        for line in data.decode("latin-1").splitlines():
            t = line.split()
            if t and t[0] == "vertex":
                cur.append(tuple(float(x) for x in t[1:4]))
                if len(cur) == 3:
                    tris.append(tuple(cur))
                    cur = []
    positions = [p for tri in tris for p in tri]
    faces = [(3 * i, 3 * i + 1, 3 * i + 2) for i in range(len(tris))]
    return positions, faces


PARSERS = {".off": parse_off, ".ply": parse_ply, ".obj": parse_obj, ".stl": parse_stl}


# ----------------------------------------------------------------------------------------------- counting

def _bfs_pieces(nodes, neighbours):
    """Connected pieces of a graph given as an adjacency dict; returns {node: piece id} and the count."""
    piece = {}
    count = 0
    for s in nodes:
        if s in piece:
            continue
        piece[s] = count
        queue = collections.deque([s])
        while queue:
            u = queue.popleft()
            for w in neighbours.get(u, ()):
                if w not in piece:
                    piece[w] = count
                    queue.append(w)
        count += 1
    return piece, count


def count_mesh(positions, faces):
    nv, nf = len(positions), len(faces)
    finite = [all(math.isfinite(c) for c in p) for p in positions]
    fin = [p for p, ok in zip(positions, finite) if ok]
    diag2 = 0.0
    if fin:
        diag2 = sum((max(p[d] for p in fin) - min(p[d] for p in fin)) ** 2 for d in range(3))
    area_tol = DEGENERATE_AREA_EPSILON * diag2

    referenced = [False] * nv
    topo = []
    out_of_range = repeated = degenerate = 0
    adjacency = collections.defaultdict(set)
    for (a, b, c) in faces:
        if min(a, b, c) < 0 or max(a, b, c) >= nv:
            out_of_range += 1
            continue
        referenced[a] = referenced[b] = referenced[c] = True
        adjacency[a].update((b, c))
        adjacency[b].update((a, c))
        adjacency[c].update((a, b))
        if a == b or b == c or a == c:
            repeated += 1
            degenerate += 1
            continue
        topo.append((a, b, c))
        if finite[a] and finite[b] and finite[c]:
            pa, pb, pc = positions[a], positions[b], positions[c]
            u = (pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2])
            w = (pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2])
            cx = u[1] * w[2] - u[2] * w[1]
            cy = u[2] * w[0] - u[0] * w[2]
            cz = u[0] * w[1] - u[1] * w[0]
            if 0.5 * math.sqrt(cx * cx + cy * cy + cz * cz) <= area_tol:
                degenerate += 1

    # edges: unordered pair -> list of directions (+1 when traversed lo -> hi)
    edges = collections.defaultdict(list)
    link = collections.defaultdict(list)  # vertex -> link edges (the opposite side of each incident face)
    for fi, (a, b, c) in enumerate(topo):
        for s, t in ((a, b), (b, c), (c, a)):
            edges[(min(s, t), max(s, t))].append((1 if s < t else -1, fi))
        link[a].append((b, c))
        link[b].append((c, a))
        link[c].append((a, b))
    boundary_adj = collections.defaultdict(set)
    nboundary = nnm_edges = ninconsistent = 0
    nm_vertices_of_edges = set()
    face_nbrs = collections.defaultdict(list)
    for (lo, hi), inc in edges.items():
        if len(inc) == 1:
            nboundary += 1
            boundary_adj[lo].add(hi)
            boundary_adj[hi].add(lo)
        elif len(inc) == 2:
            same = inc[0][0] == inc[1][0]
            ninconsistent += same
            face_nbrs[inc[0][1]].append((inc[1][1], same))
            face_nbrs[inc[1][1]].append((inc[0][1], same))
        else:
            nnm_edges += 1
            nm_vertices_of_edges.add(lo)

    # non-manifold vertices: the link graph of the vertex falls into several pieces
    nm_vertices = set()
    for v, ledges in link.items():
        g = collections.defaultdict(set)
        for x, y in ledges:
            g[x].add(y)
            g[y].add(x)
        _, pieces = _bfs_pieces(list(g), g)
        if pieces > 1:
            nm_vertices.add(v)

    comp, ncomp = _bfs_pieces(range(nv), adjacency)
    bpiece, nloops = _bfs_pieces(list(boundary_adj), boundary_adj)

    # orientability by BFS over faces across manifold edges, carrying a flip bit
    non_orientable_comps = set()
    flip = {}
    for f0 in range(len(topo)):
        if f0 in flip:
            continue
        flip[f0] = 0
        queue = collections.deque([f0])
        while queue:
            f = queue.popleft()
            for g, same in face_nbrs.get(f, ()):
                want = flip[f] ^ int(same)
                if g not in flip:
                    flip[g] = want
                    queue.append(g)
                elif flip[g] != want:
                    non_orientable_comps.add(comp[topo[f][0]])

    per = collections.defaultdict(lambda: [0, 0, 0, 0, True])  # V, E, F, loops, manifold
    for v in range(nv):
        if referenced[v]:
            per[comp[v]][0] += 1
    for (lo, _hi) in edges:
        per[comp[lo]][1] += 1
    for (a, _b, _c) in topo:
        per[comp[a]][2] += 1
    seen_loops = set()
    for v, p in bpiece.items():
        if p not in seen_loops:
            seen_loops.add(p)
            per[comp[v]][3] += 1
    for v in nm_vertices | nm_vertices_of_edges:
        per[comp[v]][4] = False
    for (a, b, c) in faces:
        if 0 <= min(a, b, c) and max(a, b, c) < nv and (a == b or b == c or a == c):
            per[comp[a]][4] = False
    genus_total, genus_ok, genera = 0, True, []
    for cid in sorted(per, key=lambda k: k):
        V, E, F, b, manifold = per[cid]
        twice = 2 - (V - E + F) - b
        g = twice // 2 if manifold and cid not in non_orientable_comps and twice >= 0 and twice % 2 == 0 else -1
        genera.append(g)
        if g < 0:
            genus_ok = False
        else:
            genus_total += g

    seen_pos = set()
    duplicates = 0
    for p, ok in zip(positions, finite):
        if not ok:
            continue
        key = (p[0] + 0.0, p[1] + 0.0, p[2] + 0.0)  # + 0.0 folds -0.0 into 0.0, as == does in C++
        if key in seen_pos:
            duplicates += 1
        else:
            seen_pos.add(key)

    return {
        "vertices": nv,
        "faces": nf,
        "edges": len(edges),
        "components": ncomp,
        "boundary_edges": nboundary,
        "boundary_loops": nloops,
        "non_manifold_edges": nnm_edges,
        "non_manifold_vertices": len(nm_vertices),
        "inconsistent_edges": ninconsistent,
        "degenerate_faces": degenerate,
        "repeated_index_faces": repeated,
        "duplicate_vertices": duplicates,
        "non_finite_vertices": nv - len(fin),
        "out_of_range_faces": out_of_range,
        "unreferenced_vertices": referenced.count(False),
        "euler_characteristic": nv - len(edges) + len(topo),
        "genus": genus_total if genus_ok else -1,
        "orientable": not non_orientable_comps,
        "component_genera": genera,
    }


def count_file(path):
    ext = os.path.splitext(path)[1].lower()
    try:
        positions, faces = PARSERS[ext](path)
        return path, count_mesh(positions, faces), None
    except Exception as e:  # report, do not stop the whole run
        return path, None, "%s: %s" % (type(e).__name__, e)


# ------------------------------------------------------------------------------------------ file handling

def expand(args):
    files = []
    for a in args:
        if os.path.isdir(a):
            found = []
            for root, _dirs, names in os.walk(a):
                for n in names:
                    if os.path.splitext(n)[1].lower() in MESH_EXTENSIONS:
                        found.append(os.path.join(root, n))
            files += sorted(found)
        else:
            files.append(a)
    return files


def run_shapestruct(binary, files, chunk=40):
    reports = {}
    for i in range(0, len(files), chunk):
        part = files[i:i + chunk]
        proc = subprocess.run([binary, "inspect", "--json", "--max-examples", "0"] + part,
                              capture_output=True, text=True)
        for rec in json.loads(proc.stdout):
            reports[rec["file"]] = rec
    return reports


COMPARED = ["vertices", "faces", "edges", "components", "boundary_edges", "boundary_loops", "non_manifold_edges",
            "non_manifold_vertices", "inconsistent_edges", "degenerate_faces", "repeated_index_faces",
            "duplicate_vertices", "non_finite_vertices", "out_of_range_faces", "unreferenced_vertices",
            "euler_characteristic", "genus", "orientable"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("paths", nargs="+")
    ap.add_argument("--compare", metavar="SHAPESTRUCT", help="path of the shapestruct executable")
    ap.add_argument("--root", help="data root: the first folder below it names the data set in the table")
    ap.add_argument("--jobs", type=int, default=1)
    args = ap.parse_args()
    files = expand(args.paths)
    if args.jobs > 1:
        import multiprocessing
        with multiprocessing.Pool(args.jobs) as pool:
            results = pool.map(count_file, files, chunksize=4)
    else:
        results = [count_file(f) for f in files]
    if not args.compare:
        for path, counts, err in results:
            print(json.dumps({"file": path, "counts": counts, "error": err}))
        return 0 if all(err is None for _, _, err in results) else 1

    ours = run_shapestruct(args.compare, files)
    table = collections.OrderedDict()
    disagreements, notable = [], []
    for path, counts, err in results:
        ds = os.path.relpath(path, args.root).split(os.sep)[0] if args.root else os.path.dirname(path)
        row = table.setdefault(ds, collections.Counter())
        row["files"] += 1
        rec = ours.get(path)
        if err is not None:
            row["python_failed"] += 1
            disagreements.append("%s: python could not parse: %s" % (path, err))
            continue
        if rec is None or not rec["ok"]:
            row["shapestruct_failed"] += 1
            disagreements.append("%s: shapestruct could not read: %s" % (path, rec and rec.get("error")))
            continue
        rep = rec["report"]
        diff = [k for k in COMPARED if rep.get(k) != counts[k]]
        if diff:
            row["disagree"] += 1
            disagreements.append("%s: %s" % (path, ", ".join("%s shapestruct %s python %s" % (k, rep.get(k), counts[k])
                                                              for k in diff)))
        else:
            row["agree"] += 1
        flags = []
        if counts["boundary_edges"]:
            row["with_boundary"] += 1
            flags.append("%d boundary edges in %d loops" % (counts["boundary_edges"], counts["boundary_loops"]))
        if counts["non_manifold_edges"] or counts["non_manifold_vertices"]:
            row["non_manifold"] += 1
            flags.append("%d non-manifold edges, %d non-manifold vertices" %
                         (counts["non_manifold_edges"], counts["non_manifold_vertices"]))
        if counts["genus"] > 0:
            row["genus_gt_0"] += 1
            flags.append("genus %d" % counts["genus"])
        if counts["components"] > 1:
            row["several_components"] += 1
            flags.append("%d components (%d unreferenced vertices)" %
                         (counts["components"], counts["unreferenced_vertices"]))
        if counts["degenerate_faces"]:
            row["degenerate"] += 1
            flags.append("%d degenerate faces" % counts["degenerate_faces"])
        if counts["duplicate_vertices"]:
            row["duplicates"] += 1
            flags.append("%d duplicate vertices" % counts["duplicate_vertices"])
        if counts["inconsistent_edges"]:
            row["inconsistent"] += 1
            flags.append("%d inconsistently oriented edges" % counts["inconsistent_edges"])
        if flags:
            notable.append("%s: %s" % (path, "; ".join(flags)))

    cols = ["files", "agree", "disagree", "shapestruct_failed", "python_failed", "with_boundary", "non_manifold",
            "genus_gt_0", "several_components", "degenerate", "duplicates", "inconsistent"]
    print("| data set | " + " | ".join(cols) + " |")
    print("|---" * (len(cols) + 1) + "|")
    total = collections.Counter()
    for ds, row in table.items():
        total.update(row)
        print("| %s | %s |" % (ds, " | ".join(str(row[c]) for c in cols)))
    print("| **all** | %s |" % " | ".join(str(total[c]) for c in cols))
    print("\nDisagreements (%d):" % len(disagreements))
    for d in disagreements:
        print("  " + d)
    print("\nNotable meshes (%d):" % len(notable))
    for n in notable:
        print("  " + n)
    return 0 if not disagreements else 1


if __name__ == "__main__":
    sys.exit(main())
