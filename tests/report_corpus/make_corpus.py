#!/usr/bin/env python3
"""The report corpus: synthetic sherd scans made independently of `sherd synth`.

    python3 tests/report_corpus/make_corpus.py OUTDIR [--vessels N] [--seed S] [--jobs J] [--quick]

Writes NAME.ply + NAME.truth.json for every fragment, the same files for the same seed.
The project never tunes on this corpus: it only reports on it (see README.md beside this
file). It is made without `src/synth`, on purpose differently from `sherd synth`.
`--without deformation,roughness,scan` is a diagnostic (the same fragments with stages
left out, to tell which one a failure comes from), not the report corpus.

How a vessel becomes scans, in short:
  profile    the mid-line of the wall in the (r, z) half-plane, a monotone cubic (PCHIP)
             curve through family-specific control points, with a thickness that varies
             along it, a base form (flat, ring foot, convex) and a lip form (flat, rounded,
             everted, thickened), turned into a signed distance field on a fine 2D grid;
  fracture   a Voronoi diagram of 15-40 seeds on the mid-surface whose cell boundaries
             are displaced by a smooth random 3D field (rough, slanted break faces);
  meshing    each cell (wall minus its neighbours' half-spaces) is meshed with marching
             cubes on a randomly rotated voxel grid of the fragment's own edge length
             (0.3-2 mm, log-uniform), evaluated only where the wall is;
  throwing   ovality, lobed radial waves and a rim tilt warp the vertices (the truth axis
             stays the ideal one); correlated bumps and white noise roughen the surface;
  scanning   a turntable scan (one or two passes, 2-3 elevations x 8-12 azimuths) keeps
             the vertices some view sees (depth buffer of splatted surface samples) and adds
             noise along the normal that grows with the incidence angle;
  output     a random rigid motion, a PLY (binary, with or without normals, or ASCII) and
             the truth JSON (key names shared with `sherd synth` where they overlap).
"""

from __future__ import annotations

import argparse
import json
import math
import multiprocessing
import os
import sys
import time

# One thread per process: the vessels run in parallel processes, and threaded BLAS only
# adds overhead to the small matrix products used here.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402
from scipy.interpolate import PchipInterpolator  # noqa: E402
from scipy.ndimage import gaussian_filter, map_coordinates  # noqa: E402
from scipy.sparse import coo_matrix  # noqa: E402
from scipy.sparse.csgraph import connected_components  # noqa: E402
from scipy.spatial import ConvexHull, cKDTree  # noqa: E402
from scipy.spatial.transform import Rotation  # noqa: E402
from skimage.measure import marching_cubes  # noqa: E402

from evaluate import sector_bin  # noqa: E402  (one definition of the sector bins)

GENERATOR = "report_corpus"
FAMILIES = ["plate", "carinated_bowl", "jar", "beaker", "bowl"]
GRID_2D_MM = 0.2          # resolution of the profile's signed distance field
MIDLINE_STEP_MM = 0.2     # spacing of the mid-line samples
COARSE_MM = 1.6           # the first, coarse meshing of a cell
MAX_FACES = 600_000       # a finer fragment is coarsened to about this
MIN_FACES = 300           # smaller fragments are dropped
MIN_EXTENT_MM = 15.0      # ... and so are fragments smaller across than this
PIXEL_MM = 0.6            # depth-buffer pixel of the simulated scanner
MAX_INCIDENCE_DEG = 78.0  # the scanner loses surfaces seen more obliquely
DEFAULT_VESSELS = 12
QUICK_VESSELS = 3
QUICK_KEEP = 0.55         # share of the quick vessels' fragments a quick corpus writes


# ----------------------------------------------------------------------------- helpers

def smoothstep(x):
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x)


def smin(a, b, k):
    """Polynomial smooth minimum (union) of two distance fields, blending over k mm."""
    h = np.maximum(k - np.abs(a - b), 0.0) / k
    return np.minimum(a, b) - h * h * k * 0.25


def log_uniform(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


class NoiseGrid:
    """A smooth random field over a box, R^3 -> R^C: white noise on a grid, smoothed by a
    gaussian of `correlation_mm` / 2 and scaled to an RMS of `amplitude` per component,
    read by trilinear interpolation (so |field| never exceeds `bound`). The grid's step is
    a fraction of the correlation length, coarsened to at most `max_side` points a side."""

    def __init__(self, rng, lo, hi, components, correlation_mm, amplitude, max_side=160):
        lo = np.asarray(lo, float) - 2.0 * correlation_mm
        hi = np.asarray(hi, float) + 2.0 * correlation_mm
        step = max(correlation_mm / 2.5, float((hi - lo).max()) / max_side)
        shape = tuple(int(x) for x in np.ceil((hi - lo) / step).astype(int) + 2)
        self.lo, self.step = lo, step
        grids = []
        for _ in range(components):
            g = rng.standard_normal(shape).astype(np.float32)
            g = gaussian_filter(g, sigma=0.5 * correlation_mm / step, mode="wrap")
            g *= amplitude / max(float(g.std()), 1e-9)
            grids.append(g)
        self.grids = grids
        self.bound = float(np.sqrt(sum(g.astype(np.float64) ** 2 for g in grids)).max())

    def __call__(self, p):
        coords = ((p - self.lo) / self.step).T
        return np.stack([map_coordinates(g, coords, order=1, mode="nearest") for g in self.grids], axis=1)


def polar_sector_deg(x, y):
    """360 minus the largest angular gap of the points about the z axis, degrees."""
    if len(x) < 2:
        return 0.0
    th = np.sort(np.arctan2(y, x))
    gaps = np.diff(np.concatenate([th, [th[0] + 2 * np.pi]]))
    return float(360.0 - np.degrees(gaps.max()))


def vertex_normals(v, f):
    """Area-weighted vertex normals (unit; zero for isolated vertices)."""
    fn = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    n = np.zeros_like(v)
    for k in range(3):
        np.add.at(n, f[:, k], fn)
    norm = np.linalg.norm(n, axis=1, keepdims=True)
    return n / np.maximum(norm, 1e-12)


def face_components(nv, f):
    """Connected components of a triangle mesh through shared vertices: (count, label per face)."""
    if len(f) == 0:
        return 0, np.zeros(0, int)
    rows = np.concatenate([f[:, 0], f[:, 1], f[:, 2]])
    cols = np.concatenate([f[:, 1], f[:, 2], f[:, 0]])
    g = coo_matrix((np.ones(len(rows), np.int8), (rows, cols)), shape=(nv, nv))
    n, lab = connected_components(g, directed=False)
    return n, lab[f[:, 0]]


def compact(v, f, keep_faces, *extra):
    """Keep the given faces and the vertices they use; extra per-vertex arrays follow."""
    f = f[keep_faces]
    used = np.zeros(len(v), bool)
    used[f.ravel()] = True
    remap = -np.ones(len(v), np.int64)
    remap[used] = np.arange(used.sum())
    return (v[used], remap[f]) + tuple(e[used] for e in extra)


def extent_mm(v):
    """The length of the point set along its longest principal direction."""
    c = v - v.mean(axis=0)
    _, _, vt = np.linalg.svd(c[:: max(1, len(c) // 20000)], full_matrices=False)
    proj = c @ vt.T
    return float((proj.max(axis=0) - proj.min(axis=0)).max())


# ----------------------------------------------------------------------------- vessel

class Vessel:
    """One thrown vessel: profile, its 2D signed distance field, measurements, fracture
    seeds and fields, deformation. Everything is drawn from `rng` in a fixed order."""

    def __init__(self, index, design, rng):
        self.index = index
        self.family, self.forms = design[0], design[1:]
        self.rng = rng
        self._design()
        self._sample_midline()
        self._distance_field()
        self._measure()
        self._fracture_design()
        self._deformation_design()
        self._surface_design()

    # -- profile -------------------------------------------------------------------
    def _design(self):
        rng, fam = self.rng, self.family
        # The lip and base forms cycle over the vessels (see vessel_design) so that every
        # form appears in a corpus; the draws below keep the random stream the same length.
        rng.uniform(size=2)
        self.lip_form, self.base_form = self.forms

        t_rim = rng.uniform(3.0, 7.0) if fam != "plate" else rng.uniform(4.5, 8.0)
        t_base = min(10.0, t_rim * rng.uniform(1.15, 1.6))
        self.t_rim, self.t_base = t_rim, t_base
        zf = t_base / 2.0
        self.ring = None
        self.sag = 0.0
        if self.base_form == "ring":
            self.ring_height = rng.uniform(3.0, 7.0)
            zf += self.ring_height
        elif self.base_form == "convex":
            self.sag = rng.uniform(1.5, 4.0)

        # Standing edge radius (outer), and the mid-line knot where the floor ends.
        Rb = {"plate": (50, 90), "carinated_bowl": (30, 70), "jar": (30, 70), "beaker": (25, 50), "bowl": (25, 60)}[fam]
        Rb = rng.uniform(*Rb)
        if self.base_form == "ring":
            ring_w = rng.uniform(4.0, 8.0)
            self.ring = (Rb - ring_w, Rb, self.ring_height + t_base * 0.5)   # r0, r1, top z
            r_e = Rb + rng.uniform(0.0, 8.0) - t_base / 2.0
        else:
            r_e = Rb - 0.25 * t_base
        z_e = zf + self.sag

        # The floor: from the base centre to the base edge (convex: rising towards it).
        fl = np.linspace(0.0, 1.0, 5)
        floor = [(r_e * x, zf + self.sag * x * x) for x in fl[:-1]]
        heel = [(r_e, z_e)]

        if fam == "plate":
            H = rng.uniform(70, 100)
            z_top = H - t_rim / 2.0
            alpha = math.radians(rng.uniform(25, 40))
            dz = z_top - z_e
            dr = dz / math.tan(alpha)
            gamma = rng.uniform(1.2, 1.6)
            wall = [(r_e + dr * f, z_e + dz * f ** gamma) for f in (0.2, 0.45, 0.7, 1.0)]
        elif fam == "bowl":
            Rr = rng.uniform(100, 170)
            H = max(70.0, min(320.0, Rr * rng.uniform(0.55, 0.75)))
            z_top = H - t_rim / 2.0
            incurve = rng.uniform(0.0, 0.04) * Rr
            phis = np.linspace(0.0, np.pi / 2, 8)[1:]
            wall = [(r_e + (Rr - t_rim / 2 - r_e) * math.sin(p) - incurve * max(0.0, math.sin(2 * p - np.pi / 2)) ** 2 * (p > np.pi / 4),
                     z_e + (z_top - z_e) * (1 - math.cos(p))) for p in phis]
        elif fam == "carinated_bowl":
            Rr = rng.uniform(80, 150)
            H = rng.uniform(70, 130)
            z_top = H - t_rim / 2.0
            hc = z_e + (z_top - z_e) * rng.uniform(0.3, 0.55)
            inward = rng.uniform() < 0.6
            Rc = Rr * (rng.uniform(1.05, 1.2) if inward else rng.uniform(0.85, 0.95))
            Rc = max(Rc, r_e + 25.0)
            lower_dir = np.array([Rc - r_e, hc - z_e])
            lower_dir /= np.linalg.norm(lower_dir)
            upper_dir = np.array([Rr - t_rim / 2 - Rc, z_top - hc])
            upper_dir /= np.linalg.norm(upper_dir)
            c = np.array([Rc, hc])
            wall = [(r_e + 0.55 * (Rc - r_e), z_e + 0.3 * (hc - z_e)),
                    tuple(c - 3.0 * lower_dir), tuple(c), tuple(c + 3.0 * upper_dir),
                    tuple(c + 0.5 * (np.array([Rr - t_rim / 2, z_top]) - c) + np.array([0.6, 0.0])),
                    (Rr - t_rim / 2, z_top)]
        elif fam == "jar":
            H = rng.uniform(150, 320)
            z_top = H - t_rim / 2.0
            Rm = float(np.clip(H * rng.uniform(0.33, 0.48), 80, 150))
            hm = z_e + (z_top - z_e) * rng.uniform(0.38, 0.55)
            Rn = Rm * rng.uniform(0.35, 0.55)
            hn = z_e + (z_top - z_e) * rng.uniform(0.82, 0.9)
            Rt = Rn + rng.uniform(2.0, 8.0)
            lower = [(r_e + (Rm - r_e) * math.sin(p), z_e + (hm - z_e) * (1 - math.cos(p)))
                     for p in np.linspace(0, np.pi / 2, 6)[1:]]
            upper = [(Rm - (Rm - Rn) * (1 - math.cos(p)), hm + (hn - hm) * math.sin(p))
                     for p in np.linspace(0, 0.85 * np.pi / 2, 6)[1:]]
            neck = [(Rn, hn + 0.25 * (z_top - hn)), (Rn + 0.35 * (Rt - Rn), hn + 0.65 * (z_top - hn)), (Rt, z_top)]
            wall = lower + upper + neck
        elif fam == "beaker":
            H = rng.uniform(110, 260)
            z_top = H - t_rim / 2.0
            Rt = r_e * rng.uniform(1.02, 1.5)
            bulge = rng.uniform(0.0, 6.0)
            wall = [(r_e + 0.6, z_e + 3.0)] + [
                (r_e + (Rt - r_e) * f ** 1.5 + bulge * math.sin(np.pi * f), z_e + 3.0 + (z_top - z_e - 3.0) * f)
                for f in (0.2, 0.45, 0.7, 1.0)]
        else:
            raise ValueError(fam)

        knots = floor + heel + wall
        # The lip: everted lips turn outwards past the wall top.
        self.evert = None
        if self.lip_form == "everted":
            e = rng.uniform(5.0, 14.0)
            beta = math.radians(rng.uniform(5.0, 45.0))
            end = np.array(knots[-1])
            prev = np.array(knots[-2])
            tdir = (end - prev) / np.linalg.norm(end - prev)
            mid_dir = tdir + np.array([math.cos(beta), math.sin(beta)])
            mid_dir /= np.linalg.norm(mid_dir)
            p1 = end + 0.45 * e * mid_dir
            p2 = p1 + 0.6 * e * np.array([math.cos(beta), math.sin(beta)])
            knots += [tuple(p1), tuple(p2)]
            self.evert = (e, math.degrees(beta))
        self.knots = np.array(knots, float)
        self.nominal_height = H
        self.r_edge_knot = r_e

    def _sample_midline(self):
        k = self.knots
        u = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(k, axis=0), axis=1))])
        fr, fz = PchipInterpolator(u, k[:, 0]), PchipInterpolator(u, k[:, 1])
        uu = np.linspace(0.0, u[-1], int(u[-1] / 0.02) + 2)
        pts = np.stack([fr(uu), fz(uu)], axis=1)
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
        ss = np.arange(0.0, s[-1], MIDLINE_STEP_MM)
        ss = np.append(ss, s[-1])
        self.mid = np.stack([np.interp(ss, s, pts[:, 0]), np.interp(ss, s, pts[:, 1])], axis=1)
        self.mid[0, 0] = 0.0
        self.s = ss
        self.s_end = float(ss[-1])
        # Where the floor ends: the mid-line's base-edge knot.
        heel_u = u[4]
        self.s_edge = float(np.interp(heel_u, uu, s))
        # Thickness along the mid-line: the base's on the floor, easing to the rim's with a
        # slow ripple; a flat lip widens (or thins) towards its top.
        rng = self.rng
        x = (ss - self.s_edge) / max(1.0, 0.45 * (self.s_end - self.s_edge))
        t = self.t_rim + (self.t_base - self.t_rim) * (1.0 - smoothstep(x))
        ripple = rng.uniform(0.0, 0.06)
        t *= 1.0 + ripple * np.sin(2 * np.pi * ss / rng.uniform(40, 90) + rng.uniform(0, 2 * np.pi)) * (ss > self.s_edge)
        tang = np.gradient(self.mid, axis=0)
        tang /= np.linalg.norm(tang, axis=1, keepdims=True)
        self.tangent = tang
        self.flat_cut = None
        if self.lip_form == "flat":
            alpha = math.atan2(abs(tang[-1, 1]), abs(tang[-1, 0]))   # end slope above horizontal
            width = min(13.0, self.t_rim * rng.uniform(1.05, 1.7))
            want = width * math.sin(alpha)
            w = float(np.clip(want / t[-1] - 1.0, -0.3, 1.0))
            lw = rng.uniform(6.0, 15.0)
            t *= 1.0 + w * smoothstep((ss - (self.s_end - lw)) / lw)
            self.flat_cut = float(self.mid[-1, 1])
        self.t = np.clip(t, 2.5, 14.0)
        self.bead = None
        if self.lip_form == "thickened":
            b = float(np.clip(self.t[-1] * rng.uniform(0.35, 0.6), 1.5, 3.8))
            T = tang[-1]
            N = np.array([T[1], -T[0]])            # outward normal of the mid-line
            centre = self.mid[-1] - T * (1.6 * b + 0.3) + N * (self.t[-1] / 2.0 + 0.15 * b)
            self.bead = (centre, T, N, 1.6 * b, b)
        lip_len = {"flat": 3.0, "rounded": 3.0}.get(self.lip_form, 0.0)
        if self.lip_form == "everted":
            lip_len = self.evert[0] + 3.0
        if self.lip_form == "thickened":
            lip_len = 2 * self.bead[3] + 3.0
        self.s_lip = self.s_end - lip_len

    def _distance_field(self):
        """The wall's signed distance field (negative inside) on a 2D (z, r) grid, and
        the mid-line parameter s of each grid point's nearest mid-line point."""
        g = GRID_2D_MM
        rmax = float(self.mid[:, 0].max() + self.t.max() + 12.0)
        zmax = float(self.mid[:, 1].max() + self.t.max() + 12.0)
        self.z0 = -6.0
        nr = int(rmax / g) + 2
        nz = int((zmax - self.z0) / g) + 2
        rr = np.arange(nr) * g
        zz = self.z0 + np.arange(nz) * g
        R, Z = np.meshgrid(rr, zz, indexing="xy")        # shape (nz, nr)
        q = np.stack([R.ravel(), Z.ravel()], axis=1)
        tree = cKDTree(self.mid)
        _, j = tree.query(q, workers=1)
        best_d = np.full(len(q), np.inf)
        best_s = np.zeros(len(q))
        m = len(self.mid)
        for a_off in (-1, 0):
            a = np.clip(j + a_off, 0, m - 2)
            pa, pb = self.mid[a], self.mid[a + 1]
            ab = pb - pa
            tt = np.clip(np.einsum("ij,ij->i", q - pa, ab) / np.einsum("ij,ij->i", ab, ab), 0.0, 1.0)
            d = np.linalg.norm(q - (pa + ab * tt[:, None]), axis=1)
            sv = self.s[a] + tt * (self.s[a + 1] - self.s[a])
            better = d < best_d
            best_d[better] = d[better]
            best_s[better] = sv[better]
        thick = np.interp(best_s, self.s, self.t)
        f = best_d - thick / 2.0
        if self.ring is not None:
            r0, r1, ztop = self.ring
            cr = 0.8
            c = np.array([(r0 + r1) / 2, ztop / 2])
            hsz = np.array([(r1 - r0) / 2 - cr, ztop / 2 - cr])
            dq = np.abs(q - c) - hsz
            box = np.linalg.norm(np.maximum(dq, 0.0), axis=1) + np.minimum(dq.max(axis=1), 0.0) - cr
            f = smin(f, box, 1.0)
        if self.bead is not None:
            centre, T, N, a, b = self.bead
            d = q - centre
            u, v = d @ T, d @ N
            ell = (np.sqrt((u / a) ** 2 + (v / b) ** 2) - 1.0) * b
            f = smin(f, ell, 0.8)
        if self.flat_cut is not None:
            f = np.maximum(f, Z.ravel() - self.flat_cut)
        # The convex underside and the flat floor keep the solid above z = 0 at r = 0.
        self.F = f.reshape(nz, nr).astype(np.float64)
        self.S = best_s.reshape(nz, nr)
        self.rr, self.zz = rr, zz

    def wall_sdf(self, p):
        r = np.hypot(p[:, 0], p[:, 1])
        coords = np.stack([(p[:, 2] - self.z0) / GRID_2D_MM, r / GRID_2D_MM])
        return map_coordinates(self.F, coords, order=1, mode="nearest")

    def s_of(self, p):
        r = np.hypot(p[:, 0], p[:, 1])
        iz = np.clip(np.rint((p[:, 2] - self.z0) / GRID_2D_MM).astype(int), 0, self.F.shape[0] - 1)
        ir = np.clip(np.rint(r / GRID_2D_MM).astype(int), 0, self.F.shape[1] - 1)
        return self.S[iz, ir]

    def _outer_crossing(self, cell_mask):
        """The largest radius where the solid, restricted to `cell_mask`, ends (per grid
        row, the sub-cell crossing of the field's zero), or None."""
        F = self.F
        solid = (F < 0) & cell_mask
        best = None
        rows = np.nonzero(solid.any(axis=1))[0]
        for iz in rows:
            i = np.nonzero(solid[iz])[0].max()
            if i + 1 >= F.shape[1]:
                continue
            f0, f1 = F[iz, i], F[iz, i + 1]
            r = self.rr[i] + GRID_2D_MM * (f0 / (f0 - f1) if f1 > f0 else 0.0)
            best = r if best is None else max(best, r)
        return best

    def _measure(self):
        solid = self.F < 0
        zrows = np.nonzero(solid.any(axis=1))[0]
        self.z_min = float(self.zz[zrows.min()])
        self.z_max = float(self.zz[zrows.max()])
        self.height = self.z_max - self.z_min
        lipzone = self.S >= self.s_lip
        self.rim_radius = self._outer_crossing(lipzone)
        top_rows = (self.zz >= self.z_max - 0.5)[:, None] & np.ones_like(solid)
        self.rim_top_radius = self._outer_crossing(top_rows & lipzone)
        edge_z = self.z_min + self.sag + 0.5
        low = (self.zz <= edge_z)[:, None] & (self.S <= self.s_edge + 3.0 * self.t_base)
        self.base_radius = self._outer_crossing(low & np.ones_like(solid))
        self.lip_width = None
        if self.flat_cut is not None:
            iz = int(np.searchsorted(self.zz, self.flat_cut - 0.15)) - 1
            xs = np.nonzero(solid[iz])[0]
            self.lip_width = float((xs.max() - xs.min() + 1) * GRID_2D_MM) if len(xs) else None

    # -- fracture -------------------------------------------------------------------
    def _fracture_design(self):
        rng = self.rng
        # Mid-surface area per mid-line sample: 2 pi r ds.
        w = 2 * np.pi * np.maximum(self.mid[:, 0], 0.5) * MIDLINE_STEP_MM
        area = float(w.sum())
        # Sherd size is physical (a few cm whatever the vessel): the cell width is drawn in
        # mm, so large vessels give narrow sectors and small ones wide.
        self.cell_width_mm = rng.uniform(50.0, 90.0)
        k = int(np.clip(round(area / self.cell_width_mm ** 2), 15, 40))
        self.n_seeds = k
        idx = rng.choice(len(w), size=k, p=w / area)
        th = rng.uniform(0, 2 * np.pi, size=k)
        r, z = self.mid[idx, 0], self.mid[idx, 1]
        self.seeds = np.stack([r * np.cos(th), r * np.sin(th), z], axis=1)
        tree = cKDTree(self.seeds)
        nn = min(k, 17)
        _, nb = tree.query(self.seeds, k=nn)
        self.neighbours = nb[:, 1:]
        self.break_amplitude = rng.uniform(0.3, 2.0)
        self.break_fine_mm = rng.uniform(3.0, 6.0)
        self.break_coarse_mm = rng.uniform(12.0, 25.0)

    def break_field(self, rng, lo, hi):
        """The rough break surface's displacement field of one cell (over its box): a fine
        component (3-6 mm correlation) and a coarse one (12-25 mm), RMS together
        `break_amplitude` per component."""
        amp = self.break_amplitude
        fine = min(0.6, 0.35 * amp)
        coarse = math.sqrt(max(amp * amp - fine * fine, 0.01))
        f1 = NoiseGrid(rng, lo, hi, 3, self.break_fine_mm, fine)
        f2 = NoiseGrid(rng, lo, hi, 3, self.break_coarse_mm, coarse, max_side=60)
        return f1, f2

    def cell_sdf(self, i, p, field):
        """Negative inside cell i: the largest signed distance to the bisector planes with
        the neighbouring seeds, taken at the point moved by the cell's break field. The
        move is at most the fields' bound and each bisector distance is 1-Lipschitz, so
        the moved value is only computed where the unmoved one is that close to zero."""
        si = self.seeds[i]
        nb = self.seeds[self.neighbours[i]]
        D = nb - si
        dn = np.linalg.norm(D, axis=1)
        off = (si @ si - np.einsum("ij,ij->i", nb, nb)) / 2.0
        Dn, offn = D.T / dn, off / dn
        f = (p @ Dn + offn).max(axis=1)
        f1, f2 = field
        near = np.abs(f) <= f1.bound + f2.bound
        if near.any():
            pn = p[near]
            q = pn + f1(pn) + f2(pn)
            f[near] = (q @ Dn + offn).max(axis=1)
        return f

    def labels(self, p):
        _, lab = cKDTree(self.seeds).query(p)
        return lab

    def midsurface_samples(self, step=1.5):
        """Points on the mid-surface about `step` mm apart, with their local thickness."""
        idx = np.arange(0, len(self.mid), max(1, int(step / MIDLINE_STEP_MM)))
        pts, th = [], []
        for i in idx:
            r, z = self.mid[i]
            n = max(3, int(math.ceil(2 * np.pi * r / step)))
            a = np.arange(n) * (2 * np.pi / n)
            pts.append(np.stack([r * np.cos(a), r * np.sin(a), np.full(n, z)], axis=1))
            th.append(np.full(n, self.t[i]))
        return np.concatenate(pts), np.concatenate(th)

    # -- deformation and surface --------------------------------------------------------
    def _deformation_design(self):
        rng = self.rng
        self.ovality = rng.uniform(0.0, 0.02)
        self.ovality_angle = rng.uniform(0, np.pi)
        self.waves = []
        for _ in range(2):
            self.waves.append(dict(lobes=int(rng.integers(3, 7)), amplitude=rng.uniform(0.0, 0.006),
                                   phase=rng.uniform(0, 2 * np.pi), power=rng.uniform(0.5, 1.5)))
        self.tilt = math.radians(rng.uniform(0.0, 0.6))
        self.tilt_azimuth = rng.uniform(0, 2 * np.pi)

    def deform(self, p):
        x, y, z = p[:, 0], p[:, 1], p[:, 2]
        th = np.arctan2(y, x)
        h = np.clip(z / self.height, 0.0, 1.2)
        k = 1.0 + self.ovality * np.cos(2 * (th - self.ovality_angle))
        for w in self.waves:
            k = k + w["amplitude"] * h ** w["power"] * np.cos(w["lobes"] * th + w["phase"])
        out = np.empty_like(p)
        out[:, 0] = x * k
        out[:, 1] = y * k
        out[:, 2] = z + math.tan(self.tilt) * (x * math.cos(self.tilt_azimuth) + y * math.sin(self.tilt_azimuth)) * h * h
        return out

    def _surface_design(self):
        rng = self.rng
        self.roughness = rng.uniform(0.05, 0.3)
        # Most of it as gentle bumps (4-10 mm across: a median normal tilt of 1-5 degrees),
        # the rest per vertex.
        self.bump_mm = rng.uniform(4.0, 10.0)
        self.white = min(0.3 * self.roughness, 0.04)
        self.bump_sigma = math.sqrt(self.roughness ** 2 - self.white ** 2)

    def deformation_record(self):
        return dict(
            ovality=self.ovality,
            ovality_angle_deg=math.degrees(self.ovality_angle),
            waves=[dict(lobes=w["lobes"], amplitude_fraction=w["amplitude"], phase_deg=math.degrees(w["phase"]),
                        height_power=w["power"]) for w in self.waves],
            rim_tilt_deg=math.degrees(self.tilt),
            rim_tilt_azimuth_deg=math.degrees(self.tilt_azimuth),
        )


# ----------------------------------------------------------------------------- meshing

def eval_grid(vessel, cell, field, rot, origin, h, shape):
    """The fragment field max(wall, cell) on a voxel grid: point (i,j,k) lies at
    rot @ (origin + h*(i,j,k)) in the vessel frame. The wall's distance is first taken on
    every 4th point; fine points all of whose coarse corners lie far outside the wall are
    left at a positive value, the others are evaluated, and the cell part only where the
    wall is within 1.5 voxels."""
    shape = tuple(int(x) for x in shape)
    m = 4 if min(shape) >= 12 else 1
    thr = 1.1 * m * h * math.sqrt(3.0) + 1.5 * h
    if m > 1:
        cs = tuple((n - 1) // m + 2 for n in shape)
        ci = [np.arange(n) * (m * h) for n in cs]
        CX, CY, CZ = np.meshgrid(*ci, indexing="ij")
        cp = (np.stack([CX.ravel(), CY.ravel(), CZ.ravel()], axis=1) + origin) @ rot.T
        far = (vessel.wall_sdf(cp) > thr).reshape(cs)
        far_cell = far[:-1, :-1, :-1] & far[1:, :-1, :-1] & far[:-1, 1:, :-1] & far[:-1, :-1, 1:] \
            & far[1:, 1:, :-1] & far[1:, :-1, 1:] & far[:-1, 1:, 1:] & far[1:, 1:, 1:]
        ix, iy, iz = (np.arange(n) // m for n in shape)
        mask = ~far_cell[np.ix_(ix, iy, iz)]
        idx = np.nonzero(mask)
    else:
        idx = tuple(a.ravel() for a in np.meshgrid(*[np.arange(n) for n in shape], indexing="ij"))
    vol = np.full(shape, thr, np.float32)
    chunk = 400_000
    for c0 in range(0, len(idx[0]), chunk):
        ii = tuple(a[c0:c0 + chunk] for a in idx)
        g = np.stack(ii, axis=1) * h + origin
        p = g @ rot.T
        f = vessel.wall_sdf(p)
        near = f < 1.5 * h
        if near.any():
            f[near] = np.maximum(f[near], vessel.cell_sdf(cell, p[near], field))
        vol[ii] = f
    return vol


def mesh_cell(vessel, cell, field, rot, h, points_grid_frame, margin):
    """Marching cubes of the fragment field over the bounding box of `points_grid_frame`
    (+ margin). Returns vertices in the vessel frame, faces (outward), and whether the
    solid touched the box (a too-small box)."""
    lo = points_grid_frame.min(axis=0) - margin
    hi = points_grid_frame.max(axis=0) + margin
    shape = tuple(int(x) for x in np.ceil((hi - lo) / h).astype(int) + 1)
    vol = eval_grid(vessel, cell, field, rot, lo, h, shape)
    touched = bool((vol[0] < 0).any() or (vol[-1] < 0).any() or (vol[:, 0] < 0).any() or (vol[:, -1] < 0).any()
                   or (vol[:, :, 0] < 0).any() or (vol[:, :, -1] < 0).any())
    vol[0], vol[-1], vol[:, 0], vol[:, -1], vol[:, :, 0], vol[:, :, -1] = h, h, h, h, h, h
    if vol.min() >= 0:
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64), touched
    verts, faces, _, _ = marching_cubes(vol, 0.0, spacing=(h, h, h), allow_degenerate=False)
    verts = (verts + lo) @ rot.T
    faces = faces.astype(np.int64)
    a = verts[faces]
    if np.einsum("ij,ij->i", a[:, 0], np.cross(a[:, 1], a[:, 2])).sum() < 0:
        faces = faces[:, ::-1].copy()
    return verts, faces, touched


# ----------------------------------------------------------------------------- scanning

def random_rotation(rng):
    return Rotation.from_quat(rng.normal(size=4)).as_matrix()


def rotation_taking(a, b):
    """A rotation matrix taking unit vector a onto unit vector b."""
    a = a / np.linalg.norm(a)
    b = b / np.linalg.norm(b)
    v = np.cross(a, b)
    c = float(a @ b)
    if c < -0.999999:
        axis = np.cross(a, [1.0, 0, 0])
        if np.linalg.norm(axis) < 1e-6:
            axis = np.cross(a, [0, 1.0, 0])
        axis /= np.linalg.norm(axis)
        return Rotation.from_rotvec(np.pi * axis).as_matrix()
    vx = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + vx + vx @ vx / (1.0 + c)


def resting_pose(v, down, rng):
    """A pose resting on the convex-hull facet that faces most nearly `down` (a unit
    direction in the fragment's frame), turned at random about the vertical. Returns the
    rotation and the lift putting the lowest point on the table z = 0."""
    sub = v[:: max(1, len(v) // 30000)]
    hull = ConvexHull(sub)
    normals = hull.equations[:, :3]
    facet = int(np.argmax(normals @ down))
    rot = rotation_taking(normals[facet], np.array([0.0, 0.0, -1.0]))
    spin = Rotation.from_rotvec([0, 0, rng.uniform(0, 2 * np.pi)]).as_matrix()
    rot = spin @ rot
    lift = -float((v @ rot.T)[:, 2].min())
    return rot, lift


def splat_points(v, f, edge):
    """Vertices plus barycentric samples of the faces, dense enough for PIXEL_MM."""
    k = int(np.clip(math.ceil(1.4 * edge / PIXEL_MM), 1, 6))
    if k == 1:
        return v
    pts = [v]
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    for i in range(k + 1):
        for j in range(k + 1 - i):
            if (i, j) in ((0, 0), (k, 0), (0, k)):
                continue
            u, w = i / k, j / k
            pts.append(a * (1 - u - w) + b * u + c * w)
    return np.concatenate(pts)


def scan_views(rng):
    n_el = int(rng.integers(2, 4))
    elevations = np.sort(rng.uniform([10, 30, 52][:n_el], [22, 45, 68][:n_el]))
    n_az = int(rng.integers(8, 13))
    az0 = rng.uniform(0, 2 * np.pi)
    views = []
    for el in np.radians(elevations):
        for a in az0 + np.arange(n_az) * 2 * np.pi / n_az:
            views.append(np.array([math.cos(el) * math.cos(a), math.cos(el) * math.sin(a), math.sin(el)]))
    return views, [float(x) for x in elevations], n_az


def visibility(v_pose, n_pose, splats, views, contact_mm):
    """Per vertex: seen by some view, and the smallest incidence angle's cosine. Each view
    is orthographic: a depth buffer of PIXEL_MM pixels holds the nearest splat, and a
    vertex facing the view no more obliquely than MAX_INCIDENCE_DEG is seen when it lies
    within a slope-dependent tolerance of its pixel's depth."""
    best_cos = np.zeros(len(v_pose))
    seen = np.zeros(len(v_pose), bool)
    cos_max = math.cos(math.radians(MAX_INCIDENCE_DEG))
    above = v_pose[:, 2] > contact_mm
    centre = splats.mean(axis=0)
    sp0 = (splats - centre).astype(np.float32)
    vp0 = (v_pose - centre).astype(np.float32)
    rad = float(np.sqrt((sp0.astype(np.float64) ** 2).sum(axis=1).max())) + PIXEL_MM
    n = int(math.ceil(2 * rad / PIXEL_MM)) + 1
    inv = np.float32(1.0 / PIXEL_MM)
    off = np.float32(rad)
    for d in views:
        e1 = np.cross(d, [0.0, 0.0, 1.0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(d, e1)
        basis = np.stack([e1, e2, -d], axis=1).astype(np.float32)   # u, v, depth (smaller = nearer)
        cosang = n_pose @ d
        cand = np.nonzero((cosang > cos_max) & above)[0]
        if len(cand) == 0:
            continue
        sp = sp0 @ basis
        lin = ((sp[:, 0] + off) * inv).astype(np.int64) * n + ((sp[:, 1] + off) * inv).astype(np.int64)
        zbuf = np.full(n * n, np.inf, np.float32)
        np.minimum.at(zbuf, lin, sp[:, 2])
        vp = vp0[cand] @ basis
        vlin = ((vp[:, 0] + off) * inv).astype(np.int64) * n + ((vp[:, 1] + off) * inv).astype(np.int64)
        c = cosang[cand]
        tanang = np.sqrt(np.maximum(1.0 - c * c, 0.0)) / np.maximum(c, 1e-3)
        tol = 0.25 + PIXEL_MM * np.minimum(tanang, 3.0)
        ok = vp[:, 2] <= zbuf[vlin] + tol
        idx = cand[ok]
        seen[idx] = True
        best_cos[idx] = np.maximum(best_cos[idx], c[ok])
    return seen, best_cos


def simulate_scan(v, f, edge, rng):
    """A turntable scan: which vertices survive (seen by some view of one or two passes)
    and the cosine of their best incidence. The fragment is put down lying on a hull
    facet, or (some single passes) propped on its edge in putty."""
    n = vertex_normals(v, f)
    c = v - v.mean(axis=0)
    _, _, vt = np.linalg.svd(c[:: max(1, len(c) // 20000)], full_matrices=False)
    thin = vt[2]                     # the wall's normal, roughly
    long_axis = vt[0]
    two_pass = bool(rng.uniform() < 0.5)
    if two_pass:
        mode = "two_pass"
    else:
        mode = "single_pass_lying" if rng.uniform() < 0.6 else "single_pass_propped"
    # Which side of the wall is convex: the vertices bulge away from their centroid there.
    side = np.sign(np.mean(((c @ thin) ** 3))) or 1.0
    convex_dir = side * thin         # points to the convex side (roughly)
    splats = splat_points(v, f, edge)
    seen = np.zeros(len(v), bool)
    best = np.zeros(len(v))
    passes = []
    if mode == "single_pass_propped":
        down_list = [long_axis * (1 if rng.uniform() < 0.5 else -1)]
        contact = rng.uniform(2.0, 5.0)
    else:
        first = convex_dir if rng.uniform() < 0.7 else -convex_dir
        down_list = [first, -first] if two_pass else [first]
        contact = 0.4
    for down in down_list:
        rot, lift = resting_pose(v, down, rng)
        vp = v @ rot.T
        vp[:, 2] += lift
        np_ = n @ rot.T
        sp = splats @ rot.T
        sp[:, 2] += lift
        views, elevations, n_az = scan_views(rng)
        s, b = visibility(vp, np_, sp, views, contact)
        seen |= s
        best = np.maximum(best, b)
        passes.append(dict(elevations_deg=elevations, azimuths=n_az))
    # Dropouts: small patches the scanner missed (dark inclusions, glints) in some scans.
    dropouts = 0
    if rng.uniform() < 0.4:
        dropouts = int(rng.integers(1, 5))
        tree = cKDTree(v)
        for c in rng.integers(0, len(v), size=dropouts):
            seen[tree.query_ball_point(v[c], rng.uniform(1.0, 4.0))] = False
    return seen, best, n, dict(mode=mode, passes=passes, contact_mm=contact, dropouts=dropouts)


# ----------------------------------------------------------------------------- fragments

def classify(vessel, ideal):
    s = vessel.s_of(ideal)
    lip = s >= vessel.s_lip
    has_lip = int(lip.sum()) >= 5
    reaches_edge = float(s.min()) <= vessel.s_edge + 1.0
    has_wall = float(s.max()) >= vessel.s_edge + max(5.0, vessel.t_base)
    if has_lip and reaches_edge:
        part = "rim_to_base"
    elif has_lip:
        part = "rim"
    elif reaches_edge:
        part = "base" if has_wall else "flat"
    else:
        part = "body"
    return part, lip, s


def make_fragments(vessel, cell, rng, mid_pts, mid_lab, mid_thick):
    """All fragments (connected pieces) of one Voronoi cell; a list of dicts with the mesh
    in the vessel frame and its facts."""
    sel = mid_lab == cell
    if sel.sum() < 3:
        return []
    edge = log_uniform(rng, 0.3, 2.0)
    rot = random_rotation(rng)
    cp = mid_pts[sel]
    reach = float(mid_thick[sel].max()) / 2 + 3.0 * COARSE_MM + 6.0
    field = vessel.break_field(rng, cp.min(axis=0) - reach - 10.0, cp.max(axis=0) + reach + 10.0)
    pts_g = cp @ rot                     # grid frame (rot maps grid -> vessel)
    margin = reach + field[0].bound + field[1].bound
    hc = max(COARSE_MM, edge)
    for _ in range(3):
        v, f, touched = mesh_cell(vessel, cell, field, rot, hc, pts_g, margin)
        if not touched:
            break
        margin *= 1.5
    if len(f) == 0:
        return []
    if extent_mm(v) < MIN_EXTENT_MM:
        return []
    h = edge
    if edge < hc:
        est = len(f) * (hc / edge) ** 2
        if est > MAX_FACES:
            h = hc * math.sqrt(len(f) / MAX_FACES)
        if h < hc * 0.95:
            fine_pts = v @ rot
            v, f, _ = mesh_cell(vessel, cell, field, rot, h, fine_pts, 2.0 * hc)
        else:
            h = hc
    else:
        h = hc
    ncomp, lab = face_components(len(v), f)
    out = []
    for c in range(ncomp):
        keep = lab == c
        if keep.sum() < MIN_FACES:
            continue
        cv, cf = compact(v, f, keep)
        if extent_mm(cv) < MIN_EXTENT_MM:
            continue
        out.append(dict(v=cv, f=cf, edge=h, edge_drawn=edge))
    return out


def finish_fragment(vessel, frag, rng, without=()):
    """Warp, roughen, scan, measure; None when too little survives. `without` (a
    diagnostic, not the report corpus) names the stages to leave out: "deformation",
    "roughness", "scan" (holes and scanner noise). The same random draws are made."""
    ideal, f = frag["v"], frag["f"]
    v = ideal.copy() if "deformation" in without else vessel.deform(ideal)
    n = vertex_normals(v, f)
    bumps = NoiseGrid(rng, ideal.min(axis=0), ideal.max(axis=0), 1, vessel.bump_mm, vessel.bump_sigma)
    bump = bumps(ideal)[:, 0] + rng.normal(0.0, vessel.white, size=len(v))
    if "roughness" not in without:
        v = v + n * bump[:, None]
    seen, best_cos, n2, scan = simulate_scan(v, f, frag["edge"], rng)
    if "scan" in without:
        seen[:] = True
        best_cos[:] = 1e9
        scan["mode"] = "none"
    keep_face = seen[f].all(axis=1)
    holes = bool((~keep_face).any())
    area = np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1) / 2
    seen_fraction = float(area[keep_face].sum() / area.sum())
    v, f, ideal, best_cos, n2 = compact(v, f, keep_face, ideal, best_cos, n2)
    # Scanner software drops small floating islands.
    ncomp, lab = face_components(len(v), f)
    if ncomp > 1:
        counts = np.bincount(lab, minlength=ncomp)
        keep = counts[lab] >= max(30, 0.02 * counts.max())
        if not keep.all():
            v, f, ideal, best_cos, n2 = compact(v, f, keep, ideal, best_cos, n2)
    if len(f) < MIN_FACES or extent_mm(v) < MIN_EXTENT_MM:
        return None
    sigma = np.minimum(0.03 / np.maximum(best_cos, 1e-3), 0.12)   # (0 for an ideal surface)
    v = v + n2 * (rng.normal(size=len(v)) * sigma)[:, None]
    part, lip, s = classify(vessel, ideal)
    x, y = v[:, 0], v[:, 1]
    sector = polar_sector_deg(x, y)
    rim_sector = polar_sector_deg(x[lip], y[lip]) if part in ("rim", "rim_to_base") else None
    thick = float(np.median(np.interp(s, vessel.s, vessel.t)))
    return dict(v=v, f=f, part=part, sector=sector, rim_sector=rim_sector, height=float(v[:, 2].max() - v[:, 2].min()),
                thickness=thick, holes=holes, seen_fraction=seen_fraction, scan=scan, edge=frag["edge"],
                edge_drawn=frag["edge_drawn"], z_mean=float(v[:, 2].mean()))


# ----------------------------------------------------------------------------- output

def write_ply(path, v, f, normals=None, ascii=False):
    nv, nf = len(v), len(f)
    props = ["property float x", "property float y", "property float z"]
    if normals is not None:
        props += ["property float nx", "property float ny", "property float nz"]
    fmt = "ascii" if ascii else "binary_little_endian"
    header = "\n".join(["ply", f"format {fmt} 1.0", f"comment generated by {GENERATOR} (tests/report_corpus)",
                        "comment units mm", f"element vertex {nv}"] + props +
                       [f"element face {nf}", "property list uchar int vertex_indices", "end_header"]) + "\n"
    cols = v if normals is None else np.concatenate([v, normals], axis=1)
    with open(path, "wb") as fh:
        fh.write(header.encode("ascii"))
        if ascii:
            lines = [" ".join(f"{x:.5f}" for x in row) for row in cols.astype(np.float32).astype(np.float64)]
            fh.write(("\n".join(lines) + "\n").encode("ascii"))
            fh.write(("\n".join(f"3 {a} {b} {c}" for a, b, c in f) + "\n").encode("ascii"))
        else:
            fh.write(np.ascontiguousarray(cols, dtype="<f4").tobytes())
            rec = np.zeros(nf, dtype=[("n", "u1"), ("i", "<i4", (3,))])
            rec["n"] = 3
            rec["i"] = f
            fh.write(rec.tobytes())


LIP_FORMS = ["flat", "rounded", "everted", "thickened"]
BASE_FORMS = ["flat", "ring", "convex"]


def vessel_design(seed, count):
    """(family, lip form, base form) of each vessel: each list cycles in a seeded order
    (the first five vessels cover the five families, the first four the lip forms, the
    first three the base forms); the cycles' lengths differ, so the combinations vary."""
    r = np.random.default_rng([seed, 999])
    fam, lip, base = r.permutation(len(FAMILIES)), r.permutation(len(LIP_FORMS)), r.permutation(len(BASE_FORMS))
    return [(FAMILIES[fam[i % 5]], LIP_FORMS[lip[i % 4]], BASE_FORMS[base[i % 3]]) for i in range(count)]


def build_vessel(args):
    seed, vi, design, outdir, quick, without = args
    family = design[0]
    t0 = time.time()
    rng = np.random.default_rng([seed, vi])
    vessel = Vessel(vi, design, rng)
    mid_pts, mid_thick = vessel.midsurface_samples()
    mid_lab = vessel.labels(mid_pts)
    records = []
    fi = -1      # the piece's number in the vessel; pieces dropped later leave gaps
    for cell in range(vessel.n_seeds):
        crng = np.random.default_rng([seed, vi, cell])
        pieces = make_fragments(vessel, cell, crng, mid_pts, mid_lab, mid_thick)
        for pi, piece in enumerate(pieces):
            fi += 1
            prng = np.random.default_rng([seed, vi, cell, pi, 7])
            # The quick corpus writes a fixed subset of the same fragments (the draw is
            # made either way, so that the files are the same).
            if prng.uniform() > QUICK_KEEP and quick:
                continue
            frag = finish_fragment(vessel, piece, prng, without)
            if frag is None:
                continue
            name = f"rc{seed}_v{vi:02d}_c{cell:02d}{'abcdefgh'[pi] if pi < 8 else pi}"
            records.append(write_fragment(outdir, name, vessel, frag, seed, vi, fi, cell, prng, without))
    return dict(vessel_index=vi, family=family, seconds=time.time() - t0, fragments=records,
                n_seeds=vessel.n_seeds)


def write_fragment(outdir, name, vessel, frag, seed, vi, fi, cell, rng, without=()):
    rot = random_rotation(rng)
    tr = rng.normal(size=3)
    tr *= rng.uniform(0, 200.0) / np.linalg.norm(tr)
    v = frag["v"] @ rot.T + tr
    has_normals = bool(rng.uniform() < 0.5)
    ascii = bool(rng.uniform() < 0.125)
    normals = vertex_normals(v, frag["f"]) if has_normals else None
    write_ply(os.path.join(outdir, name + ".ply"), v, frag["f"], normals, ascii)
    point = rot @ np.array([0.0, 0.0, frag["z_mean"]]) + tr
    direction = rot @ np.array([0.0, 0.0, 1.0])
    has_lip = frag["part"] in ("rim", "rim_to_base")
    has_base = frag["part"] in ("base", "rim_to_base", "flat")
    truth = {
        "axis": {"point": [float(x) for x in point], "direction": [float(x) for x in direction]},
        "axis_point_height_mm": frag["z_mean"],
        "part": frag["part"],
        "sector_angle_deg": frag["sector"],
        "rim_sector_angle_deg": frag["rim_sector"],
        "rim_radius_mm": vessel.rim_radius if has_lip else None,
        "base_radius_mm": vessel.base_radius if has_base else None,
        "height_mm": frag["height"],
        "generator": GENERATOR,
        "family": vessel.family,
        "lip_form": vessel.lip_form,
        "base_form": vessel.base_form,
        "vessel_index": vi,
        "fragment_index": fi,
        "cell_index": cell,
        "seed": seed,
        "edge_mm": frag["edge"],
        "edge_drawn_mm": frag["edge_drawn"],
        "faces": int(len(frag["f"])),
        "vertices": int(len(frag["v"])),
        "roughness_mm": 0.0 if "roughness" in without else vessel.roughness,
        "roughness_correlation_mm": vessel.bump_mm,
        "roughness_white_mm": vessel.white,
        "wall_thickness_mm": frag["thickness"],
        "has_normals": has_normals,
        "ascii": ascii,
        "holes": frag["holes"],
        "seen_area_fraction": frag["seen_fraction"],
        "scan": frag["scan"],
        "deformation": None if "deformation" in without else vessel.deformation_record(),
        "left_out": sorted(without),
        "break_amplitude_mm": vessel.break_amplitude,
        "vessel_height_mm": vessel.height,
        "vessel_rim_radius_mm": vessel.rim_radius,
        "vessel_rim_top_radius_mm": vessel.rim_top_radius,
        "vessel_base_radius_mm": vessel.base_radius,
        "flat_lip_width_mm": vessel.lip_width,
        "vessel_seeds": vessel.n_seeds,
        "motion": {"rotation_matrix": rot.tolist(), "translation_mm": [float(x) for x in tr]},
        "definitions": {
            "rim_radius_mm": "largest radius of the undeformed lip (its outer edge, as a radius chart reads it)",
            "base_radius_mm": "largest radius of the undeformed underside within 0.5 mm of its standing edge level",
            "axis": "the ideal vessel's axis, direction from base to rim; point at the fragment's mean height",
        },
    }
    with open(os.path.join(outdir, name + ".truth.json"), "w") as fh:
        json.dump(truth, fh, indent=1)
    return dict(name=name, part=frag["part"], sector=frag["sector"], faces=int(len(frag["f"])), holes=frag["holes"])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("outdir")
    ap.add_argument("--vessels", type=int, default=None, help=f"number of vessels (default {DEFAULT_VESSELS}; {QUICK_VESSELS} with --quick)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="the first 3 vessels, a fixed share of their fragments")
    ap.add_argument("--without", default="",
                    help="diagnostic only, not the report corpus: the same fragments with stages left out, "
                         "a comma list of deformation, roughness, scan (holes and scanner noise)")
    a = ap.parse_args(argv)
    count = a.vessels if a.vessels is not None else (QUICK_VESSELS if a.quick else DEFAULT_VESSELS)
    os.makedirs(a.outdir, exist_ok=True)
    designs = vessel_design(a.seed, count)
    without = tuple(sorted(w for w in a.without.split(",") if w))
    unknown = set(without) - {"deformation", "roughness", "scan"}
    if unknown:
        ap.error(f"--without: unknown stage(s) {', '.join(sorted(unknown))}")
    tasks = [(a.seed, vi, designs[vi], a.outdir, a.quick, without) for vi in range(count)]
    t0 = time.time()
    results = []

    def report(r):
        results.append(r)
        print(f"vessel {r['vessel_index']:2d} {r['family']:15s} {len(r['fragments']):3d} fragments "
              f"{r['seconds']:6.1f} s", flush=True)

    if a.jobs <= 1:
        for t in tasks:
            report(build_vessel(t))
    else:
        with multiprocessing.get_context("fork").Pool(a.jobs) as pool:
            for r in pool.imap_unordered(build_vessel, tasks):
                report(r)
    frags = [f for r in results for f in r["fragments"]]
    parts, bins = {}, {}
    for f in frags:
        parts[f["part"]] = parts.get(f["part"], 0) + 1
        b = sector_bin(f["sector"])
        bins[b] = bins.get(b, 0) + 1
    print(f"{len(frags)} fragments from {count} vessels in {time.time() - t0:.1f} s -> {a.outdir}")
    print("parts: " + ", ".join(f"{k} {parts.get(k, 0)}" for k in ["rim", "base", "body", "rim_to_base", "flat"]))
    print("sectors: " + ", ".join(f"{k} {bins.get(k, 0)}" for k in ["<20", "20-40", "40-90", ">=90"]))
    print(f"with holes: {sum(f['holes'] for f in frags)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
