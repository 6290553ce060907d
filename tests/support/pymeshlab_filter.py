"""Applies one pymeshlab filter to a mesh and writes the resulting vertex positions.

    python3 pymeshlab_filter.py INPUT.ply OUTPUT.txt FILTER_NAME '{"param": value}'

Used by tests/meshlab_smoothing.rs to compare sherd's smoothing with MeshLab's on the
same input; OUTPUT.txt has one "x y z" row per vertex, in the input's vertex order.
"""
import json
import sys

import numpy as np
import pymeshlab


def main():
    source, target, filter_name, parameters = sys.argv[1], sys.argv[2], sys.argv[3], json.loads(sys.argv[4])
    meshes = pymeshlab.MeshSet()
    meshes.load_new_mesh(source)
    getattr(meshes, filter_name)(**parameters)
    np.savetxt(target, meshes.current_mesh().vertex_matrix(), fmt="%.17g")


if __name__ == "__main__":
    main()
