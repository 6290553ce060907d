#!/usr/bin/env python3
"""Evaluate `sherd orient` on synthetic corpora with known axes.

    python3 tests/report_corpus/evaluate.py CORPUS_DIR [CORPUS_DIR...] [--sherd PATH]
        [--jobs 2] [--refine auto|none|...] [--out results.json] [--markdown table.md]

Runs `PATH orient FILE --json [--refine X]` on every *.ply of the folders (J at a time),
reads each NAME.truth.json beside it (this corpus's, or `sherd synth`'s: both have
`axis`, `part`, `sector_angle_deg`, `rim_radius_mm`), and prints the figures as markdown
tables. All per-fragment rows go to --out. The main figure is the mean point distance of
Wilczek et al. 2018, section 3.1: the vertices are put in the found axis's frame and in
the true axis's frame, superposed by the best rotation about and shift along that axis,
and the mean distance of corresponding vertices is taken; 4 mm is "well oriented".
"""

from __future__ import annotations

import argparse
import atexit
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

THRESHOLD_MM = 4.0
PARTS = ["rim", "base", "body", "rim_to_base", "flat"]
RIMS_AND_BASES = ("rim", "base", "rim_to_base")
SECTOR_BINS = ["<20", "20-40", "40-90", ">=90"]
ANSWER_STATUSES = ("ok", "axis_uncertain", "sense_uncertain")
STATUSES = ["ok", "axis_uncertain", "sense_uncertain", "needs_manual_orientation", "error"]

# ----------------------------------------------------------------------------- PLY

_PLY_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1",
    "short": "i2", "int16": "i2", "ushort": "u2", "uint16": "u2",
    "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
    "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
}


def read_ply_vertices(path):
    """The x, y, z of a PLY's vertices (ASCII or binary, either byte order), float64.
    The vertex element must come first or after elements without list properties."""
    with open(path, "rb") as fh:
        if fh.readline().strip() != b"ply":
            raise ValueError(f"{path}: not a PLY file")
        fmt = None
        elements = []          # [name, count, [(prop name, dtype or ('list', count type, item type))]]
        while True:
            line = fh.readline()
            if not line:
                raise ValueError(f"{path}: header without end_header")
            words = line.decode("ascii", "replace").split()
            if not words:
                continue
            if words[0] == "format":
                fmt = words[1]
            elif words[0] == "element":
                elements.append([words[1], int(words[2]), []])
            elif words[0] == "property":
                if words[1] == "list":
                    elements[-1][2].append((words[4], ("list", words[2], words[3])))
                else:
                    elements[-1][2].append((words[2], _PLY_TYPES[words[1]]))
            elif words[0] == "end_header":
                break
        if fmt == "ascii":
            for name, count, props in elements:
                if name == "vertex":
                    names = [p[0] for p in props]
                    rows = []
                    for _ in range(count):
                        rows.append(fh.readline().split())
                    arr = np.array(rows, dtype=np.float64)
                    return arr[:, [names.index(c) for c in ("x", "y", "z")]]
                for _ in range(count):       # skip an element's lines
                    fh.readline()
            raise ValueError(f"{path}: no vertex element")
        order = "<" if fmt == "binary_little_endian" else ">"
        for name, count, props in elements:
            if any(isinstance(t, tuple) for _, t in props):
                if name == "vertex":
                    raise ValueError(f"{path}: list property in the vertex element")
                raise ValueError(f"{path}: element {name} with a list comes before the vertices")
            dtype = np.dtype([(p, order + t) for p, t in props])
            data = np.frombuffer(fh.read(dtype.itemsize * count), dtype=dtype, count=count)
            if name == "vertex":
                return np.stack([data[c].astype(np.float64) for c in ("x", "y", "z")], axis=1)
        raise ValueError(f"{path}: no vertex element")


# ----------------------------------------------------------------------------- geometry

def unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v)


def axis_frame(vertices, point, direction):
    """Vertex coordinates in a frame with the axis on z (pointing along `direction`)."""
    d = unit(direction)
    helper = np.array([1.0, 0.0, 0.0]) if abs(d[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = unit(np.cross(d, helper))
    e2 = np.cross(d, e1)
    q = vertices - np.asarray(point, dtype=np.float64)
    return np.stack([q @ e1, q @ e2, q @ d], axis=1)


def mean_point_distance(vertices, found, truth):
    """Wilczek et al. 2018, 3.1: the mean distance between the vertices placed under the
    found axis and under the true one, after the rotation about z and the shift along z
    that superpose them best (closed form; the two are independent)."""
    e = axis_frame(vertices, found["point"], found["direction"])
    t = axis_frame(vertices, truth["point"], truth["direction"])
    shift = float(np.mean(t[:, 2] - e[:, 2]))
    angle = math.atan2(float(np.sum(e[:, 0] * t[:, 1] - e[:, 1] * t[:, 0])),
                       float(np.sum(e[:, 0] * t[:, 0] + e[:, 1] * t[:, 1])))
    c, s = math.cos(angle), math.sin(angle)
    moved = np.stack([c * e[:, 0] - s * e[:, 1], s * e[:, 0] + c * e[:, 1], e[:, 2] + shift], axis=1)
    return float(np.mean(np.linalg.norm(moved - t, axis=1)))


def axis_figures(vertices, axis, truth_axis):
    """Distances and angles of a found axis against the truth."""
    df = unit(axis["direction"])
    dt = unit(truth_axis["direction"])
    cosang = float(np.clip(df @ dt, -1.0, 1.0))
    flipped = {"point": axis["point"], "direction": list(-df)}
    d_given = mean_point_distance(vertices, axis, truth_axis)
    d_flipped = mean_point_distance(vertices, flipped, truth_axis)
    return {
        "distance_mm": d_given,
        "line_distance_mm": min(d_given, d_flipped),
        "right_way_up": cosang > 0,
        "line_angle_deg": math.degrees(math.acos(abs(cosang))),
        "directed_angle_deg": math.degrees(math.acos(cosang)),
    }


# ----------------------------------------------------------------------------- running

def sector_bin(deg):
    if deg is None:
        return None
    if deg < 20:
        return "<20"
    if deg < 40:
        return "20-40"
    if deg < 90:
        return "40-90"
    return ">=90"


def run_one(sherd, ply, refine, timeout):
    cmd = [sherd, "orient", str(ply), "--json"]
    if refine:
        cmd += ["--refine", refine]
    t0 = time.monotonic()
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"status": "error", "error": f"timed out after {timeout} s"}, time.monotonic() - t0
    wall = time.monotonic() - t0
    try:
        out = json.loads(proc.stdout)
    except json.JSONDecodeError:
        msg = (proc.stderr or proc.stdout).strip().splitlines()
        return {"status": "error", "error": f"exit {proc.returncode}: {msg[-1] if msg else 'no output'}"}, wall
    if proc.returncode != 0 and out.get("status") in (None, "ok"):
        out["status"] = "error"
    return out, wall


def evaluate_fragment(corpus, ply, sherd, refine, timeout):
    truth_path = ply.with_name(ply.name[: -len(".ply")] + ".truth.json")
    truth = json.loads(truth_path.read_text())
    out, wall = run_one(sherd, ply, refine, timeout)
    status = out.get("status") or "error"
    if status not in STATUSES:
        status = "error" if out.get("error") else status
    row = {
        "corpus": corpus,
        "name": ply.name[: -len(".ply")],
        "part": truth.get("part"),
        "sector_angle_deg": truth.get("sector_angle_deg"),
        "sector_bin": sector_bin(truth.get("sector_angle_deg")),
        "truth_rim_radius_mm": truth.get("rim_radius_mm"),
        "family": truth.get("family") or (truth.get("vessel") or {}).get("shape"),
        "status": status,
        "reason": out.get("reason"),
        "error": out.get("error"),
        "method": out.get("method"),
        "wall_s": wall,
        "timings": out.get("timings") or {},
    }
    axis = out.get("axis")
    row["answer"] = status in ANSWER_STATUSES and axis is not None
    vertices = None
    if row["answer"] or isinstance(out.get("best_guess"), dict):
        vertices = read_ply_vertices(ply)
        row["vertices"] = int(len(vertices))
    if row["answer"]:
        row.update(axis_figures(vertices, axis, truth["axis"]))
        ai = out.get("axis_angle_interval_deg")
        di = out.get("axis_distance_interval_mm")
        row["angle_interval_deg"], row["distance_interval_mm"] = ai, di
        row["angle_interval_holds"] = None if not ai else bool(ai[1] >= row["line_angle_deg"])
        row["distance_interval_holds"] = None if not di else bool(di[1] >= row["line_distance_mm"])
    rim_true = truth.get("rim_radius_mm")
    rim_found = out.get("rim_diameter_mm")
    ri = out.get("rim_diameter_interval_mm")
    row["rim_diameter_mm"] = rim_found
    row["rim_interval_holds"] = None
    if row["answer"] and rim_true and ri:
        row["rim_interval_holds"] = bool(ri[0] <= 2 * rim_true <= ri[1])
    row["rim_error_percent"] = (100.0 * (rim_found - 2 * rim_true) / (2 * rim_true)
                                if row["answer"] and rim_true and rim_found else None)
    # The report corpus also records the radius at the lip's highest point (smaller than
    # the outer edge on rounded and thickened lips): the error against it tells a
    # definition's share of the rim error from the measurement's.
    rim_top = truth.get("vessel_rim_top_radius_mm") if rim_true else None
    row["rim_top_error_percent"] = (100.0 * (rim_found - 2 * rim_top) / (2 * rim_top)
                                    if row["answer"] and rim_top and rim_found else None)
    bg = out.get("best_guess")
    if isinstance(bg, dict) and isinstance(bg.get("axis"), dict):
        figs = axis_figures(vertices, bg["axis"], truth["axis"])
        row["best_guess"] = {k: figs[k] for k in ("distance_mm", "line_distance_mm", "right_way_up", "line_angle_deg")}
    return row


# ----------------------------------------------------------------------------- figures

def frac(k, n):
    return f"{k}/{n} ({100.0 * k / n:.0f}%)" if n else "-"


def pct(values, q):
    return float(np.percentile(values, q)) if len(values) else None


def fmt(x, digits=2, unit=""):
    return "-" if x is None else f"{x:.{digits}f}{unit}"


def oriented(r):
    return (r["status"] in ("ok", "axis_uncertain") and r["answer"] and r["right_way_up"]
            and r["distance_mm"] <= THRESHOLD_MM)


def axis_line(r):
    return r["answer"] and r["line_distance_mm"] <= THRESHOLD_MM


def summarise(rows):
    """The figures of one group of rows, as a dict (also written to --out)."""
    n = len(rows)
    s = {"fragments": n}
    s["oriented"] = sum(oriented(r) for r in rows)
    s["axis_line"] = sum(axis_line(r) for r in rows)
    s["declined"] = sum(not r["answer"] for r in rows)
    ok = [r for r in rows if r["status"] == "ok" and r["answer"]]
    s["ok"] = len(ok)
    s["wrong_and_ok"] = sum(r["distance_mm"] > THRESHOLD_MM or not r["right_way_up"] for r in ok)
    oa = [r for r in rows if r["status"] in ("ok", "axis_uncertain") and r["answer"]]
    s["ok_or_axis_uncertain"] = len(oa)
    s["right_way_up_of_ok_or_axis_uncertain"] = sum(r["right_way_up"] for r in oa)
    answers = [r for r in rows if r["answer"]]
    s["answers"] = len(answers)
    s["median_line_angle_deg"] = pct([r["line_angle_deg"] for r in answers], 50)
    s["median_line_distance_mm"] = pct([r["line_distance_mm"] for r in answers], 50)
    for key in ("angle_interval_holds", "distance_interval_holds", "rim_interval_holds"):
        vals = [r[key] for r in rows if r.get(key) is not None]
        s[key] = [sum(vals), len(vals)]
    rim_ok = [r for r in ok if r["truth_rim_radius_mm"]]
    errs = [abs(r["rim_error_percent"]) for r in rim_ok if r["rim_error_percent"] is not None]
    signed = [r["rim_error_percent"] for r in rim_ok if r["rim_error_percent"] is not None]
    top = [r["rim_top_error_percent"] for r in rim_ok if r.get("rim_top_error_percent") is not None]
    s["rim_top_error_median_percent"] = pct([abs(x) for x in top], 50)
    s["rim_top_error_signed_median_percent"] = pct(top, 50)
    s["rim_ok_with_truth"] = len(rim_ok)
    s["rim_ok_measured"] = len(errs)
    s["rim_error_median_percent"] = pct(errs, 50)
    s["rim_error_p95_percent"] = pct(errs, 95)
    s["rim_error_signed_median_percent"] = pct(signed, 50)
    s["status_counts"] = {st: sum(r["status"] == st for r in rows) for st in STATUSES}
    bg = [r["best_guess"] for r in rows if not r["answer"] and r.get("best_guess")]
    s["declined_with_best_guess"] = len(bg)
    s["best_guess_axis_line"] = sum(b["line_distance_mm"] <= THRESHOLD_MM for b in bg)
    s["best_guess_oriented"] = sum(b["right_way_up"] and b["distance_mm"] <= THRESHOLD_MM for b in bg)
    timing_keys = sorted({k for r in rows for k in r["timings"]})
    s["timings"] = {}
    for k in timing_keys + ["wall_s"]:
        vals = [r["timings"][k] for r in rows if isinstance(r["timings"].get(k), (int, float))] if k != "wall_s" \
            else [r["wall_s"] for r in rows]
        s["timings"][k] = {"median": pct(vals, 50), "p90": pct(vals, 90)}
    s["by_part"] = {}
    for p in PARTS + ["rims_and_bases"]:
        sub = [r for r in rows if (r["part"] in RIMS_AND_BASES if p == "rims_and_bases" else r["part"] == p)]
        s["by_part"][p] = {"n": len(sub), "oriented": sum(oriented(r) for r in sub), "axis_line": sum(axis_line(r) for r in sub),
                           "declined": sum(not r["answer"] for r in sub)}
    s["by_sector"] = {}
    for b in SECTOR_BINS:
        sub = [r for r in rows if r["sector_bin"] == b]
        s["by_sector"][b] = {"n": len(sub), "oriented": sum(oriented(r) for r in sub), "axis_line": sum(axis_line(r) for r in sub),
                             "declined": sum(not r["answer"] for r in sub)}
    return s


def markdown(groups, title):
    """Markdown tables: the summary (one column per group), then by part and by sector."""
    names = list(groups)
    S = {g: summarise(rows) for g, rows in groups.items()}
    lines = [f"### {title}", ""]
    head = "| figure | " + " | ".join(names) + " |"
    lines += [head, "|---" * (len(names) + 1) + "|"]

    def row(label, fn):
        lines.append(f"| {label} | " + " | ".join(fn(S[g]) for g in names) + " |")

    row("fragments", lambda s: str(s["fragments"]))
    row(f"**oriented** (ok/axis_uncertain, right way up, distance <= {THRESHOLD_MM:g} mm)", lambda s: frac(s["oriented"], s["fragments"]))
    row("oriented, rims and bases", lambda s: frac(s["by_part"]["rims_and_bases"]["oriented"], s["by_part"]["rims_and_bases"]["n"]))
    row(f"**axis line** (any answer, line distance <= {THRESHOLD_MM:g} mm)", lambda s: frac(s["axis_line"], s["fragments"]))
    row("declined (needs_manual_orientation or error)", lambda s: frac(s["declined"], s["fragments"]))
    row("wrong and ok: of all fragments", lambda s: frac(s["wrong_and_ok"], s["fragments"]))
    row("wrong and ok: of ok", lambda s: frac(s["wrong_and_ok"], s["ok"]))
    row("right way up, of ok and axis_uncertain", lambda s: frac(s["right_way_up_of_ok_or_axis_uncertain"], s["ok_or_axis_uncertain"]))
    row("median line angle error of answers", lambda s: fmt(s["median_line_angle_deg"], 2, " deg"))
    row("median line distance of answers", lambda s: fmt(s["median_line_distance_mm"], 2, " mm"))
    row("angle interval holds the truth", lambda s: frac(*s["angle_interval_holds"]))
    row("distance interval holds the truth", lambda s: frac(*s["distance_interval_holds"]))
    row("rim diameter interval holds the truth", lambda s: frac(*s["rim_interval_holds"]))
    row("rim diameter error of ok rims: median / p95 (abs)",
        lambda s: f"{fmt(s['rim_error_median_percent'])}% / {fmt(s['rim_error_p95_percent'])}% (n={s['rim_ok_measured']} of {s['rim_ok_with_truth']})")
    row("rim diameter error of ok rims: signed median", lambda s: fmt(s["rim_error_signed_median_percent"], 2, "%"))
    if any(S[g]["rim_top_error_median_percent"] is not None for g in names):
        row("rim diameter error of ok rims against the lip's top radius: median abs / signed",
            lambda s: f"{fmt(s['rim_top_error_median_percent'])}% / {fmt(s['rim_top_error_signed_median_percent'])}%")
    if any(S[g]["declined_with_best_guess"] for g in names):
        row("declined with a best guess: axis line / oriented",
            lambda s: f"{frac(s['best_guess_axis_line'], s['declined_with_best_guess'])} / {frac(s['best_guess_oriented'], s['declined_with_best_guess'])}")
    for st in STATUSES:
        row(f"status {st}", lambda s, st=st: str(s["status_counts"][st]))
    tkeys = [k for k in S[names[0]]["timings"]]
    for k in tkeys:
        row(f"time {k}: median / p90", lambda s, k=k: "-" if k not in s["timings"] or s["timings"][k]["median"] is None
            else f"{s['timings'][k]['median']:.3f} / {s['timings'][k]['p90']:.3f} s")
    lines.append("")
    for g in names:
        s = S[g]
        lines += [f"#### {g}: by part", "", "| part | n | oriented | axis line | declined |", "|---|---|---|---|---|"]
        for p in PARTS + ["rims_and_bases"]:
            b = s["by_part"][p]
            lines.append(f"| {p.replace('_', ' ')} | {b['n']} | {frac(b['oriented'], b['n'])} | {frac(b['axis_line'], b['n'])} | {frac(b['declined'], b['n'])} |")
        lines += ["", f"#### {g}: by sector angle (truth)", "", "| sector | n | oriented | axis line | declined |", "|---|---|---|---|---|"]
        for sb in SECTOR_BINS:
            b = s["by_sector"][sb]
            lines.append(f"| {sb} deg | {b['n']} | {frac(b['oriented'], b['n'])} | {frac(b['axis_line'], b['n'])} | {frac(b['declined'], b['n'])} |")
        lines.append("")
    return "\n".join(lines), S


def binary_stamp(path):
    """The binary's SHA-256, to notice a rebuild during a run."""
    import hashlib
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def default_sherd():
    here = Path(__file__).resolve().parent
    candidate = here.parent.parent / "target" / "release" / "sherd"
    return str(candidate if candidate.exists() else Path("target/release/sherd"))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("corpora", nargs="+", help="folders of NAME.ply + NAME.truth.json")
    ap.add_argument("--sherd", default=None, help="the sherd binary (default: target/release/sherd)")
    ap.add_argument("--jobs", type=int, default=2, help="orient runs at a time")
    ap.add_argument("--refine", default=None, help="passed on as --refine (auto, none, ...); sherd's default when absent")
    ap.add_argument("--out", default=None, help="write the per-fragment rows and the figures here (JSON)")
    ap.add_argument("--markdown", default=None, help="write the tables here too")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds per orient run")
    a = ap.parse_args(argv)
    sherd = a.sherd or default_sherd()
    if not os.path.exists(sherd):
        print(f"no sherd binary at {sherd}", file=sys.stderr)
        return 2
    tasks = []
    for d in a.corpora:
        folder = Path(d)
        label = folder.name or str(folder)
        plys = sorted(p for p in folder.glob("*.ply") if p.with_name(p.name[:-4] + ".truth.json").exists())
        missing = len(list(folder.glob("*.ply"))) - len(plys)
        if missing:
            print(f"{d}: {missing} PLY files without a truth file left out", file=sys.stderr)
        if not plys:
            print(f"{d}: no PLY with a truth file", file=sys.stderr)
        tasks += [(label, p) for p in plys]
    # Run a private copy: a rebuild of the binary during the run must not mix two builds.
    snapshot_dir = tempfile.mkdtemp(prefix="sherd_eval_")
    atexit.register(shutil.rmtree, snapshot_dir, True)
    runner = os.path.join(snapshot_dir, "sherd")
    shutil.copy2(sherd, runner)
    stamp = binary_stamp(runner)
    t0 = time.monotonic()
    rows = []
    with ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        futures = [pool.submit(evaluate_fragment, label, p, runner, a.refine, a.timeout) for label, p in tasks]
        for i, fut in enumerate(futures):
            rows.append(fut.result())
            if (i + 1) % 25 == 0 or i + 1 == len(futures):
                print(f"  {i + 1}/{len(futures)} fragments, {time.monotonic() - t0:.0f} s", file=sys.stderr, flush=True)
    changed = binary_stamp(sherd) != stamp
    if changed:
        print(f"note: {sherd} was rebuilt during the run; the figures are those of the build it had at the start",
              file=sys.stderr)
    groups = {"all": rows}
    labels = list(dict.fromkeys(label for label, _ in tasks))
    if len(labels) > 1:
        for label in labels:
            groups[label] = [r for r in rows if r["corpus"] == label]
    title = f"sherd orient{' --refine ' + a.refine if a.refine else ''} on {', '.join(a.corpora)}"
    text, summaries = markdown(groups, title)
    text += f"\nsherd: {sherd} (sha256 {stamp[:12]}, copied at the start{'; rebuilt since' if changed else ''})\n"
    print(text)
    if a.markdown:
        Path(a.markdown).write_text(text + "\n")
    if a.out:
        Path(a.out).write_text(json.dumps({"sherd": sherd, "sherd_sha256": stamp, "sherd_changed_during_run": changed,
                                           "refine": a.refine, "corpora": a.corpora,
                                           "threshold_mm": THRESHOLD_MM, "summary": summaries, "fragments": rows},
                                          indent=1, default=float))
    return 0


if __name__ == "__main__":
    sys.exit(main())
