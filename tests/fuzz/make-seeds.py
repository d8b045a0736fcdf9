#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora (tests/fuzz/corpus/<target>/) and the inputs that once
crashed, hung or fooled scanpick (tests/fuzz/regressions/<target>/).

Each seed is a small well-formed file in the formats scanpick writes, prefixed by the byte with
which the target chooses its reader (see tests/fuzz/Fuzz*.cpp). Usage:
  tests/fuzz/make-seeds.py [DEMO_OUT]
DEMO_OUT (default demo-output) is a `scanpick-cli demo --out` folder whose ground truth and
results files become the JSON seeds."""
import json
import pathlib
import struct
import sys
import zlib

HERE = pathlib.Path(__file__).resolve().parent
DEMO = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "demo-output")


def write(folder, name, data):
    path = HERE / folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data if isinstance(data, bytes) else data.encode("latin-1"))


def pcd_header(fields, size, typ, count, width, height, data):
    return (f"# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS {fields}\nSIZE {size}\n"
            f"TYPE {typ}\nCOUNT {count}\nWIDTH {width}\nHEIGHT {height}\n"
            f"VIEWPOINT 0 0 0 1 0 0 0\nPOINTS {int(width) * int(height)}\nDATA {data}\n").encode()


POINTS = [(10.0, 20.0, 700.0), (11.0, 20.0, 701.0), (float("nan"),) * 3, (12.0, 21.0, 702.5)]
BOX_V = [(0, 0, 0), (10, 0, 0), (10, 20, 0), (0, 20, 0), (0, 0, 30), (10, 0, 30), (10, 20, 30),
         (0, 20, 30)]
BOX_F = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5),
         (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]


def cloud_seeds():
    binary = pcd_header("x y z", "4 4 4", "F F F", "1 1 1", 2, 2, "binary") + b"".join(
        struct.pack("<3f", *p) for p in POINTS)
    write("corpus/cloud", "binary-organized.pcd", b"\0" + binary)
    ascii_ = pcd_header("x y z normal_x normal_y normal_z rgb", "4 4 4 4 4 4 4", "F F F F F F U",
                        "1 1 1 1 1 1 1", 4, 1, "ascii") + b"".join(
        b"%g %g %g 0 0 1 %d\n" % (*p, 0x102030) for p in POINTS)
    write("corpus/cloud", "ascii-normals-rgb.pcd", b"\0" + ascii_)
    doubles = pcd_header("x y z", "8 8 8", "F F F", "1 1 1", 4, 1, "binary") + b"".join(
        struct.pack("<3d", *p) for p in POINTS)
    write("corpus/cloud", "binary-double.pcd", b"\0" + doubles)
    ply = (b"ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty "
           b"float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar "
           b"blue\nend_header\n" + b"".join(struct.pack("<3f3B", *p, 1, 2, 3) for p in POINTS))
    write("corpus/cloud", "binary.ply", b"\1" + ply)
    ply_ascii = (b"ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double "
                 b"y\nproperty double z\nend_header\n" +
                 b"".join(b"%g %g %g\n" % p for p in POINTS))
    write("corpus/cloud", "ascii.ply", b"\1" + ply_ascii)


def mesh_seeds():
    ply = (f"ply\nformat ascii 1.0\nelement vertex {len(BOX_V)}\nproperty float x\nproperty float "
           f"y\nproperty float z\nelement face {len(BOX_F)}\nproperty list uchar int "
           f"vertex_indices\nend_header\n").encode()
    ply += b"".join(b"%d %d %d\n" % v for v in BOX_V) + b"".join(b"3 %d %d %d\n" % f for f in BOX_F)
    write("corpus/mesh", "box.ply", b"\0" + ply)
    stl = b"solid box\n" + b"".join(
        b"facet normal 0 0 0\nouter loop\n" + b"".join(b"vertex %d %d %d\n" % BOX_V[i] for i in f) +
        b"endloop\nendfacet\n" for f in BOX_F) + b"endsolid box\n"
    write("corpus/mesh", "box.stl", b"\1" + stl)
    obj = b"".join(b"v %d %d %d\n" % v for v in BOX_V) + b"".join(
        b"f %d %d %d\n" % tuple(i + 1 for i in f) for f in BOX_F)
    write("corpus/mesh", "box.obj", b"\2" + obj)
    vtk = (b"# vtk DataFile Version 3.0\nbox\nASCII\nDATASET POLYDATA\nPOINTS 8 float\n" +
           b"".join(b"%d %d %d\n" % v for v in BOX_V) + b"POLYGONS 12 48\n" +
           b"".join(b"3 %d %d %d\n" % f for f in BOX_F))
    write("corpus/mesh", "box.vtk", b"\3" + vtk)


def model_bytes(header_edit=None, version=2):
    points = [p for p in POINTS if p[0] == p[0]]
    block = b"".join(struct.pack("<3f", *p) for p in points)
    header = {"format": "scanpick-model", "version": version, "units": "mm", "name": "seed",
              "teach_scan": "seed.pcd", "source_units": "mm", "diameter_mm": 3.2,
              "T_teach_model": [[1, 0, 0, 11], [0, 1, 0, 20], [0, 0, 1, 701], [0, 0, 0, 1]],
              "params": {}, "features": [{"type": "line", "centre_mm": [0, 0, 0],
                                          "direction": [1, 0, 0], "size_mm": 2.0,
                                          "inlier_count": 3}],
              "grip_points": [{"name": "centre", "position_mm": [0, 0, 0]}],
              "block": {"encoding": "float32-le", "cloud_points": len(points),
                        "cloud_normals": False, "keypoints": 0, "bytes": len(block),
                        "crc32": zlib.crc32(block)}}
    if header_edit:
        header_edit(header)
    header["header_crc32"] = "00000000"
    line = json.dumps(header, sort_keys=True, separators=(",", ":"))
    line = line.replace('"header_crc32":"00000000"',
                        '"header_crc32":"%08x"' % zlib.crc32(line.encode()))
    return line.encode() + b"\n" + block


def model_seeds():
    write("corpus/model", "tiny.spmodel", model_bytes())
    write("regressions/model", "diameter-zero.spmodel",
          model_bytes(lambda h: h.update(diameter_mm=0)))
    write("regressions/model", "zero-transform.spmodel",
          model_bytes(lambda h: h.update(T_teach_model=[[0] * 4] * 4)))
    write("regressions/model", "huge-count.spmodel",
          model_bytes(lambda h: h["block"].update(cloud_points=1e300)))
    write("regressions/model", "deep.spmodel", "{\"a\":" + "[" * 60000 + "]" * 60000 + "}\n")


def json_seeds():
    write("corpus/json", "params.json", b"\0" + json.dumps(
        {"features.ransac_size": 50, "matching.min_coverage": 0.6}).encode())
    for selector, name in ((1, "demo-bin.gt.json"), (2, "demo-results.json")):
        path = DEMO / name
        if path.exists():
            write("corpus/json", name, bytes([selector]) + path.read_bytes())
        else:
            print(f"{path} is missing: run scanpick-cli demo --out {DEMO} first", file=sys.stderr)
    deep = "[" * 60000 + "]" * 60000
    for selector in range(3):
        write("regressions/json", f"deep-{selector}.json", bytes([selector]) + deep.encode())


def regressions():
    head = lambda *a: pcd_header(*a)
    cases = {
        "text.pcd": b"just some notes\n",
        "png.pcd": b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR",
        "one-byte.pcd": b"x",
        "misspelled-fields.pcd": b"VERSION 0.7\nFIELSD x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\n"
                                 b"HEIGHT 1\nDATA ascii\n1 2 3\n",
        "huge-grid.pcd": head("x y z", "4 4 4", "F F F", "1 1 1", 2147483648, 2147483648, "binary")
                         .replace(b"POINTS 4611686014132420609\n", b""),
        "huge-count.pcd": head("x y z", "4 4 4", "F F F", "1 2147483647 1", 1, 1, "binary"),
        "flipped-bit.pcd": head("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "binary") +
                           struct.pack("<6f", 10, 20, 700, 1.67e20, 20, 700),
        "uint8-xyz.pcd": head("x y z", "1 1 1", "U U U", "1 1 1", 1, 1, "binary") + b"abc",
        "malformed-ascii.pcd": head("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "ascii") +
                               b"1 2 3\n4 five\n",
        "compressed-lies.pcd": head("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "binary_compressed")
                               + struct.pack("<2I", 1000000, 24) + b"\0" * 8,
    }
    for name, data in cases.items():
        write("regressions/cloud", name, b"\0" + data)
    huge_ply = (b"ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\n"
                b"property float x\nproperty float y\nproperty float z\nend_header\n" + b"\0" * 12)
    write("regressions/cloud", "huge-elements.ply", b"\1" + huge_ply)
    write("regressions/mesh", "huge-elements.ply", b"\0" + huge_ply)
    write("regressions/mesh", "huge-polygon.vtk",
          b"\3# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 "
          b"0 1 0\nPOLYGONS 1 4\n1000000000000000000 0 1 2\n")


def multipart_seeds():
    # One Range part of 4 x 4 Coord3D_ABC32f points (kind 1, format choice 5), then the same
    # with a Confidence8 part (kind 3, format choice 9); see tests/fuzz/FuzzMultipart.cpp.
    range_ = b"".join(struct.pack("<3f", x, y, 700.0 + x) for y in range(4) for x in range(4))
    write("corpus/multipart", "range.bin", bytes([0, 0, 1, 5, 3, 0, 3, 0]) + range_)
    write("corpus/multipart", "range-confidence.bin",
          bytes([1, 0, 1, 5, 3, 0, 3, 0, 3, 9, 3, 0, 3, 0]) + range_ + b"\x01" * 16 + b"\0" * 176)


def link_seeds():
    # The robot link (tests/fuzz/FuzzLink.cpp, docs/robot-link.md): selector 0 binary requests,
    # 1 a JSON line, 2+ a mixed stream cut into chunks of (selector % 37) + 1 bytes.
    def binary(command, request_id=0, arg=0):
        return b"SPK1" + struct.pack("<7i", command, request_id, arg, 0, 0, 0, 0)
    write("corpus/link", "binary-all.bin", b"\0" + b"".join(binary(c, c) for c in range(1, 6)))
    write("corpus/link", "binary-set-recipe.bin", b"\0" + binary(4, 7, 1))
    write("corpus/link", "json-trigger.txt", b"\1" + b'{"cmd": "trigger", "id": 1}')
    write("corpus/link", "json-set-recipe.txt", b"\1" + b'{"cmd": "set_recipe", "recipe": "a"}')
    # A trigger at a flange pose (command 6, 12 int32): rotation vector, then Euler angles.
    trigger_at = b"SPK1" + struct.pack("<11i", 6, 8, 0, 1000000, -2000000, 5000000,
                                       100000, 0, 900000, 0, 0)
    write("corpus/link", "binary-trigger-at.bin",
          b"\0" + trigger_at + trigger_at[:12] + struct.pack("<i", 1) + trigger_at[16:])
    write("corpus/link", "json-trigger-flange.txt",
          b"\1" + b'{"cmd": "trigger", "id": 2, "flange_pose": [100, -200, 500, 10, 0, 90]}')
    write("corpus/link", "json-trigger-flange-quaternion.txt",
          b"\1" + b'{"cmd": "trigger", "flange_pose": [1, 2, 3, 1, 0, 0, 0]}')
    write("corpus/link", "stream-mixed.bin", b"\5" + b'{"cmd":"status"}\n' + binary(2, 3) +
          b' \r\n{"cmd":"next","id":4}\n' + binary(3)[:20])
    write("regressions/link", "deep.txt", b"\1" + b'{"cmd":' + b"[" * 5000 + b"]" * 5000 + b"}")
    write("regressions/link", "bad-utf8-recipe.txt", b"\1" + b'{"cmd":"set_recipe","recipe":"\xff\xfe"}')
    write("regressions/link", "overlong-line.bin", b"\2{" + b" " * 5000 + b"\n")


cloud_seeds()
link_seeds()
multipart_seeds()
mesh_seeds()
model_seeds()
json_seeds()
regressions()
