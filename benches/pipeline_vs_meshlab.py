#!/usr/bin/env python3
"""Decimation, sherd against MeshLab (pymeshlab) on the same file: time and peak memory.

    python3 benches/pipeline_vs_meshlab.py [--faces 500000] [--target 20000] [--input SCAN.ply] [--repeat 3]

Without --input, writes a noisy vessel wall of about --faces faces (the same revolved
profile as tests/support/decimation_vessel.rs, with normals and colours, as scans have)
to a temporary binary PLY. Each side runs as its own process under /usr/bin/time -v,
load + decimate + write, so "peak" is the whole process's maximum resident set; the
decimation alone is timed inside each process (CPU and wall). The best of --repeat runs
is kept: the machine may be shared. MeshLab runs at its boundary-, topology- and
normal-preserving settings (as tests/meshlab_decimation.rs compares quality).
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "target", "release", "examples", "decimate_scan")

MESHLAB = r"""
import json, sys, time, pymeshlab
meshes = pymeshlab.MeshSet()
meshes.load_new_mesh(sys.argv[1])
cpu, wall = time.process_time(), time.perf_counter()
meshes.meshing_decimation_quadric_edge_collapse(targetfacenum=int(sys.argv[3]), qualitythr=0.3,
    preserveboundary=True, preservetopology=True, preservenormal=True, optimalplacement=True)
cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
meshes.save_current_mesh(sys.argv[2])
print(json.dumps({"cpu_seconds": cpu, "wall_seconds": wall, "faces": meshes.current_mesh().face_number()}))
"""


def vessel_radius_mm(z):
    return 60.0 + 25.0 * np.sin(0.9 * np.pi * z / 80.0) - 0.1 * z


def write_noisy_vessel(path, faces, noise_mm=0.1, seed=11):
    """The test support's vessel wall (80 mm high, 2.4 rad sector), as a binary PLY."""
    rows = max(2, round((faces / 4.2) ** 0.5))
    columns = max(2, round(2.1 * rows))
    z, theta = np.meshgrid(np.linspace(0, 80.0, rows), np.linspace(0, 2.4, columns), indexing="ij")
    radius = vessel_radius_mm(z) + noise_mm * np.random.default_rng(seed).uniform(-1, 1, z.shape)
    slope = (vessel_radius_mm(z + 1e-4) - vessel_radius_mm(z - 1e-4)) / 2e-4
    normals = np.stack([np.cos(theta), np.sin(theta), -slope], -1)
    normals /= np.linalg.norm(normals, axis=-1, keepdims=True)
    vertex = np.zeros(rows * columns, dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("nx", "<f4"), ("ny", "<f4"),
                                              ("nz", "<f4"), ("red", "u1"), ("green", "u1"), ("blue", "u1")])
    vertex["x"], vertex["y"], vertex["z"] = (radius * np.cos(theta)).ravel(), (radius * np.sin(theta)).ravel(), z.ravel()
    vertex["nx"], vertex["ny"], vertex["nz"] = (normals[..., k].ravel() for k in range(3))
    vertex["red"] = (255 * z / 80.0).ravel().round()
    vertex["green"] = (255 * theta / 2.4).ravel().round()
    vertex["blue"] = 90
    index = np.arange(rows * columns).reshape(rows, columns)
    a, b, c, d = index[:-1, :-1], index[:-1, 1:], index[1:, 1:], index[1:, :-1]
    triangles = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    face = np.zeros(len(triangles), dtype=[("count", "u1"), ("indices", "<i4", (3,))])
    face["count"], face["indices"] = 3, triangles
    header = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(vertex)}\n"
              + "".join(f"property float {n}\n" for n in ("x", "y", "z", "nx", "ny", "nz"))
              + "property uchar red\nproperty uchar green\nproperty uchar blue\n"
              + f"element face {len(face)}\nproperty list uchar int vertex_indices\nend_header\n")
    with open(path, "wb") as out:
        out.write(header.encode())
        out.write(vertex.tobytes())
        out.write(face.tobytes())
    return len(face)


def timed(command):
    """Runs `command` under /usr/bin/time -v: (stdout, peak MiB, process CPU s, process wall s)."""
    run = subprocess.run(["/usr/bin/time", "-v"] + command, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"{command[0]} failed:\n{run.stderr}")
    field = lambda name: re.search(name + r": (.+)", run.stderr).group(1)
    minutes, seconds = field(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\)").rsplit(":", 1)
    wall = float(seconds) + 60 * float(minutes.split(":")[-1])
    cpu = float(field("User time \\(seconds\\)")) + float(field("System time \\(seconds\\)"))
    return run.stdout, int(field(r"Maximum resident set size \(kbytes\)")) / 1024, cpu, wall


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--faces", type=int, default=500_000)
    parser.add_argument("--target", type=int, default=20_000)
    parser.add_argument("--input")
    parser.add_argument("--repeat", type=int, default=3)
    arguments = parser.parse_args()
    subprocess.run(["cargo", "build", "--release", "--quiet", "--example", "decimate_scan"], cwd=ROOT, check=True)
    with tempfile.TemporaryDirectory() as directory:
        source = arguments.input or os.path.join(directory, "vessel.ply")
        if not arguments.input:
            write_noisy_vessel(source, arguments.faces)
        best = {}
        for _ in range(arguments.repeat):
            out, peak, cpu, wall = timed([EXAMPLE, source, os.path.join(directory, "sherd.ply"), str(arguments.target)])
            report = json.loads(out)
            sherd = {"decimate_wall_s": report["elapsed_seconds"], "process_cpu_s": cpu, "process_wall_s": wall,
                     "peak_mib": peak, "faces_in": report["input_faces"], "faces_out": report["output_faces"]}
            out, peak, cpu, wall = timed([sys.executable, "-c", MESHLAB, source, os.path.join(directory, "meshlab.ply"),
                                          str(arguments.target)])
            meshlab = json.loads(out)
            meshlab = {"decimate_wall_s": meshlab["wall_seconds"], "decimate_cpu_s": meshlab["cpu_seconds"],
                       "process_cpu_s": cpu, "process_wall_s": wall, "peak_mib": peak, "faces_out": meshlab["faces"]}
            for name, run in (("sherd", sherd), ("meshlab", meshlab)):
                if name not in best or run["decimate_wall_s"] < best[name]["decimate_wall_s"]:
                    best[name] = run
    s, m = best["sherd"], best["meshlab"]
    print(f"| {s['faces_in']} -> {arguments.target} faces | sherd | MeshLab | MeshLab / sherd |")
    print("|---|---|---|---|")
    for label, key in (("decimation, wall s", "decimate_wall_s"), ("whole process (load, decimate, write), CPU s", "process_cpu_s"),
                       ("whole process, wall s", "process_wall_s"), ("peak resident memory, MiB", "peak_mib")):
        print(f"| {label} | {s[key]:.2f} | {m[key]:.2f} | {m[key] / s[key]:.2f} |")
    print(f"\nfaces out: sherd {s['faces_out']}, MeshLab {m['faces_out']}; MeshLab decimation CPU {m['decimate_cpu_s']:.2f} s")


if __name__ == "__main__":
    main()
