#!/usr/bin/env python3
"""Writes the PLY fixtures of this folder (run from anywhere; rewrites them all).

Each file's second header line is `comment expect: WHERE: TEXT`, which tests/cli/ply_cli.rs checks
against the error message: `line N` (the header or an ASCII body line: `FILE:N: TEXT`) or
`byte N` (a binary body: `FILE: at byte N: TEXT`). Files named `valid_*` must render. The byte
offsets are computed here from the layout written, independently of lanecast."""

import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
TRI = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]


def header(fmt, expect, lines, eol="\n"):
    return eol.join(["ply", f"comment expect: {expect}", f"format {fmt} 1.0", *lines, "end_header", ""])


VERT_XYZ = ["element vertex {nv}", "property float x", "property float y", "property float z"]
FACE_LIST = ["element face {nf}", "property list uchar int vertex_indices"]


def mesh_lines(nv, nf, extra=()):
    return [l.format(nv=nv, nf=nf) for l in VERT_XYZ + FACE_LIST] + list(extra)


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def ascii_fixtures():
    v4 = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
    ok = mesh_lines(4, 2)
    # (name, header lines, body, expectation); the body's first line is len(lines) + 5
    cases = [
        ("bad_magic.ply", ok, v4 + "3 0 1 2\n3 0 2 3\n", "line 1: not a PLY file"),
        ("unknown_format.ply", ok, "", "line 3: unknown format 'ascii2'"),
        ("bad_version.ply", ok, "", "line 3: PLY version '1.1'"),
        ("unknown_type.ply", ["element vertex 4", "property float x", "property float y",
                              "property half z"], "", "line 7: unknown property type 'half'"),
        ("missing_z.ply", ["element vertex 4", "property float x", "property float y"]
         + mesh_lines(4, 2)[4:], "", "line 4: element 'vertex' has no property 'z'"),
        ("point_cloud.ply", mesh_lines(4, 0)[:4], v4,
         "line 8: no 'face' element"),
        ("face_without_list.ply", mesh_lines(4, 1)[:4] + ["element face 1", "property int flags"],
         v4 + "0\n", "line 8: element 'face' has no list 'vertex_indices'"),
        ("float_list_count.ply", mesh_lines(4, 1)[:5] + ["property list float int vertex_indices"],
         "", "line 9: a list count must be an integer type, not float"),
        ("huge_vertex_count.ply", mesh_lines(4000000000, 2), v4 + "3 0 1 2\n3 0 2 3\n",
         "line 4: 4000000000 'vertex' records of at least 6 bytes need 24000000000 bytes"),
        ("ascii_nan.ply", ok, "0 0 0\n1 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",
         "line 13: vertex 2: y is NaN"),
        ("ascii_bad_number.ply", ok, "0 0 0\n1 0 0\n1 1 0\n0 1.5.5 0\n3 0 1 2\n3 0 2 3\n",
         "line 14: vertex 3: '1.5.5' is not a number"),
        ("ascii_index_out_of_range.ply", ok, v4 + "3 0 1 2\n3 0 2 9\n",
         "line 16: face 1: vertex index 9 is out of range (the file has 4 vertices"),
        ("ascii_two_vertex_face.ply", ok, v4.replace("0 0 0", "0.0 0.0 0.0") + "3 0 1 2\n2 0 2\n",
         "line 16: face 1: a face needs at least 3 vertices, got 2"),
        ("ascii_count_overflow.ply", ok, v4 + "3 0 1 2\n300 0 2 3\n",
         "line 16: face 1: '300' is not a valid uchar"),
        ("ascii_trailing_garbage.ply", ok, v4 + "3 0 1 2\n3 0 2 3\n3 0 1 3\n",
         "line 17: '3' after the last element the header declares"),
        ("ascii_cut_short.ply", ok,
         "0.000000 0.000000 0.000000\n1.000000 0.000000 0.000000\n"
         "1.000000 1.000000 0.000000\n0.000000 1.000000 0.000000\n3 0 1 2\n",
         "line 15: face 1: the file ends before this record"),
    ]
    for name, lines, body, expect in cases:
        fmt = {"unknown_format.ply": "ascii2"}.get(name, "ascii")
        text = header(fmt, expect, lines) + body
        if name == "bad_magic.ply":
            text = "PLY" + text[3:]
        if name == "bad_version.ply":
            text = text.replace("format ascii 1.0", "format ascii 1.1")
        write(name, text)
    # valid: CRLF, comments, extra properties, a quad, a pentagon, an element to skip
    lines = ["comment CRLF line ends, a quad and a pentagon", "obj_info by hand",
             "element vertex 9", "property float x", "property float nx", "property float y",
             "property float z", "property uchar red",
             "element face 2", "property list uchar int vertex_indices",
             "property list uchar float texcoord",
             "element edge 1", "property int vertex1", "property int vertex2"]
    # a quad on the left, a convex pentagon on the right: every fanned triangle in view
    body = ("-2 0 -1 0 9\r\n-0.5 0 -1 0 9\r\n-0.5 0 1 0 9\r\n-2 0 1 0 9\r\n"
            "0.5 1 -1 0 9\r\n2 1 -1 0 9\r\n2.5 1 0.5 0 9\r\n1.25 1 1.5 0 9\r\n0 1 0.5 0 9\r\n"
            "4 0 1 2 3 0\r\n5 4 5 6 7 8 2 0.5 0.5\r\n0 1\r\n")
    write("valid_crlf_ascii.ply", header("ascii", "- (renders)", lines, "\r\n") + body)


def binary(name, big, expect_fn, lines, body_fn, cut=0):
    """expect_fn(body_start, body) -> expectation; body_fn(pack) -> body bytes."""
    e = ">" if big else "<"
    fmt = "binary_big_endian" if big else "binary_little_endian"
    body = body_fn(lambda f, *v: struct.pack(e + f, *v))
    expect = "?"
    for _ in range(4):  # the header's length depends on the offset it quotes
        head = header(fmt, expect, lines).encode()
        data = (head + body)[: len(head) + len(body) - cut]
        expect = expect_fn(len(head), data)
    assert header(fmt, expect, lines).encode() == head, name
    write(name, data)


def verts(p, vs):
    return b"".join(p("3f", *v) for v in vs)


def faces(p, fs, count="B", item="i"):
    return b"".join(p(count, len(f)) + p(f"{len(f)}{item}", *f) for f in fs)


def binary_fixtures():
    nan = [TRI[0], TRI[1], (1, float("nan"), 0), TRI[3]]
    binary("le_nan.ply", False, lambda b, d: f"byte {b + 2 * 12 + 4}: vertex 2: y is NaN",
           mesh_lines(4, 2), lambda p: verts(p, nan) + faces(p, [(0, 1, 2), (0, 2, 3)]))
    inf = [TRI[0], TRI[1], TRI[2], (0, 1, float("-inf"))]
    binary("be_inf.ply", True, lambda b, d: f"byte {b + 3 * 12 + 8}: vertex 3: z is infinite",
           mesh_lines(4, 2), lambda p: verts(p, inf) + faces(p, [(0, 1, 2), (0, 2, 3)]))
    binary("le_index_out_of_range.ply", False,
           lambda b, d: f"byte {b + 48 + 13 + 1 + 8}: face 1: vertex index 7 is out of range",
           mesh_lines(4, 3), lambda p: verts(p, TRI) + faces(p, [(0, 1, 2), (0, 2, 7), (0, 9, 9)]))
    binary("be_index_out_of_range_quad.ply", True,
           lambda b, d: f"byte {b + 48 + 17 + 1 + 4}: face 1: vertex index -1 is out of range",
           mesh_lines(4, 2), lambda p: verts(p, TRI) + faces(p, [(0, 1, 2, 3), (0, -1, 2, 3)]))
    binary("le_cut_short_quad.ply", False,
           lambda b, d: f"byte {len(d)}: face 1: the file ends within this record",
           mesh_lines(4, 2), lambda p: verts(p, TRI) + faces(p, [(0, 1, 2, 3), (0, 1, 2, 3)]),
           cut=2)
    binary("be_cut_short_triangles.ply", True,
           lambda b, d: "line 8: 2 'face' records of at least 13 bytes need 26 bytes, but only 25",
           mesh_lines(4, 2), lambda p: verts(p, TRI) + faces(p, [(0, 1, 2), (0, 2, 3)]), cut=1)
    binary("le_trailing_garbage.ply", False,
           lambda b, d: f"byte {b + 48 + 26}: 1 byte after the last element the header declares",
           mesh_lines(4, 2), lambda p: verts(p, TRI) + faces(p, [(0, 1, 2), (0, 2, 3)]) + b"\n")
    binary("be_two_vertex_face.ply", True,
           lambda b, d: f"byte {b + 48 + 13}: face 1: a face needs at least 3 vertices, got 2",
           mesh_lines(4, 3),
           lambda p: verts(p, TRI) + faces(p, [(0, 1, 2), (0, 2), (0, 1, 2, 3, 0, 1, 2)]))
    binary("le_huge_face_count.ply", False,
           lambda b, d: "line 8: 4000000000 'face' records of at least 13 bytes",
           mesh_lines(4, 4000000000), lambda p: verts(p, TRI) + faces(p, [(0, 1, 2)]))
    binary("be_negative_list_count.ply", True,
           lambda b, d: f"byte {b + 48 + 26}: material 0: negative list count -1",
           mesh_lines(4, 2, ["element material 1", "property list char int name"]),
           lambda p: verts(p, TRI) + faces(p, [(0, 1, 2), (0, 2, 3)]) + p("b", -1) + p("4i", 1, 2, 3, 4))
    # the header runs into the body: no end_header line
    text = header("binary_little_endian", "line 10: the header is not ASCII text", mesh_lines(4, 2))
    body = verts(lambda f, *v: struct.pack("<" + f, *v), TRI)
    write("le_no_end_header.ply", text.replace("end_header\n", "").encode() + body)
    # valid: a quad and a triangle, extra properties of several types, an element to skip
    lines = ["element vertex 5", "property double x", "property uchar red", "property double y",
             "property float nz", "property double z",
             "element face 2", "property uchar flags", "property list uint8 uint32 vertex_index",
             "element material 1", "property list uchar uchar name", "property float shininess"]
    vs = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0), (0, 2, 0.5)]
    for big, name in [(False, "valid_binary_le.ply"), (True, "valid_binary_be.ply")]:
        binary(name, big, lambda b, d: "- (renders)", lines,
               lambda p: b"".join(p("dBdfd", x, 7, y, 1.0, z) for x, y, z in vs)
               + p("B", 1) + p("B4I", 4, 0, 1, 2, 3) + p("B", 0) + p("B3I", 3, 3, 2, 4)
               + p("B", 3) + b"abc" + p("f", 0.5))


ascii_fixtures()
binary_fixtures()
