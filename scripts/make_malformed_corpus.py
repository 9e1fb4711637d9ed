#!/usr/bin/env python3
"""Generates the mesh I/O test corpus: tests/data/malformed/* (+ EXPECTED.tsv) and tests/data/good/*.

Deterministic (no randomness without a fixed seed). Re-run after editing and commit the generated files:
    python3 scripts/make_malformed_corpus.py
EXPECTED.tsv columns: file, expected substring of the error message, expected InputError::line()
(empty = not checked; 0 = no line, as for binary data).
"""
import pathlib
import random
import struct

ROOT = pathlib.Path(__file__).resolve().parent.parent
BAD = ROOT / "tests" / "data" / "malformed"
GOOD = ROOT / "tests" / "data" / "good"

TETRA_V = [(0, 0, 0), (10, 0, 0), (0, 10, 0), (0, 0, 10)]
TETRA_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]

expected = []


def bad(name, content, substring, line=""):
    data = content.encode() if isinstance(content, str) else content
    assert len(data) < 10 * 1024, name
    (BAD / name).write_bytes(data)
    expected.append((name, substring, str(line)))


def good(name, content):
    data = content.encode() if isinstance(content, str) else content
    (GOOD / name).write_bytes(data)


def garbage(n, seed):
    rng = random.Random(seed)
    return bytes(rng.randrange(256) for _ in range(n))


# ---------------------------------------------------------------- STL ----------------------------------------
def stl_ascii(facets, name="t"):
    out = [f"solid {name}"]
    for tri in facets:
        out += ["  facet normal 0 0 1", "    outer loop"]
        out += [f"      vertex {v}" for v in tri]
        out += ["    endloop", "  endfacet"]
    out.append(f"endsolid {name}")
    return "\n".join(out) + "\n"


def stl_binary(tris, count=None, header=b"binary test"):
    data = header.ljust(80, b" ") + struct.pack("<I", len(tris) if count is None else count)
    for tri in tris:
        data += struct.pack("<3f", 0, 0, 1)
        for v in tri:
            data += struct.pack("<3f", *v)
        data += b"\0\0"
    return data


TETRA_TRIS = [[TETRA_V[i] for i in f] for f in TETRA_F]
tri_text = [["0 0 0", "10 0 0", "0 10 0"], ["0 0 0", "0 0 10", "10 0 0"]]

bad("stl_ascii_truncated.stl", stl_ascii(tri_text).split("      vertex 0 0 10")[0], "unexpected end of file in facet 1 (file truncated?)", 11)
bad("stl_ascii_nan.stl", stl_ascii([["0 0 0", "nan 0 0", "0 10 0"]]), "facet 0 vertex 1 has a non-finite coordinate (x = nan)", 5)
bad("stl_ascii_bad_number.stl", stl_ascii([["0 0 0", "1.0abc 0 0", "0 10 0"]]), "cannot parse vertex x from '1.0abc'", 5)
bad("stl_ascii_two_vertices.stl", stl_ascii([["0 0 0", "10 0 0"]]), "face 0 has only 2 vertices", 5)
bad("stl_ascii_extra_token.stl", stl_ascii([["0 0 0", "10 0 0 7", "0 10 0"]]), "unexpected extra token '7' after vertex coordinates", 5)
bad("stl_ascii_unknown_keyword.stl", stl_ascii(tri_text).replace("  facet normal 0 0 1\n", "  facett normal 0 0 1\n", 1),
    "expected 'facet' or 'endsolid', found 'facett'", 2)
bad("stl_ascii_missing_loop.stl", stl_ascii(tri_text).replace("    outer loop\n", "", 1), "expected 'outer' in facet 0, found 'vertex'", 3)
bad("stl_ascii_only_header.stl", "solid empty\n", "missing 'endsolid'", 1)

bad("stl_binary_billion_triangles.stl", stl_binary(TETRA_TRIS, count=1_000_000_000),
    "binary STL header claims 1000000000 triangles (50000000084 bytes) but the file has only 284 bytes", 0)
bad("stl_binary_truncated.stl", stl_binary(TETRA_TRIS)[:-25], "claims 4 triangles (284 bytes) but the file has only 259 bytes", 0)
bad("stl_binary_extra_bytes.stl", stl_binary(TETRA_TRIS) + b"\0" * 7, "extra data after the last triangle", 0)
nan_tris = [list(t) for t in TETRA_TRIS]
nan_tris[1][2] = (0.0, float("inf"), 0.0)
bad("stl_binary_inf.stl", stl_binary(nan_tris), "triangle 1 corner 2 has a non-finite coordinate (y = inf)", 0)
bad("stl_binary_zero_triangles.stl", stl_binary([]), "no triangles", 0)
bad("stl_binary_garbage.stl", garbage(3000, 1), "not an STL file", 0)
bad("stl_binary_tiny_garbage.stl", garbage(40, 2), "too small for a binary STL header", 0)
bad("stl_binary_solid_header_truncated.stl", stl_binary(TETRA_TRIS, header=b"solid fooled you")[:-50],
    "claims 4 triangles", 0)
bad("stl_empty.stl", b"", "file is empty", 0)

# ---------------------------------------------------------------- OBJ ----------------------------------------
OBJ_V = "v 0 0 0\nv 10 0 0\nv 0 10 0\nv 0 0 10\n"
bad("obj_index_out_of_range.obj", "# tetra\n" + OBJ_V + "f 1 3 2\nf 1 2 9\n",
    "face 2: vertex index 9 is out of range (4 vertices defined so far)", 7)
bad("obj_zero_index.obj", OBJ_V + "f 0 1 2\n", "face 1: vertex index 0 is invalid", 5)
bad("obj_negative_too_far.obj", OBJ_V + "f -1 -2 -10\n", "face 1: vertex index -10 is out of range", 5)
bad("obj_forward_reference.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", "vertex index 3 is out of range (2 vertices defined so far)", 3)
bad("obj_inf_vertex.obj", "v 0 0 0\nv 10 0 0\nv 0 inf 0\nf 1 2 3\n", "vertex 3 has a non-finite coordinate (y = inf)", 3)
bad("obj_two_vertex_face.obj", OBJ_V + "f 1 2 3\nf 1 2\n", "face 2 has only 2 vertices", 6)
bad("obj_bad_number.obj", "v 0 0 0\nv 10 0 1,5\n", "cannot parse vertex z from '1,5'", 2)
bad("obj_number_too_large.obj", "v 0 0 0\nv 1e999 0 0\n", "cannot parse vertex x from '1e999'", 2)
bad("obj_missing_coordinate.obj", "v 0 0 0\nv 10 0\n", "line ends before vertex z", 2)
bad("obj_extra_token.obj", "v 0 0 0 1 1 1 1 1\n", "unexpected extra token '1' after vertex data", 1)
bad("obj_bad_face_reference.obj", OBJ_V + "f 1 2/x 3\n", "face 1: malformed vertex reference '2/x'", 5)
bad("obj_too_many_slashes.obj", OBJ_V + "f 1/1/1/1 2 3\n", "malformed vertex reference '1/1/1/1'", 5)
bad("obj_no_faces.obj", "# only points\n" + OBJ_V, "the file contains no triangles", 0)
bad("obj_binary_garbage.obj", b"\x89PNG\r\n\x1a\n" + garbage(500, 3), "unknown OBJ statement '\\x89PNG'", 1)
bad("obj_only_comments.obj", "# nothing\n\n   \n# here\n", "no triangles", 0)

# ---------------------------------------------------------------- PLY ----------------------------------------
def ply_header(fmt, nv, nf, vprops="property float x\nproperty float y\nproperty float z\n",
               fprops="property list uchar int vertex_indices\n", extra=""):
    return (f"ply\nformat {fmt} 1.0\ncomment test\nelement vertex {nv}\n{vprops}{extra}"
            f"element face {nf}\n{fprops}end_header\n")


ASCII_V = "0 0 0\n10 0 0\n0 10 0\n0 0 10\n"
ASCII_F = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"
bad("ply_ascii_count_lies.ply", ply_header("ascii", 1_000_000_000, 4) + ASCII_V + ASCII_F,
    "header declares 1000000000 'vertex' elements", 4)
bad("ply_ascii_truncated.ply", ply_header("ascii", 4, 4) + ASCII_V + "3 0 2 1\n3 0 1", "unexpected end of file while reading face 1 list item (file truncated?)", 16)
bad("ply_ascii_index_out_of_range.ply", ply_header("ascii", 4, 4) + ASCII_V + "3 0 2 1\n3 0 1 7\n3 0 3 2\n3 1 2 3\n",
    "face 1: vertex index 7 is out of range (the file has 4 vertices)", 16)
bad("ply_ascii_no_end_header.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n", "no 'end_header'", 4)
bad("ply_ascii_bad_number.ply", ply_header("ascii", 4, 4) + "0 0 0\n10 0 0\n0 1O 0\n0 0 10\n" + ASCII_F,
    "cannot parse vertex 2 from '1O'", 13)
bad("ply_ascii_float_index.ply", ply_header("ascii", 4, 4) + ASCII_V + "3 0 2 1.5\n" + ASCII_F,
    "cannot parse face 0 list item from '1.5' (expected an integer)", 15)
bad("ply_ascii_extra_data.ply", ply_header("ascii", 4, 4) + ASCII_V + ASCII_F + "3 0 1 2\n", "unexpected extra data '3' after the last element", 19)
bad("ply_ascii_no_faces.ply", ply_header("ascii", 4, 0) + ASCII_V, "no triangles", 0)
bad("ply_ascii_unknown_type.ply", ply_header("ascii", 4, 4, vprops="property flot x\n") + ASCII_V, "unknown property type 'flot'", 5)
bad("ply_ascii_missing_z.ply", ply_header("ascii", 4, 4, vprops="property float x\nproperty float y\n") + ASCII_V,
    "the vertex element has no 'z' property", 4)
bad("ply_ascii_no_index_list.ply", ply_header("ascii", 4, 4, fprops="property list uchar int corners\n") + ASCII_V + ASCII_F,
    "no 'vertex_indices'", 8)
bad("ply_ascii_two_index_face.ply", ply_header("ascii", 4, 4) + ASCII_V + "2 0 1\n" + ASCII_F[8:], "face 0 has only 2 vertices", 15)
bad("ply_ascii_nan.ply", ply_header("ascii", 4, 4) + "0 0 0\n10 0 0\n0 10 nan\n0 0 10\n" + ASCII_F,
    "vertex 2 has a non-finite coordinate (z = nan)", 13)
bad("ply_not_ply.ply", "solid x\nfacet\n", "not a PLY file", 1)


def ply_binary_body(le=True, vfmt="fff", faces=TETRA_F, verts=TETRA_V, cfmt="B", ifmt="i"):
    e = "<" if le else ">"
    body = b"".join(struct.pack(e + vfmt, *v) for v in verts)
    for f in faces:
        body += struct.pack(e + cfmt, len(f)) + struct.pack(e + ifmt * len(f), *f)
    return body


bad("ply_binary_truncated.ply", (ply_header("binary_little_endian", 4, 4) + "").encode() + ply_binary_body()[:80],
    "face 2 claims a list of 3 items but only 5 bytes remain (file truncated?)", 0)
bad("ply_binary_huge_vertex_count.ply", ply_header("binary_little_endian", 4_000_000_000, 4).encode() + ply_binary_body(),
    "header declares 4000000000 'vertex' elements", 4)
bad("ply_binary_count_overflow.ply", ply_header("binary_little_endian", 4, 2**62).encode() + ply_binary_body(),
    "header declares 4611686018427387904 'face' elements", 8)
be_nan_verts = [(0.0, 0.0, 0.0), (10.0, 0.0, 0.0), (0.0, float("nan"), 0.0), (0.0, 0.0, 10.0)]
bad("ply_binary_be_nan.ply",
    ply_header("binary_big_endian", 4, 4, vprops="property double x\nproperty double y\nproperty double z\n").encode()
    + ply_binary_body(le=False, vfmt="ddd", verts=be_nan_verts),
    "vertex 2 has a non-finite coordinate (y = nan)", 0)
huge_list = ply_binary_body()[:48] + struct.pack("<I", 0xFFFFFFF0) + b"\0" * 40
bad("ply_binary_huge_list.ply",
    ply_header("binary_little_endian", 4, 4, fprops="property list uint int vertex_indices\n").encode() + huge_list,
    "face 0 claims a list of 4294967280 items", 0)
bad("ply_binary_index_out_of_range.ply", ply_header("binary_little_endian", 4, 4).encode()
    + ply_binary_body(faces=[(0, 2, 1), (0, 1, 3), (0, 3, -5), (1, 2, 3)]),
    "face 2: vertex index -5 is out of range (the file has 4 vertices)", 0)
bad("ply_binary_one_index_face.ply", ply_header("binary_little_endian", 4, 1).encode()
    + ply_binary_body(faces=[(0,)]) + b"\0" * 8, "face 0 has only 1 vertices", 0)
bad("ply_binary_bad_format.ply", b"ply\nformat binary_middle_endian 1.0\nend_header\n" + garbage(64, 4),
    "unknown PLY format 'binary_middle_endian'", 2)
bad("ply_binary_garbage.ply", b"ply\n" + garbage(600, 5), "unknown PLY header keyword", 2)

# ---------------------------------------------------------------- OFF ----------------------------------------
OFF_V = "0 0 0\n10 0 0\n0 10 0\n0 0 10\n"
OFF_F = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"
bad("off_counts_lie.off", "OFF\n100000000 4 0\n" + OFF_V + OFF_F, "header declares 100000000 vertices and 4 faces", 2)
bad("off_truncated.off", "OFF\n4 4 6\n" + OFF_V.replace(" ", ".000000 ") + OFF_F[:8], "unexpected end of file after 1 of 4 faces (file truncated?)", 7)
bad("off_index_out_of_range.off", "OFF\n4 4 6\n" + OFF_V + "3 0 2 1\n3 0 1 12\n3 0 3 2\n3 1 2 3\n",
    "face 1: vertex index 12 is out of range (the file has 4 vertices)", 8)
bad("off_extra_token.off", "OFF\n4 4 6\n0 0 0\n10 0 0 5\n0 10 0\n0 0 10\n" + OFF_F,
    "unexpected extra token '5' after the vertex data", 4)
bad("off_face_short_line.off", "OFF\n4 4 6\n" + OFF_V + "4 0 1 2\n" + OFF_F[8:], "face 0 declares 4 vertices but the line has only 3 indices", 7)
bad("off_two_vertex_face.off", "OFF\n4 4 6\n" + OFF_V + "2 0 1\n" + OFF_F[8:], "face 0 has only 2 vertices", 7)
bad("off_4d_keyword.off", "4OFF\n4 4 6\n" + OFF_V + OFF_F, "unsupported OFF variant '4OFF'", 1)
bad("off_binary.off", "OFF BINARY\n" + "\0" * 40, "binary OFF is not supported", 1)
bad("off_binary_garbage.off", garbage(700, 6).replace(b"#", b"!").replace(b"\n", b"!"), "cannot parse the vertex count", 1)
bad("off_inf_vertex.off", "OFF\n# comment\n4 4 6\n0 0 0\n10 0 0\n0 10 0\n-inf 0 10\n" + OFF_F,
    "vertex 3 has a non-finite coordinate (x = -inf)", 7)
bad("off_trailing_garbage.off", "OFF\n4 4 6\n" + OFF_V + OFF_F + "garbage here\n", "unexpected data after the last face", 11)
bad("off_negative_count.off", "OFF\n-4 4 6\n" + OFF_V + OFF_F, "negative vertex or face count", 2)
bad("off_no_faces.off", "OFF\n4 0 0\n" + OFF_V, "no triangles", 2)
bad("off_coff_missing_colour.off", "COFF\n4 4 6\n0 0 0 1 0 0 1\n10 0 0\n0 10 0 1 1 1 1\n0 0 10 1 1 1 1\n" + OFF_F,
    "vertex 1: expected 3 more values for this OFF variant", 4)

# ---------------------------------------------------------------- VTP ----------------------------------------
def vtp(points, conn, offsets, npoints=None, npolys=None, extra_piece=""):
    npoints = len(points) // 3 if npoints is None else npoints
    npolys = len(offsets) if npolys is None else npolys
    p = " ".join(str(x) for x in points)
    return f"""<?xml version="1.0"?>
<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">
  <PolyData>
    <Piece NumberOfPoints="{npoints}" NumberOfVerts="0" NumberOfLines="0" NumberOfStrips="0" NumberOfPolys="{npolys}"{extra_piece}>
      <Points>
        <DataArray type="Float32" NumberOfComponents="3" format="ascii">{p}</DataArray>
      </Points>
      <Polys>
        <DataArray type="Int32" Name="connectivity" format="ascii">{" ".join(map(str, conn))}</DataArray>
        <DataArray type="Int32" Name="offsets" format="ascii">{" ".join(map(str, offsets))}</DataArray>
      </Polys>
    </Piece>
  </PolyData>
</VTKFile>
"""


TP = [c for v in TETRA_V for c in v]
TC = [i for f in TETRA_F for i in f]
TO = [3, 6, 9, 12]
good_vtp = vtp(TP, TC, TO)
bad("vtp_truncated.vtp", good_vtp[: good_vtp.index("<Polys>") + 20], "VTK could not read the file", 0)
bad("vtp_not_xml.vtp", garbage(300, 7), "not a VTK XML file", 0)
bad("vtp_unstructured_grid.vtp", good_vtp.replace('type="PolyData"', 'type="UnstructuredGrid"'), "not a VTK PolyData file", 0)
bad("vtp_huge_point_count.vtp", vtp(TP, TC, TO, npoints=999_999_999_999), "NumberOfPoints = 999999999999", 0)
bad("vtp_index_out_of_range.vtp", vtp(TP, [0, 2, 99] + TC[3:], TO), "face 0: vertex index 99 is out of range (the file has 4 vertices)", 0)
bad("vtp_no_polys.vtp", vtp(TP, [], [], npolys=0), "no triangles", 0)
bad("vtp_two_point_poly.vtp", vtp(TP, [0, 1] + TC[3:], [2, 5, 8, 11]), "face 0 has only 2 vertices", 0)
bad("vtp_bad_number.vtp", vtp(TP[:4] + ["abc"] + TP[5:], TC, TO), "VTK could not read the file", 0)
bad("vtp_empty.vtp", b"", "file is empty", 0)

# ---------------------------------------------------------------- misc ---------------------------------------
bad("unknown_extension.xyz", "0 0 0\n", "unknown mesh file extension '.xyz'", 0)

(BAD / "EXPECTED.tsv").write_text(
    "# file\texpected substring of the InputError message\texpected line (empty: unchecked, 0: binary/none)\n"
    + "".join(f"{f}\t{s}\t{l}\n" for f, s, l in expected))

# ---------------------------------------------------------------- good files ---------------------------------
good("tetra_be_types.ply",
     ("ply\nformat binary_big_endian 1.0\ncomment odd but valid types\nelement vertex 4\nproperty uchar flag\n"
      "property float x\nproperty double y\nproperty short z\nproperty int extra\nelement edge 2\n"
      "property int vertex1\nproperty int vertex2\nelement face 4\nproperty int tag\n"
      "property list ushort uint vertex_indices\nend_header\n").encode()
     + b"".join(struct.pack(">BfdhI", 7, v[0], v[1], v[2], 99) for v in TETRA_V)
     + struct.pack(">4i", 0, 1, 1, 2)
     + b"".join(struct.pack(">iH3I", 5, 3, *f) for f in TETRA_F))
good("tetra_le_vertex_index.ply",
     ("ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
      "property double z\nproperty list uchar float extra_list\nelement face 4\nproperty list int short vertex_index\n"
      "end_header\n").encode()
     + b"".join(struct.pack("<3dB2f", *v, 2, 0.5, 0.25) for v in TETRA_V)
     + b"".join(struct.pack("<i3h", 3, *f) for f in TETRA_F))
