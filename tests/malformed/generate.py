#!/usr/bin/env python3
"""Writes the malformed-file corpus of tests/malformed/ and its table expected.tsv.

Each case is (file name, kind, expected substring, content): kind "error" means reading
must fail with a message containing the file name and the substring; kind "warning" means
reading succeeds with a warning containing the substring; kind "repair" means reading
succeeds and, after repair with the default options, the read and repair reports have
the listed field=value pairs (the mesh is then given to the automatic orientation, which
must answer, error or not, without panicking; values are JSON, or plain strings, and pairs
are separated by "; "); kind "aux" is a file another case refers to. tests/io_malformed.rs
reads the table; run this script again after changing a case:
python3 tests/malformed/generate.py
"""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def ply_header(fmt, *lines):
    return ("ply\nformat %s 1.0\n" % fmt + "".join(l + "\n" for l in lines) + "end_header\n").encode()


XYZ = ("property float x", "property float y", "property float z")
FACES = ("element face %d", "property list uchar int vertex_indices")


def faces(n):
    return (FACES[0] % n, FACES[1])


def le_floats(*values):
    return struct.pack("<%df" % len(values), *values)


def le_face(*indices):
    return struct.pack("<B%di" % len(indices), len(indices), *indices)


TRIANGLE_VERTICES = le_floats(0, 0, 0, 1, 0, 0, 0, 1, 0)
ASCII_TRIANGLE = b"0 0 0\n1 0 0\n0 1 0\n"

# A closed tetrahedron, outward faces, in the forms the cases need.
TETRA_POINTS = [(0, 0, 0), (10, 0, 0), (0, 10, 0), (0, 0, 10)]
TETRA_FACE_LIST = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
TETRA_ASCII = b"".join(b"%d %d %d\n" % p for p in TETRA_POINTS)
TETRA_FACES_ASCII = b"".join(b"3 %d %d %d\n" % f for f in TETRA_FACE_LIST)
TETRA_OBJ = b"".join(b"v %d %d %d\n" % p for p in TETRA_POINTS) + b"".join(b"f %d %d %d\n" % tuple(i + 1 for i in f) for f in TETRA_FACE_LIST)
TETRA_TRIANGLES = [tuple(TETRA_POINTS[i] for i in f) for f in TETRA_FACE_LIST]


def stl_ascii(triangles):
    facets = b"".join(b"facet normal 0 0 0\nouter loop\n" + b"".join(b"vertex %g %g %g\n" % v for v in t) + b"endloop\nendfacet\n" for t in triangles)
    return b"solid s\n" + facets + b"endsolid s\n"


def png_chunks(ihdr, idat):
    """A PNG file with these IHDR and IDAT payloads (CRCs right, content as given)."""
    def chunk(kind, payload):
        return struct.pack(">I", len(payload)) + kind + payload + struct.pack(">I", zlib.crc32(kind + payload))
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", idat) + chunk(b"IEND", b"")

cases = [
    # --- PLY: header ---
    ("empty.ply", "error", "the file is empty", b""),
    ("png_named_ply.ply", "error", "this is a PNG image", b"\x89PNG\r\n\x1a\n" + bytes(40)),
    ("zip_named_ply.ply", "error", "this is a ZIP archive", b"PK\x03\x04" + bytes(40)),
    ("not_ply.ply", "error", "not a PLY file", b"hello world\nthis is text\n"),
    ("no_end_header.ply", "error", "no end_header", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"),
    ("no_format.ply", "error", "no format line", b"ply\nelement vertex 0\nproperty float x\nend_header\n"),
    ("unknown_format.ply", "error", "unknown format", b"ply\nformat binary_middle_endian 1.0\nend_header\n"),
    ("unknown_type.ply", "error", 'unknown property type "float128"', ply_header("ascii", "element vertex 1", "property float128 x")),
    ("property_before_element.ply", "error", "property declared before any element", ply_header("ascii", "property float x")),
    ("negative_count.ply", "error", "not a non-negative integer", ply_header("ascii", "element vertex -5", *XYZ)),
    ("malformed_element.ply", "error", "malformed element line", ply_header("ascii", "element vertex", *XYZ)),
    ("unknown_keyword.ply", "error", 'unknown header keyword "elemnt"', ply_header("ascii", "elemnt vertex 3", *XYZ)),
    ("non_utf8_header.ply", "error", "header line is not text", b"ply\nformat ascii 1.0\ncomment caf\xe9\xff\nend_header\n"),
    ("float_indices.ply", "error", "must be a list of integers", ply_header("ascii", "element vertex 3", *XYZ, "element face 1", "property list uchar float vertex_indices") + ASCII_TRIANGLE + b"3 0 1 2\n"),
    ("float_list_count.ply", "error", "list counts must be integers", ply_header("ascii", "element vertex 3", *XYZ, "element face 1", "property list float int vertex_indices")),
    ("no_vertex_element.ply", "error", "no vertex element", ply_header("ascii", "element point 1", *XYZ) + b"0 0 0\n"),
    ("no_z.ply", "error", "no z property", ply_header("ascii", "element vertex 1", "property float x", "property float y") + b"0 0\n"),
    ("no_vertex_indices.ply", "error", "no vertex_indices list", ply_header("ascii", "element vertex 3", *XYZ, "element face 1", "property uchar flags") + ASCII_TRIANGLE + b"1\n"),
    ("huge_face_count.ply", "error", "declares 1000000000000 face elements", ply_header("binary_little_endian", "element vertex 3", *XYZ, *faces(10**12)) + TRIANGLE_VERTICES + le_face(0, 1, 2)),
    # --- PLY: lying counts, checked before allocating ---
    ("huge_count_binary.ply", "error", "declares 1000000000000 vertex elements", ply_header("binary_little_endian", "element vertex 1000000000000", *XYZ) + TRIANGLE_VERTICES),
    ("huge_count_ascii.ply", "error", "declares 1000000000000 vertex elements", ply_header("ascii", "element vertex 1000000000000", *XYZ) + ASCII_TRIANGLE),
    ("lying_face_count.ply", "error", "declares 1000 face elements", ply_header("binary_little_endian", "element vertex 3", *XYZ, *faces(1000)) + TRIANGLE_VERTICES + le_face(0, 1, 2)),
    ("huge_list_count.ply", "error", "list length 4000000000 is impossible", ply_header("binary_little_endian", "element vertex 3", *XYZ, "element face 1", "property list uint int vertex_indices") + TRIANGLE_VERTICES + struct.pack("<I", 4000000000) + struct.pack("<3i", 0, 1, 2)),
    ("negative_list_count.ply", "error", "list length -1 is impossible", ply_header("binary_little_endian", "element vertex 3", *XYZ, "element face 1", "property list char int vertex_indices") + TRIANGLE_VERTICES + struct.pack("<b3i", -1, 0, 1, 2)),
    ("huge_empty_element.ply", "warning", "element junk (1000000000000 entries) skipped", ply_header("ascii", "element vertex 3", *XYZ, "element junk 1000000000000") + ASCII_TRIANGLE),
    # --- PLY: truncated bodies ---
    ("truncated_binary_face.ply", "error", "face 1 of 2", ply_header("binary_little_endian", "element vertex 3", *XYZ, *faces(2)) + TRIANGLE_VERTICES + le_face(0, 1, 2) + b"\x03\x00"),
    ("truncated_binary_list.ply", "error", "list length 3 is impossible", ply_header("binary_little_endian", "element vertex 3", *XYZ, *faces(1)) + TRIANGLE_VERTICES + le_face(0, 1, 2)[:9]),
    ("truncated_binary_face_property.ply", "error", "the file ends here", ply_header("binary_little_endian", "element vertex 3", *XYZ, *faces(2), "property float quality") + TRIANGLE_VERTICES + le_face(0, 1, 2) + le_floats(0.5) + le_face(2, 1, 0)),
    ("truncated_ascii.ply", "error", "the file ends here", ply_header("ascii", "element vertex 3", *XYZ) + b"0.000 0.000 0.000\n1.000 0.000 0.000\n"),
    ("missing_values_ascii.ply", "error", "line ends before all the properties", ply_header("ascii", "element vertex 3", *XYZ) + b"0.0 0.0 0.0\n1.0 0.0\n0.0 1.0 0.0\n"),
    ("extra_values_ascii.ply", "error", 'unexpected value "7"', ply_header("ascii", "element vertex 3", *XYZ) + b"0 0 0\n1 0 0 7\n0 1 0\n"),
    # --- PLY: bad values ---
    ("nan_binary.ply", "error", "coordinate y is NaN", ply_header("binary_little_endian", "element vertex 3", *XYZ) + le_floats(0, 0, 0, 1, float("nan"), 0, 0, 1, 0)),
    ("nan_big_endian.ply", "error", "coordinate x is NaN", ply_header("binary_big_endian", "element vertex 1", "property double x", "property double y", "property double z") + struct.pack(">3d", float("nan"), 0, 0)),
    ("inf_ascii.ply", "error", "coordinate z is inf", ply_header("ascii", "element vertex 3", *XYZ) + b"0 0 0\n1 0 inf\n0 1 0\n"),
    ("nan_ascii.ply", "error", "coordinate x is NaN", ply_header("ascii", "element vertex 3", *XYZ) + b"0 0 0\nnan 0 0\n0 1 0\n"),
    ("word_in_ascii.ply", "error", '"abc" is not a number', ply_header("ascii", "element vertex 3", *XYZ) + b"0 0 0\n1 abc 0\n0 1 0\n"),
    ("non_utf8_ascii_body.ply", "error", "is not a number", ply_header("ascii", "element vertex 3", *XYZ) + b"0 0 0\n1 \xff\xfe 0\n0 1 0\n"),
    ("index_out_of_range_binary.ply", "error", "vertex index 7 is out of range", ply_header("binary_little_endian", "element vertex 3", *XYZ, *faces(1)) + TRIANGLE_VERTICES + le_face(0, 1, 7)),
    ("index_out_of_range_ascii.ply", "error", "vertex index 3 is out of range: the file has 3 vertices", ply_header("ascii", "element vertex 3", *XYZ, *faces(1)) + ASCII_TRIANGLE + b"3 0 1 3\n"),
    ("negative_index.ply", "error", "vertex index -1 is out of range", ply_header("ascii", "element vertex 3", *XYZ, *faces(1)) + ASCII_TRIANGLE + b"3 0 -1 2\n"),
    ("fractional_index.ply", "error", '"2.5" is not an integer', ply_header("ascii", "element vertex 3", *XYZ, *faces(1)) + ASCII_TRIANGLE + b"3 0 1 2.5\n"),
    ("texcoord_mismatch.ply", "error", "texcoord has 4 values for a face of 3 corners", ply_header("ascii", "element vertex 3", *XYZ, *faces(1), "property list uchar float texcoord") + ASCII_TRIANGLE + b"3 0 1 2 4 0 0 1 0\n"),
    ("missing_texture.ply", "warning", "texture absent.png", ply_header("ascii", "comment TextureFile absent.png", "element vertex 3", *XYZ, *faces(1), "property list uchar float texcoord") + ASCII_TRIANGLE + b"3 0 1 2 6 0 0 1 0 0 1\n"),
    # --- STL ---
    ("empty.stl", "error", "the file is empty", b""),
    ("short.stl", "error", "too short for a binary STL", bytes(range(20))),
    ("truncated_binary.stl", "error", "declares 10 triangles", bytes(80) + struct.pack("<I", 10) + bytes(100)),
    ("huge_count.stl", "error", "declares 4000000000 triangles", bytes(80) + struct.pack("<I", 4000000000) + bytes(50)),
    ("nan_binary.stl", "error", "coordinate x is NaN", bytes(80) + struct.pack("<I", 1) + le_floats(0, 0, 1, 0, 0, 0, float("nan"), 0, 0, 0, 1, 0) + bytes(2)),
    ("ascii_bad_number.stl", "error", '"1,5", not a number', b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1,5 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n"),
    ("ascii_truncated.stl", "error", "ends inside this facet", b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"),
    ("ascii_two_vertices.stl", "error", "facet has 2 vertices", b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid s\n"),
    ("ascii_garbage.stl", "error", 'unexpected "vertx"', b"solid s\nfacet normal 0 0 1\nouter loop\nvertx 0 0 0\n"),
    ("ascii_no_facets.stl", "error", "contains no facets", b"solid s\nendsolid s\n"),
    # --- OBJ ---
    ("empty.obj", "error", "the file is empty", b""),
    ("jpeg_named_obj.obj", "error", "this is a JPEG image", b"\xff\xd8\xff\xe0" + bytes(40)),
    ("no_vertices.obj", "error", "defines no vertex", b"# only a comment\no nothing\n"),
    ("index_out_of_range.obj", "error", "vertex index 9 is out of range", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
    ("zero_index.obj", "error", "vertex index 0 is out of range", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
    ("negative_too_far.obj", "error", "vertex index -5 is out of range", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -5\n"),
    ("bad_number.obj", "error", 'v value "1,5" is not a number', b"v 0 0 0\nv 1,5 0 0\n"),
    ("nan.obj", "error", "coordinate x is NaN", b"v 0 0 0\nv nan 0 0\n"),
    ("short_vertex.obj", "error", "v has 2 coordinates", b"v 1 2\n"),
    ("uv_out_of_range.obj", "error", "texture coordinate index 5 is out of range", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/5 2/1 3/1\n"),
    ("normal_out_of_range.obj", "error", "normal index 2 is out of range", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n"),
    ("non_utf8.obj", "error", "is not a number", b"v 0 0 0\nv \xff\xfe 0 0\n"),
    ("missing_texture.obj", "warning", "texture missing or unreadable", b"mtllib missing_texture.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl m\nf 1/1 2/1 3/1\n"),
    ("missing_texture.mtl", "aux", "", b"newmtl m\nmap_Kd not_there.jpg\n"),
    ("missing_library.obj", "warning", "material library", b"mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
    # --- XYZ / PTS ---
    ("empty.xyz", "error", "the file is empty", b""),
    ("comments_only.xyz", "error", "contains no points", b"# x y z\n\n# nothing\n"),
    ("five_columns.xyz", "error", "5 values: expected 3", b"0 0 0 1 1\n"),
    ("inconsistent_columns.xyz", "error", "but the first point has a different count", b"0 0 0 0 0 1\n1 1 1\n"),
    ("nan.xyz", "error", "coordinate x is NaN", b"0 0 0\nnan 1 1\n"),
    ("zero_normal.xyz", "error", "has no direction", b"0 0 0 0 0 0\n"),
    ("word.xyz", "error", '"north" is not a number', b"0 0 0\n1 north 1\n"),
    ("negative_count.pts", "error", "point count -3 is not a non-negative integer", b"-3\n0 0 0 1\n"),
    ("binary_garbage.xyz", "error", "is not a number", bytes([0x13, 0x37, 0xC0, 0xDE] * 16)),
    ("unsupported.dae", "error", "unsupported extension", b"<COLLADA/>\n"),
    # --- more lying headers, huge counts, truncation (hardening, issue 10) ---
    ("count_overflows_u64.ply", "error", "not a non-negative integer", ply_header("ascii", "element vertex 99999999999999999999999", *XYZ) + ASCII_TRIANGLE),
    ("huge_face_count_ascii.ply", "error", "declares 1000000000000 face elements", ply_header("ascii", "element vertex 3", *XYZ, *faces(10**12)) + ASCII_TRIANGLE + b"3 0 1 2\n"),
    ("huge_list_count_ascii.ply", "error", "list length 1000000000 is impossible", ply_header("ascii", "element vertex 3", *XYZ, *faces(1)) + ASCII_TRIANGLE + b"1000000000 0 1 2\n"),
    ("truncated_header.ply", "error", "no end_header", b"ply\nformat ascii 1.0\nelement vert"),
    ("truncated_binary_vertex.ply", "error", "declares 3 vertex elements", ply_header("binary_little_endian", "element vertex 3", *XYZ) + TRIANGLE_VERTICES[:20]),
    ("lying_stl_count.stl", "warning", "100 bytes after the 1 triangles ignored", bytes(80) + struct.pack("<I", 1) + (le_floats(0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0) + bytes(2)) * 3),
    ("lying_pts_count.pts", "warning", "declares 1000000 points, the file has 2", b"1000000\n0 0 0 5\n1 1 1 6\n"),
    ("truncated.obj", "error", "v has 2 coordinates", b"v 0 0 0\nv 1 0 0\nv 0 1"),
    ("huge_index.obj", "error", 'vertex index "99999999999999999999" is not an integer', b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n"),
    ("truncated_binary_header.stl", "error", "too short for a binary STL", b"\x00" * 83),
    # --- more NaN and infinity ---
    ("nan_ascii.stl", "error", "coordinate x is NaN", b"solid s\nfacet normal 0 0 1\nouter loop\nvertex nan 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n"),
    ("inf_binary_double.ply", "error", "coordinate z is inf", ply_header("binary_little_endian", "element vertex 1", "property double x", "property double y", "property double z") + struct.pack("<3d", 0, 0, float("inf"))),
    ("nan.pts", "error", "coordinate y is NaN", b"1\n0 nan 0 5\n"),
    ("overflow_to_inf.obj", "error", "coordinate x is inf", b"v 1e999 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
    # --- textures and material libraries that are missing, wrong or hostile ---
    ("texture_is_device.obj", "warning", 'texture_is_device.mtl line 2: texture "/dev/zero" refused, not read: it is an absolute path', b"mtllib texture_is_device.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl m\nf 1/1 2/1 3/1\n"),
    ("texture_is_device.mtl", "aux", "", b"newmtl m\nmap_Kd /dev/zero\n"),
    ("library_is_device.obj", "warning", 'library_is_device.obj line 1: material library "../../../../../../dev/zero" refused, not read: its ".." leads out', b"mtllib ../../../../../../dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
    ("library_is_folder.obj", "warning", "not a regular file but a folder", b"mtllib .\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
    ("corrupt_texture.obj", "warning", "texture missing or unreadable", b"mtllib corrupt_texture.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl m\nf 1/1 2/1 3/1\n"),
    ("corrupt_texture.mtl", "aux", "", b"newmtl m\nmap_Kd corrupt_texture.png\n"),
    ("corrupt_texture.png", "aux", "", png_chunks(struct.pack(">IIBBBBB", 4, 4, 8, 6, 0, 0, 0), b"not zlib data at all")),
    ("huge_texture.ply", "warning", "100000 x 100000 pixels is larger than", ply_header("ascii", "comment TextureFile huge_texture.png", "element vertex 3", *XYZ, *faces(1), "property list uchar float texcoord") + ASCII_TRIANGLE + b"3 0 1 2 6 0 0 1 0 0 1\n"),
    ("huge_texture.png", "aux", "", png_chunks(struct.pack(">IIBBBBB", 100000, 100000, 8, 6, 0, 0, 0), zlib.compress(b"\0" * 64))),
    ("texture_without_uvs.obj", "warning", "the faces have no texture coordinates", b"mtllib texture_without_uvs.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n"),
    ("texture_without_uvs.mtl", "aux", "", b"newmtl m\nmap_Kd absent.png\n"),
    # --- files a scan names outside its folder: refused with a warning (file, line, path), geometry kept ---
    ("mtllib_escapes.obj", "warning", 'mtllib_escapes.obj line 1: material library "../../etc/passwd" refused, not read: its ".." leads out of the scan\'s folder', b"mtllib ../../etc/passwd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
    ("absolute_texture.obj", "warning", 'absolute_texture.mtl line 2: texture "/etc/passwd" refused, not read: it is an absolute path', b"mtllib absolute_texture.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl m\nf 1/1 2/1 3/1\n"),
    ("absolute_texture.mtl", "aux", "", b"newmtl m\nmap_Kd -s 1 1 1 /etc/passwd\n"),
    ("windows_absolute_texture.obj", "warning", 'windows_absolute_texture.mtl line 3: texture "C:/Users/potter/skin.png" refused, not read: it is an absolute path', b"mtllib windows_absolute_texture.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl m\nf 1/1 2/1 3/1\n"),
    ("windows_absolute_texture.mtl", "aux", "", b"# exported on Windows\r\nnewmtl m\r\nmap_Kd C:\\Users\\potter\\skin.png\r\n"),
    ("texture_escapes_via_subfolder.obj", "warning", 'texture_escapes_via_subfolder.mtl line 2: texture "textures/../../../secret.png" refused, not read: its ".." leads out', b"mtllib texture_escapes_via_subfolder.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl m\nf 1/1 2/1 3/1\n"),
    ("texture_escapes_via_subfolder.mtl", "aux", "", b"newmtl m\nmap_Kd textures/../../../secret.png\n"),
    ("texture_outside.ply", "warning", 'texture_outside.ply header line 3: texture "../../../etc/hostname" refused, not read: its ".." leads out', ply_header("ascii", "comment TextureFile ../../../etc/hostname", "element vertex 3", *XYZ, *faces(1), "property list uchar float texcoord") + ASCII_TRIANGLE + b"3 0 1 2 6 0 0 1 0 0 1\n"),
    ("texture_absolute.ply", "warning", 'texture_absolute.ply header line 4: texture "/dev/urandom" refused, not read: it is an absolute path', ply_header("binary_little_endian", "comment made by a hostile scanner", "comment TextureFile /dev/urandom", "element vertex 3", *XYZ) + le_floats(0, 0, 0, 1, 0, 0, 0, 1, 0)),
    ("non_utf8_ply_texture_name.ply", "error", "header line is not text", b"ply\nformat ascii 1.0\ncomment TextureFile t\xe9xture.png\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n"),
    # --- non-UTF-8 names (file names inside files; non-UTF-8 file names are in tests/io_malformed.rs) ---
    ("non_utf8_library_name.obj", "warning", "material library not loaded", b"mtllib caf\xe9\xff.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
    ("non_utf8_texture_name.obj", "warning", "texture missing or unreadable", b"mtllib non_utf8_texture_name.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl m\xff\nf 1/1 2/1 3/1\n"),
    ("non_utf8_texture_name.mtl", "aux", "", b"newmtl m\xff\nmap_Kd t\xe9xture.png\n"),
    ("non_utf8_stl_name.stl", "repair", "format=stl binary; faces_after=1", b"caf\xe9 \xff\xfe solid name".ljust(80, b"\0") + struct.pack("<I", 1) + le_floats(0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0) + bytes(2)),
    # --- degenerate geometry, non-manifold, zero-area faces, duplicated vertices: read,
    # then repaired with the default options; the expected fields of the read and repair
    # reports are listed as field=value ---
    ("duplicated_vertices.ply", "repair", "duplicate_vertices_merged=4; unreferenced_vertices_removed=0; vertices_after=4; faces_after=4; watertight=true", ply_header("ascii", "element vertex 8", *XYZ, *faces(4)) + TETRA_ASCII * 2 + b"3 0 6 5\n3 4 1 7\n3 0 3 6\n3 5 2 7\n"),
    ("zero_area_faces.ply", "repair", "degenerate_faces_removed=2; faces_after=4; watertight=true", ply_header("ascii", "element vertex 5", *XYZ, *faces(6)) + TETRA_ASCII + b"5 0 0\n" + TETRA_FACES_ASCII + b"3 0 1 4\n3 4 1 0\n"),
    ("repeated_corners.obj", "repair", "degenerate_faces_removed=2; faces_after=4; watertight=true", TETRA_OBJ + b"f 1 1 2\nf 3 3 3\n"),
    ("duplicate_faces.stl", "repair", "duplicate_faces_removed=2; faces_after=4; watertight=true", stl_ascii(TETRA_TRIANGLES + TETRA_TRIANGLES[:1] + [tuple(reversed(TETRA_TRIANGLES[1]))])),
    ("non_manifold_edge.ply", "repair", "non_manifold_edge_count=1; non_manifold_edges=[[0, 1]]; watertight=false", ply_header("ascii", "element vertex 5", *XYZ, *faces(3)) + b"0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n"),
    ("non_manifold_vertex.obj", "repair", "non_manifold_vertex_count=1; component_face_counts=[1, 1]", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n"),
    ("debris.ply", "repair", "component_face_counts=[4, 1]", ply_header("ascii", "element vertex 7", *XYZ, *faces(5)) + TETRA_ASCII + b"100 100 100\n101 100 100\n100 101 100\n" + TETRA_FACES_ASCII + b"3 4 5 6\n"),
    ("unreferenced_vertices.obj", "repair", "unreferenced_vertices_removed=3; vertices_after=4", TETRA_OBJ + b"v 5 5 5\nv 6 6 6\nv 7 7 7\n"),
    ("collinear.ply", "repair", "degenerate_faces_removed=2; faces_after=0", ply_header("ascii", "element vertex 4", *XYZ, *faces(2)) + b"0 0 0\n1 1 1\n2 2 2\n3 3 3\n3 0 1 2\n3 1 2 3\n"),
    ("all_one_point.stl", "repair", "faces_after=0", stl_ascii([((1, 2, 3), (1, 2, 3), (1, 2, 3))] * 3)),
    ("single_point.xyz", "repair", "vertices_after=1; faces_after=0", b"1 2 3\n"),
    ("duplicate_points.xyz", "repair", "duplicate_vertices_merged=2; vertices_after=2", b"1 2 3\n1 2 3\n4 5 6\n1 2 3\n"),
    ("tiny_coordinates.ply", "repair", "faces_after=4", ply_header("ascii", "element vertex 4", *XYZ, *faces(4)) + b"0 0 0\n1e-30 0 0\n0 1e-30 0\n0 0 1e-30\n" + TETRA_FACES_ASCII),
    ("huge_coordinates.ply", "repair", "faces_after=4", ply_header("binary_little_endian", "element vertex 4", "property double x", "property double y", "property double z", *faces(4)) + struct.pack("<12d", 0, 0, 0, 1e300, 0, 0, 0, 1e300, 0, 0, 0, 1e300) + b"".join(le_face(*f) for f in TETRA_FACE_LIST)),
    ("polygons.ply", "repair", "polygons_triangulated=2; faces_after=4", ply_header("ascii", "element vertex 6", *XYZ, *faces(2)) + b"0 0 0\n1 0 0\n1 1 0\n0 1 0\n-1 1 0\n-1 0 0\n4 0 1 2 3\n4 0 3 4 5\n" ),
]


def main():
    kept = {name for name, *_ in cases} | {"generate.py", "expected.tsv"}
    for existing in os.listdir(HERE):
        if existing not in kept:
            os.remove(os.path.join(HERE, existing))
    with open(os.path.join(HERE, "expected.tsv"), "w", encoding="utf-8") as table:
        table.write("# file\tkind\texpected substring, or field=value pairs for \"repair\" (written by generate.py)\n")
        for name, kind, expected, content in cases:
            with open(os.path.join(HERE, name), "wb") as f:
                f.write(content)
            table.write("%s\t%s\t%s\n" % (name, kind, expected))


if __name__ == "__main__":
    main()
