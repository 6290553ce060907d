"""MeshLab's (pymeshlab's) times for the operations benches/mesh_processing.rs measures,
on the same 500k-face rippled torus (1000 x 250 quads, radii 100 and 30, ripple 0.05).

    python3 benches/pymeshlab_bench.py

Each figure is the best of 5 runs of the filter alone (the mesh is copied before each
run, outside the timing). Results go into BENCHMARKS.md, "Mesh processing".
"""
import time

import numpy as np
import pymeshlab


def torus(around=1000, across=250, major=100.0, minor=30.0, ripple=0.05):
    u = np.arange(around) / around * 2 * np.pi
    v = np.arange(across) / across * 2 * np.pi
    uu, vv = np.meshgrid(u, v, indexing="ij")
    r = minor * (1.0 + ripple * np.sin(7 * uu) * np.cos(5 * vv))
    x = (major + r * np.cos(vv)) * np.cos(uu)
    y = (major + r * np.cos(vv)) * np.sin(uu)
    z = r * np.sin(vv)
    vertices = np.stack([x, y, z], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(around), np.arange(across), indexing="ij")
    index = lambda a, b: (a % around) * across + (b % across)
    first = np.stack([index(i, j), index(i + 1, j), index(i + 1, j + 1)], axis=-1).reshape(-1, 3)
    second = np.stack([index(i, j), index(i + 1, j + 1), index(i, j + 1)], axis=-1).reshape(-1, 3)
    faces = np.stack([first, second], axis=1).reshape(-1, 3)  # same order as the Rust fixture
    return vertices, faces.astype(np.int32)


def best_of(mesh, operation, runs=5):
    best = float("inf")
    for _ in range(runs):
        meshes = pymeshlab.MeshSet()
        meshes.add_mesh(pymeshlab.Mesh(vertex_matrix=mesh[0], face_matrix=mesh[1]))
        start = time.perf_counter()
        operation(meshes)
        best = min(best, time.perf_counter() - start)
    return best


def repair(meshes):
    meshes.meshing_remove_duplicate_vertices()
    meshes.meshing_remove_null_faces()
    meshes.meshing_remove_duplicate_faces()
    meshes.meshing_remove_unreferenced_vertices()
    meshes.get_topological_measures()


def main():
    vertices, faces = torus()
    welded = (vertices, faces)
    soup = (vertices[faces.reshape(-1)], np.arange(3 * len(faces), dtype=np.int32).reshape(-1, 3))
    operations = [
        ("repair_welded (dup. vertices, null + dup. faces, unreferenced, topology report)", welded, repair),
        ("repair_soup_1.5M_vertices (same filters)", soup, repair),
        ("repair_soup_tolerance_1e-3 (merge close vertices 1e-3)", soup,
         lambda m: m.meshing_merge_close_vertices(threshold=pymeshlab.PureValue(1e-3))),
        ("topology (get_topological_measures)", welded, lambda m: m.get_topological_measures()),
        ("normals_angle", welded, lambda m: m.compute_normal_per_vertex(weightmode="By Angle")),
        ("normals_area", welded, lambda m: m.compute_normal_per_vertex(weightmode="By Area")),
        ("orient_faces_outward (re-orient coherently)", welded, lambda m: m.meshing_re_orient_faces_coherently()),
        ("laplacian_3_steps_cotangent", welded,
         lambda m: m.apply_coord_laplacian_smoothing(stepsmoothnum=3, cotangentweight=True, boundary=True)),
        ("hc_1_step", welded, lambda m: m.apply_coord_hc_laplacian_smoothing()),
    ]
    print(f"pymeshlab, {len(faces)} faces, {len(vertices)} vertices (soup: {len(soup[0])})")
    for name, mesh, operation in operations:
        print(f"{name}: {best_of(mesh, operation) * 1000:.1f} ms")


if __name__ == "__main__":
    main()
