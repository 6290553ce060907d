"""Three vertices on a sherd's rim as a user picks them for the manual orientation, for
the Python and Blender tests (tests/c/pipeline.h does the same in C)."""

import numpy as np


def pick_rim_vertices(positions, oriented_transform):
    """Indices of three vertices on the rim: in the oriented frame of the true axis
    (``oriented_transform``, 4x4, the centroid on +x so the angles do not wrap), the
    highest vertex near the middle of each third of the fragment's angular extent."""
    oriented = positions @ oriented_transform[:3, :3].T + oriented_transform[:3, 3]
    angles = np.arctan2(oriented[:, 1], oriented[:, 0])
    share = 3 * (angles - angles.min()) / (angles.max() - angles.min())
    picked = []
    for third in range(3):
        candidates = np.flatnonzero(np.abs(share - third - 0.5) < 0.3)
        picked.append(int(candidates[np.argmax(oriented[candidates, 2])]))
    return picked
