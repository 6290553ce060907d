#!/usr/bin/env python3
"""Writes the small seed corpora of the fuzz targets (fuzz/corpus/<target>/): a few valid
files of each format, a few broken ones, and a few meshes for the pipeline target.
Run from anywhere:  python3 fuzz/make_seeds.py
"""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def write(target, name, data):
    folder = os.path.join(HERE, "corpus", target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


TETRA = [(0, 0, 0), (10, 0, 0), (0, 10, 0), (0, 0, 10)]
TETRA_FACES = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]

# --- ply_ascii: whole files
write("ply_ascii", "tetra.ply",
      "ply\nformat ascii 1.0\ncomment made by make_seeds.py\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
      + "".join("%g %g %g\n" % v for v in TETRA) + "".join("3 %d %d %d\n" % f for f in TETRA_FACES))
write("ply_ascii", "attributes.ply",
      "ply\nformat ascii 1.0\ncomment TextureFile tex.png\nobj_info scanner\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
      "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n"
      "property float quality\nelement face 2\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
      "0 0 0 0 0 1 255 0 0 255 0.5\n1 0 0 0 0 1 0 255 0 255 0.5\n0 1 0 0 0 1 0 0 255 255 1\n1 1 0 0 0 1 9 9 9 255 1e-3\n"
      "3 0 1 2 6 0 0 1 0 0 1\n4 1 3 2 0 8 0 0 1 0 1 1 0 1\n0 1\n")
write("ply_ascii", "points.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n-1.5e2 2 3\n4 5 6\n7 8 9\n")
write("ply_ascii", "binary.ply",
      b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      b"element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<B3i", 3, 0, 1, 2))

# --- ply_binary: first byte chooses the header (see sherd_fuzz::ply_binary), the rest is the body
body0 = b"".join(struct.pack("<3f", *v) for v in TETRA[:4]) + b"".join(struct.pack("<B3i", 3, *f) for f in TETRA_FACES[:2])
write("ply_binary", "float_xyz", b"\x00" + body0)
body1 = b"".join(struct.pack(">3d3f3B", *v, 0, 0, 1, 200, 100, 50) for v in TETRA) + b"".join(struct.pack(">B3I", 3, *f) for f in TETRA_FACES[:2])
write("ply_binary", "big_endian", b"\x01" + body1)
body2 = b"".join(struct.pack("<4f", *v, 0.5) for v in TETRA) + b"".join(struct.pack("<B3iB6f", 3, *f, 6, 0, 0, 1, 0, 0, 1) for f in TETRA_FACES[:2])
write("ply_binary", "texcoords", b"\x02" + body2)
body3 = b"".join(struct.pack("<3h", *v) for v in TETRA) + b"".join(struct.pack("<i2i", 2, 7, 8) for _ in range(3)) \
    + b"".join(struct.pack("<H3HB", 3, *f, 1) for f in TETRA_FACES[:2])
write("ply_binary", "shorts_and_junk", b"\x03" + body3)

# --- obj_mtl: OBJ, a line "#MTL", then the MTL file
obj = ("mtllib fuzz.mtl\nusemtl clay\no sherd\n" + "".join("v %g %g %g 0.5 0.4 0.3\n" % v for v in TETRA)
       + "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nvn 1 0 0\ns 1\ng part\n"
       + "f 1/1/1 3/2/1 2/3/1\nf 1//2 2//2 4//2\nf -4/-3 -1/-2 -2/-1\nf 2 3 4 1\n")
write("obj_mtl", "textured", obj + "#MTL\nnewmtl clay\nKd 0.8 0.6 0.4\nmap_Kd -s 1 1 1 -bm 0.5 absent texture.png\n")
write("obj_mtl", "plain", "".join("v %g %g %g\n" % v for v in TETRA) + "".join("f %d %d %d\n" % tuple(i + 1 for i in f) for f in TETRA_FACES))
write("obj_mtl", "points_normals", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n")

# --- stl
facets = [(TETRA[a], TETRA[b], TETRA[c]) for a, b, c in TETRA_FACES]
write("stl", "ascii.stl", "solid t\n" + "".join(
    "facet normal 0 0 1\n outer loop\n" + "".join("  vertex %g %g %g\n" % v for v in tri) + " endloop\nendfacet\n" for tri in facets) + "endsolid t\n")
binary = b"solid but binary".ljust(80, b" ") + struct.pack("<I", len(facets))
for tri in facets:
    binary += struct.pack("<3f", 0, 0, 1) + b"".join(struct.pack("<3f", *v) for v in tri) + b"\0\0"
write("stl", "binary.stl", binary)

# --- xyz: first byte even for .xyz, odd for .pts
write("xyz", "xyz3", b"\x00" + b"0 0 0\n1 0 0\n0 1 0\n# comment\n0 0 1\n")
write("xyz", "xyz6", b"\x00" + b"0 0 0 0 0 1\n1,0,0,0,1,0\n0;1;0;1;0;0\n")
write("xyz", "pts", b"\x01" + b"2\n0 0 0 5 1 2 3\n1 1 1 6 4 5 6\n")

# --- pipeline: vertex count, triangle count, int16 coordinates (0.1 mm), corner bytes,
# draw style, an axis. A cylinder patch (what a sherd looks like) and a tetrahedron.
def pipeline_seed(vertices, faces, style, axis):
    out = bytes([(len(vertices) - 3) % 64, (len(faces) - 1) % 130])
    for v in vertices:
        out += struct.pack("<3h", *(int(round(c * 10)) for c in v))
    for f in faces:
        out += bytes(f)
    return out + bytes([style]) + struct.pack("<6h", *axis)

rows, cols, radius = 6, 8, 60.0
patch = [(radius * math.cos(a), radius * math.sin(a), z) for z in (0, 10, 20, 30, 40, 50)[:rows]
         for a in [i * 0.12 for i in range(cols)]]
patch_faces = []
for r in range(rows - 1):
    for c in range(cols - 1):
        i = r * cols + c
        patch_faces += [(i, i + 1, i + cols), (i + 1, i + cols + 1, i + cols)]
write("pipeline", "cylinder_patch", pipeline_seed(patch[:64], [f for f in patch_faces if max(f) < 64][:130], 1, (0, 0, 1, 0, 0, 0)))
write("pipeline", "tetra", pipeline_seed(TETRA, TETRA_FACES, 63, (1, 1, 1, 5, 5, 5)))
