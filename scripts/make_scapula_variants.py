#!/usr/bin/env python3
"""Scapula meshes of ~45k and ~400k faces for the collision benchmark, made at bench time from the bundled
scapula (resources/bones/scapula_R_repaired.ply, 14,998 faces, closed): sqrt(3) subdivision (Kobbelt 2000),
whose vertex relaxation smooths, then one Taubin smoothing pass (lambda 0.5, mu -0.53) per step. No openly
licensed high-resolution scapula exists (../shared/data/SOURCES.md), so these are refinements of the real one,
not new anatomy; they are never committed (large, and reproducible from this script).

Each sqrt(3) step triples the face count: 14,998 -> 44,994 (one step) -> 134,982 -> 404,946 (three steps).
Uniform steps multiply by 3 (sqrt(3)) or 4 (Loop), so the "~35k" class is represented by 45k.
With --loop N the script applies N Loop-like 1:4 midpoint steps with Taubin smoothing instead
(14,998 x 4^3 = 959,872 faces: the "up to a million" case).

Usage: scripts/make_scapula_variants.py OUT_DIR [--input MESH.ply] [--sqrt3 1 3] [--loop 3]
Writes OUT_DIR/scapula_<faces>_<method>.ply (binary PLY, mm) and prints one line per file.
Pure Python (no numpy): about 10 s for the 400k mesh.
"""
import argparse
import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_INPUT = os.path.join(HERE, "..", "resources", "bones", "scapula_R_repaired.ply")


def fail(msg):
    sys.stderr.write("make_scapula_variants: error: %s\n" % msg)
    sys.exit(3)


def read_ply(path):
    """Binary little-endian or ASCII PLY with x, y, z (float/double) and a face index list."""
    try:
        data = open(path, "rb").read()
    except OSError as e:
        fail("%s: %s" % (path, e.strerror))
    end = data.find(b"end_header\n")
    if not data.startswith(b"ply") or end < 0:
        fail("%s: not a PLY file" % path)
    header = data[:end].decode("ascii", "replace").splitlines()
    body = data[end + len(b"end_header\n"):]
    fmt = None
    elements = []  # (name, count, [props])
    for line in header:
        w = line.split()
        if not w:
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            elements.append((w[1], int(w[2]), []))
        elif w[0] == "property" and elements:
            elements[-1][2].append(w[1:])
    sizes = {"char": 1, "uchar": 1, "int8": 1, "uint8": 1, "short": 2, "ushort": 2, "int16": 2, "uint16": 2,
             "int": 4, "uint": 4, "int32": 4, "uint32": 4, "float": 4, "float32": 4, "double": 8, "float64": 8}
    codes = {"char": "b", "uchar": "B", "int8": "b", "uint8": "B", "short": "h", "ushort": "H", "int16": "h",
             "uint16": "H", "int": "i", "uint": "I", "int32": "i", "uint32": "I", "float": "f", "float32": "f",
             "double": "d", "float64": "d"}
    verts, faces = [], []
    if fmt == "ascii":
        tokens = body.split()
        pos = 0
        for name, count, props in elements:
            for _ in range(count):
                vals = []
                for p in props:
                    if p[0] == "list":
                        n = int(tokens[pos]); pos += 1
                        vals.append([int(t) for t in tokens[pos:pos + n]]); pos += n
                    else:
                        vals.append(float(tokens[pos])); pos += 1
                if name == "vertex":
                    verts.append((vals[0], vals[1], vals[2]))
                elif name == "face":
                    faces.append(vals[0])
    elif fmt == "binary_little_endian":
        off = 0
        for name, count, props in elements:
            simple = all(p[0] != "list" for p in props)
            if simple:
                st = struct.Struct("<" + "".join(codes[p[0]] for p in props))
                for _ in range(count):
                    vals = st.unpack_from(body, off); off += st.size
                    if name == "vertex":
                        verts.append((float(vals[0]), float(vals[1]), float(vals[2])))
            else:
                for _ in range(count):
                    row = None
                    for p in props:
                        if p[0] == "list":
                            n = struct.unpack_from("<" + codes[p[1]], body, off)[0]; off += sizes[p[1]]
                            row = list(struct.unpack_from("<%d%s" % (n, codes[p[2]]), body, off)); off += n * sizes[p[2]]
                        else:
                            off += sizes[p[0]]
                    if name == "face":
                        faces.append(row)
    else:
        fail("%s: unsupported PLY format %s" % (path, fmt))
    tris = []
    for f in faces:
        if f is None or len(f) < 3:
            fail("%s: a face has fewer than 3 vertices" % path)
        for k in range(1, len(f) - 1):  # fan-triangulate polygons
            tris.append((f[0], f[k], f[k + 1]))
    for t in tris:
        if max(t) >= len(verts) or min(t) < 0:
            fail("%s: face index out of range" % path)
    return verts, tris


def write_ply(path, verts, tris, comments):
    with open(path, "wb") as out:
        head = ["ply", "format binary_little_endian 1.0"] + ["comment " + c for c in comments] + [
            "element vertex %d" % len(verts), "property double x", "property double y", "property double z",
            "element face %d" % len(tris), "property list uchar int vertex_indices", "end_header"]
        out.write(("\n".join(head) + "\n").encode("ascii"))
        out.write(b"".join(struct.pack("<ddd", *v) for v in verts))
        out.write(b"".join(struct.pack("<Biii", 3, *t) for t in tris))


def neighbours(nverts, tris):
    adj = [set() for _ in range(nverts)]
    for a, b, c in tris:
        adj[a].update((b, c)); adj[b].update((c, a)); adj[c].update((a, b))
    return adj


def taubin(verts, tris, lam=0.5, mu=-0.53):
    adj = neighbours(len(verts), tris)
    for factor in (lam, mu):
        new = []
        for i, (x, y, z) in enumerate(verts):
            n = adj[i]
            if not n:
                new.append((x, y, z)); continue
            k = 1.0 / len(n)
            sx = sum(verts[j][0] for j in n) * k; sy = sum(verts[j][1] for j in n) * k; sz = sum(verts[j][2] for j in n) * k
            new.append((x + factor * (sx - x), y + factor * (sy - y), z + factor * (sz - z)))
        verts = new
    return verts


def sqrt3_step(verts, tris):
    """Kobbelt's sqrt(3) subdivision: face centroids, relaxed old vertices, old edges flipped."""
    n_old = len(verts)
    edge_face = {}
    for fi, (a, b, c) in enumerate(tris):
        edge_face[(a, b)] = fi; edge_face[(b, c)] = fi; edge_face[(c, a)] = fi
    adj = neighbours(n_old, tris)
    new_verts = []
    for i, (x, y, z) in enumerate(verts):
        n = len(adj[i])
        if n == 0:
            new_verts.append((x, y, z)); continue
        alpha = (4.0 - 2.0 * math.cos(2.0 * math.pi / n)) / 9.0
        sx = sum(verts[j][0] for j in adj[i]) / n; sy = sum(verts[j][1] for j in adj[i]) / n; sz = sum(verts[j][2] for j in adj[i]) / n
        new_verts.append(((1 - alpha) * x + alpha * sx, (1 - alpha) * y + alpha * sy, (1 - alpha) * z + alpha * sz))
    for a, b, c in tris:
        va, vb, vc = verts[a], verts[b], verts[c]
        new_verts.append(((va[0] + vb[0] + vc[0]) / 3, (va[1] + vb[1] + vc[1]) / 3, (va[2] + vb[2] + vc[2]) / 3))
    out = []
    for fi, (a, b, c) in enumerate(tris):
        mf = n_old + fi
        for x, y in ((a, b), (b, c), (c, a)):
            g = edge_face.get((y, x))
            out.append((x, y, mf) if g is None else (x, n_old + g, mf))  # the flipped edge joins the centroids
    return new_verts, out


def midpoint_step(verts, tris):
    """1:4 split at edge midpoints (Loop's topology; the smoothing comes from the Taubin pass)."""
    verts = list(verts)
    mid = {}

    def m(a, b):
        key = (a, b) if a < b else (b, a)
        i = mid.get(key)
        if i is None:
            va, vb = verts[a], verts[b]
            verts.append(((va[0] + vb[0]) / 2, (va[1] + vb[1]) / 2, (va[2] + vb[2]) / 2))
            i = mid[key] = len(verts) - 1
        return i

    out = []
    for a, b, c in tris:
        ab, bc, ca = m(a, b), m(b, c), m(c, a)
        out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    return verts, out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out_dir")
    ap.add_argument("--input", default=DEFAULT_INPUT)
    ap.add_argument("--sqrt3", type=int, nargs="*", default=[1, 3], help="numbers of sqrt(3) steps, one file each")
    ap.add_argument("--loop", type=int, nargs="*", default=[], help="numbers of 1:4 steps, one file each")
    args = ap.parse_args()
    verts, tris = read_ply(args.input)
    os.makedirs(args.out_dir, exist_ok=True)
    src = os.path.basename(args.input)
    for method, counts, step in (("sqrt3", args.sqrt3, sqrt3_step), ("split4", args.loop, midpoint_step)):
        v, t, done = verts, tris, 0
        for target in sorted(counts):
            while done < target:
                v, t = step(v, t)
                v = taubin(v, t)
                done += 1
            path = os.path.join(args.out_dir, "scapula_%dk_%sx%d.ply" % (round(len(t) / 1000), method, target))
            write_ply(path, v, t, ["ReamSim scapula variant: %s, %d x %s subdivision + Taubin smoothing (one pass per step)"
                                   % (src, target, method), "generated by scripts/make_scapula_variants.py; not anatomy"])
            print("%s %d faces %d vertices" % (path, len(t), len(v)))


if __name__ == "__main__":
    main()
