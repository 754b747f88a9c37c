"""OFF meshes for the check scripts beside this file (they import it; no package needed)."""
import math
import sys


def read_off(path):
    """The vertices (x, y, z tuples) and faces (tuples of 0-based corners) of an OFF file."""
    with open(path) as f:
        words = f.read().split()
    if not words or words[0] != "OFF":
        sys.exit(f"{path}: not an OFF file")
    nv, nf = int(words[1]), int(words[2])
    at = 4
    verts = [tuple(float(w) for w in words[at + 3 * i:at + 3 * i + 3]) for i in range(nv)]
    at += 3 * nv
    faces = []
    for _ in range(nf):
        k = int(words[at])
        faces.append(tuple(int(w) for w in words[at + 1:at + 1 + k]))
        at += 1 + k
    return verts, faces


def triangle_area(a, b, c):
    u = [b[d] - a[d] for d in range(3)]
    v = [c[d] - a[d] for d in range(3)]
    x = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    return 0.5 * math.sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2])


def face_area(verts, face):
    """Area of a polygon face, fan-triangulated from its first corner."""
    return sum(triangle_area(verts[face[0]], verts[face[k]], verts[face[k + 1]]) for k in range(1, len(face) - 1))
