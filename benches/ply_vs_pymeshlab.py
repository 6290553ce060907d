"""Loading a 500k-face binary PLY: sherd's reader (through the Python binding, so both
run in the same process) against pymeshlab's `load_new_mesh`, alternately, on the same
file. Reports wall-clock and CPU time (`time.process_time`, all threads of the process):
on a shared machine the wall clock mostly measures waiting for a core, the CPU time what
each reader costs.

    cargo build --release
    target/release/sherd synth D --seed 3 --faces 500000 --part rim
    SHERD_LIBRARY=target/release/libsherd.so python3 benches/ply_vs_pymeshlab.py D/sherd_3_rim.ply [RUNS]

Figures go into BENCHMARKS.md, "PLY reading".
"""
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "bindings", "python"))

import pymeshlab  # noqa: E402
import sherd  # noqa: E402


def timed(load):
    wall, cpu = time.perf_counter(), time.process_time()
    result = load()
    return time.perf_counter() - wall, time.process_time() - cpu, result


def summary(name, samples):
    walls = sorted(s[0] for s in samples)
    cpus = sorted(s[1] for s in samples)
    middle = len(samples) // 2
    print(f"{name:10s} wall best {walls[0]:.4f} s, median {walls[middle]:.4f} s; "
          f"CPU best {cpus[0]:.4f} s, median {cpus[middle]:.4f} s")
    return cpus[middle]


def main():
    path = sys.argv[1]
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 20
    ours, theirs = [], []
    for _ in range(runs):
        wall, cpu, mesh = timed(lambda: sherd.Mesh.read(path))
        ours.append((wall, cpu))
        meshes = pymeshlab.MeshSet()
        wall, cpu, _ = timed(lambda: meshes.load_new_mesh(path))
        theirs.append((wall, cpu))
    assert mesh.vertex_count == meshes.current_mesh().vertex_number()
    assert mesh.face_count == meshes.current_mesh().face_number()
    print(f"{path}: {mesh.vertex_count} vertices, {mesh.face_count} faces, {runs} runs each")
    sherd_cpu = summary("sherd", ours)
    meshlab_cpu = summary("pymeshlab", theirs)
    print(f"pymeshlab / sherd, median CPU time: {meshlab_cpu / sherd_cpu:.2f}")


if __name__ == "__main__":
    main()
