#!/usr/bin/env python3
"""The report of `make run`: results/REPORT.md and a self-contained results/report.html.
It opens with an overview on one screen: a row per benchmark family with its verdict count, its
headline quantities against their references (error and bound), a thumbnail of its main figure
linking to its section and the command that reproduces it; a failing family's row is red. Then a
section per family saying what it shows, with its figures (PNG, matplotlib), its commands, its own
verdict table (every checked quantity with its reference, the reference's kind, the bound the
tests hold it to, scripts/verdicts.py, and PASS or FAIL; collapsed unless one fails) and its
informational quantities.
    report.py [--results DIR]   (default: results/ in the repository)
Works with whatever summaries exist: a benchmark that did not run is listed as missing."""

import argparse
import base64
import csv
import html
import json
import math
import os
import sys

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchmark_list import BENCHMARKS  # noqa: E402
from run_benchmarks import stored_reference  # noqa: E402
from freefem import ROOT, summary_failure  # noqa: E402
import md_tables  # noqa: E402
import verdicts  # noqa: E402
import vtu  # noqa: E402

RESULTS = os.path.join(ROOT, "results")
FIGURES = "figures"


# ---------------------------------------------------------------- data
def summary(name):
    path = os.path.join(RESULTS, name, "summary.json")
    return json.load(open(path)) if os.path.exists(path) else None


def read_csv(path):
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return list(csv.DictReader(f))


def column(rows, key):
    return np.array([float(r[key]) for r in rows])


def command(name):
    for n, script, args in BENCHMARKS:
        if n == name:
            return f"FreeFem++ {script} {' '.join(args)} -out results/{name}".replace("  ", " ")
    return ""


def params_text(s, keys):
    p = s["parameters"]
    return ", ".join(f"{k} = {p[k]:g}" if isinstance(p[k], (int, float)) else f"{k} = {p[k]}" for k in keys if k in p)


# ---------------------------------------------------------------- figures
def save(fig, filename):
    os.makedirs(os.path.join(RESULTS, FIGURES), exist_ok=True)
    fig.savefig(os.path.join(RESULTS, FIGURES, filename), dpi=110, bbox_inches="tight")
    plt.close(fig)
    return filename


def finish(fig, ax, xlabel, ylabel, title, filename, legend_at="best"):
    """Labels, title, legend and grid of a one-panel figure, saved under filename."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=8, loc=legend_at)
    ax.grid(alpha=0.3, which="both")
    return save(fig, filename)


def fig_hertz_pressure(names, filename, title, unit_x="x (m)"):
    """Nodal contact pressure against Hertz's ellipse, for one or more runs."""
    runs = [(n, summary(n), read_csv(os.path.join(RESULTS, n, "pressure.csv"))) for n in names]
    runs = [r for r in runs if r[1] and r[2]]
    if not runs:
        return None
    fig, ax = plt.subplots(figsize=(7, 4.2))
    markers = ["o", "s", "^", "v"]
    s0 = runs[0][1]
    a, pmax = s0["results"]["a"]["reference"], s0["results"]["p_max"]["reference"]
    xs = np.linspace(0, a, 400)
    ax.plot(xs, pmax * np.sqrt(np.clip(1 - (xs / a) ** 2, 0, None)), "k-", lw=1.5, label="Hertz")
    for i, (n, s, rows) in enumerate(runs):
        x = column(rows, "s")
        p = column(rows, "pressure")
        form = s["parameters"].get("constraint", "")
        label = f"{n} ({form}): a err {s['results']['a']['rel_error']:.1e}" if form else \
            f"{n}: a err {s['results']['a']['rel_error']:.1e}"
        ax.plot(x, p, markers[i % 4], ms=4, mfc="none", label=label)
    ax.set_xlim(0, 1.4 * a)
    return finish(fig, ax, unit_x, "contact pressure (Pa)", title, filename)


def fig_clamped_pressure(name, filename):
    s, rows = summary(name), read_csv(os.path.join(RESULTS, name, "pressure.csv"))
    ref_path = os.path.join(ROOT, "benchmarks", "reference", "clamped_square.json")
    if not s or not rows:
        return None
    fig, ax = plt.subplots(figsize=(7, 4.2))
    ax.plot(column(rows, "s"), column(rows, "pressure"), "o-", ms=3, label=f"computed, P{s['parameters']['order']} n = {s['parameters']['n']}")
    if os.path.exists(ref_path):
        ref = json.load(open(ref_path))["reference"]
        ys = [0.7, 0.8, 0.9, 0.95]
        ax.plot(ys, [ref[f"pressure_at_y{y:g}"]["value"] for y in ys], "kx", ms=9, mew=2,
                label="mesh-converged reference (P2, n = 25..200, Richardson)")
        ax.axvline(ref["separation_y"]["value"], color="gray", ls="--", lw=1, label=f"reference separation y = {ref['separation_y']['value']:.4f}")
    return finish(fig, ax, "y along the contact side x = 0 (m)", "contact pressure (Pa)",
                  "Clamped square under its own weight: pressure on the wall\n" + params_text(s, ["E", "nu", "rho", "gravity"]),
                  filename)


def draw_mesh(ax, x, u, tris, vm, amplification):
    deformed = x + amplification * u
    polys = deformed[tris]
    coll = PolyCollection(polys, array=vm, cmap="viridis", edgecolors="face", linewidths=0.2)
    spread, level = np.ptp(vm), np.abs(vm).max()
    if spread <= 1e-9 * level:   # a homogeneous field: show its value, not its rounding noise
        coll.set_clim(0.99 * level, 1.01 * level)
    ax.add_collection(coll)
    ax.set_aspect("equal")
    return coll


def fig_deformed(name, filename, title, obstacles, zoom=None, slice3d=False, amplify_to=0.05, amplify_below=1e-3):
    """Deformed body coloured by von Mises stress, obstacles drawn (functions of the axes).
    Displacements below amplify_below of the body size are amplified to amplify_to of it."""
    s = summary(name)
    vtus = sorted(f for f in os.listdir(os.path.join(RESULTS, name)) if f.endswith(".vtu")) if s else []
    if not vtus:
        return None
    path = os.path.join(RESULTS, name, vtus[-1])
    x, u, tris, vm = vtu.slice_3d(path) if slice3d else vtu.triangles_2d(path)
    size = np.ptp(x, axis=0).max()
    umax = np.abs(u).max()
    # amplified only when invisible at true scale: amplifying a body pressed on an obstacle
    # would push it through the obstacle (its rigid approach grows too)
    amplification = amplify_to * size / umax if 0 < umax < amplify_below * size else 1.0
    panels = [None] + ([zoom] if zoom else [])
    fig, axes = plt.subplots(1, len(panels), figsize=(6.5 * len(panels), 5), squeeze=False, layout="constrained")
    for ax, window in zip(axes[0], panels):
        amp = 1.0 if window else amplification
        coll = draw_mesh(ax, x, u, tris, vm, amp)
        for draw in obstacles:
            draw(ax)
        if window:
            ax.set_xlim(window[0], window[1])
            ax.set_ylim(window[2], window[3])
            ax.set_title("near the contact (true scale)", fontsize=9)
        else:
            ax.autoscale_view()
            lo, hi = ax.get_xlim(), ax.get_ylim()
            pad = 0.05 * size
            ax.set_xlim(lo[0] - pad, lo[1] + pad)
            ax.set_ylim(hi[0] - pad, hi[1] + pad)
            ax.set_title(f"displacement x {amplification:.3g}" if amplification != 1 else "true scale", fontsize=9)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("z (m)" if slice3d else "y (m)")
        fig.colorbar(coll, ax=ax, label="von Mises stress (Pa)", shrink=0.8)
    fig.suptitle(title, fontsize=10)
    return save(fig, filename)


def line(horizontal, position, label):
    def draw(ax):
        (ax.axhline if horizontal else ax.axvline)(position, color="crimson", lw=2, label=label)
        if label:
            ax.legend(fontsize=8, loc="upper right")
    return draw


def hline(y, label):
    return line(True, y, label)


def vline(x, label):
    return line(False, x, label)


def circle(cx, cy, radius, label):
    """A rigid disc's boundary (the indenting sphere's section)."""
    def draw(ax):
        t = np.linspace(0, 2 * np.pi, 400)
        ax.plot(cx + radius * np.cos(t), cy + radius * np.sin(t), color="crimson", lw=2, label=label)
        ax.legend(fontsize=8, loc="upper right")
    return draw


def arc(R2, label):
    def draw(ax):
        xs = np.linspace(-0.6 * R2, 0.6 * R2, 300)
        ax.plot(xs, np.sqrt(R2 ** 2 - xs ** 2) - R2, color="crimson", lw=2, label=label)
        ax.legend(fontsize=8, loc="upper right")
    return draw


def curve_figure(name, csv_name):
    """(summary, rows of results/<name>/<csv_name>, figure, axes) for a one-panel curve plot,
    or None when the summary or the file is missing."""
    s, rows = summary(name), read_csv(os.path.join(RESULTS, name, csv_name))
    if not s or not rows:
        return None
    fig, ax = plt.subplots(figsize=(7, 4.2))
    return s, rows, fig, ax


def fig_oring_plates(name, filename):
    data = curve_figure(name, "force_squeeze.csv")
    if not data:
        return None
    s, rows, fig, ax = data
    c = column(rows, "c")
    ax.plot(c, column(rows, "force_per_length"), "o-", ms=4, label="computed (plane strain, P1)")
    cs = np.linspace(0, c.max(), 200)
    E, d = 6 * s["parameters"]["C10"], 2 * s["parameters"]["R"]   # Neo-Hookean: C01 = 0
    ax.plot(cs, E * d * (1.25 * cs ** 1.5 + 50 * cs ** 6), "k--", label="Lindley: E d (1.25 c^1.5 + 50 c^6), E = 6 C10")
    return finish(fig, ax, "squeeze c = delta / (2R)", "force per unit length (N/m)",
                  "O-ring between plates: force against squeeze\n" + params_text(s, ["C10", "nu", "R", "h"]), filename)


def fig_oring_torus(name, plates, filename):
    """The torus's force per unit circumference against squeeze, with the plane-strain ring and Lindley."""
    data = curve_figure(name, "force_squeeze.csv")
    if not data:
        return None
    s, rows, fig, ax = data
    c = column(rows, "c")
    ax.plot(c, column(rows, "force_per_circumference"), "o-", ms=4,
            label=f"torus, r0 = {s['parameters']['meanradius']:g} ({'held at r0' if s['parameters']['holdcentre'] else 'free'})")
    plane = read_csv(os.path.join(RESULTS, plates, "force_squeeze.csv"))
    if plane:
        ax.plot(column(plane, "c"), column(plane, "force_per_length"), "s--", ms=4, mfc="none", label="plane strain (oring_plates)")
    ax.plot(c, column(rows, "lindley"), "k:", label="Lindley")
    return finish(fig, ax, "squeeze c = delta / (2R)", "force per unit length of seal",
                  "O-ring as a torus (axisymmetric face seal) against plane strain and Lindley\n"
                  + params_text(s, ["C10", "nu", "R", "meanradius", "h"]), filename)


def fig_oring_flange(names, plates, filename):
    """Force against squeeze: the rigid plates, the steel and the soft flange, Lindley."""
    data = curve_figure(names[0], "force_squeeze.csv")
    if not data:
        return None
    s, rows, fig, ax = data
    plane = read_csv(os.path.join(RESULTS, plates, "force_squeeze.csv"))
    if plane:
        ax.plot(column(plane, "c"), column(plane, "force_per_length"), "k-", lw=1, label="rigid plates (oring_plates)")
    for name, style in zip(names, ("o", "s-")):
        r = summary(name)
        flange = read_csv(os.path.join(RESULTS, name, "force_squeeze.csv"))
        if r and flange:
            p = r["parameters"]
            ax.plot(column(flange, "c"), column(flange, "force_per_length"), style, ms=5, mfc="none",
                    label=f"elastic flange E = {p['Ef']:g} MPa, nu = {p['nuf']:g}")
    ax.plot(column(rows, "c"), column(rows, "lindley"), "k:", label="Lindley (rigid plates)")
    return finish(fig, ax, "squeeze c = travel / R", "force per unit length of seal",
                  "O-ring squeezed by elastic flanges (updated pairing)\n" + params_text(s, ["C10", "nu", "R", "W", "T", "h"]),
                  filename)


def fig_sliding_disc(name, filename):
    """The block's force against the slide: Fy (its ripple) and Fx, both over the pressed Fy."""
    data = curve_figure(name, "force_slide.csv")
    if not data:
        return None
    s, rows, fig, ax = data
    slide = [r for r in rows if float(r["phase"]) == 2 or float(r["slide"]) == 0]
    x = column(slide, "slide")
    fy, fx = column(slide, "force_y"), column(slide, "force_x")
    ax.plot(x, fy / fy[0] - 1, "o-", ms=4, label="Fy / Fy(press) - 1")
    ax.plot(x, fx / fy[0], "s--", ms=4, mfc="none", label="Fx / Fy(press) (frictionless: 0)")
    return finish(fig, ax, "slide s (m)", "relative force",
                  "Disc sliding along an elastic block (updated pairing)\n" + params_text(s, ["E1", "E2", "nu", "R", "h", "press"]),
                  filename)


def fig_partial_slip(name, filename, coordinate, reference, zone_key, title, keys):
    """The shear traction of the last tangential step against the analytic one (Cattaneo's or
    Mindlin's), with mu p (the slip bound) and the fitted stick zone."""
    data = curve_figure(name, "shear.csv")
    if not data:
        return None
    s, rows, fig, ax = data
    rows = sorted(rows, key=lambda r: float(r[coordinate]))
    x, mu = column(rows, coordinate), s["parameters"]["mu"]
    # (3D: the nodes at one r carry different pressures, so mu p as points, not a line)
    ax.plot(x, mu * column(rows, "pressure"), ":" if coordinate == "x" else ".", color="0.6", ms=3,
            label="mu p (the slip bound)")
    ax.plot(x, column(rows, reference), "k-", lw=1.2, label=reference.split("_")[0].capitalize())
    ax.plot(x, column(rows, "shear"), "o", ms=3.5, label="computed (nodal shear traction)")
    c = s["results"].get(zone_key, {}).get("computed")
    if c:
        low = -c if coordinate == "x" else 0
        shown = "|x|" if coordinate == "x" else coordinate
        ax.axvspan(low, c, color="tab:green", alpha=0.08, label=f"stick zone {shown} < c = {c:.4g}")
    return finish(fig, ax, coordinate, "shear traction q",
                  title + ", Q = " + f"{s['parameters']['ratio']:.3g}" + " mu P\n" + params_text(s, keys), filename)


def fig_cattaneo(name, filename):
    return fig_partial_slip(name, filename, "x", "cattaneo_shear", "stick_half_width",
                            "Cattaneo's partial slip: two cylinders", ["E", "nu", "R", "pressure", "mu", "h"])


def fig_cattaneo_rigid(name, filename):
    return fig_partial_slip(name, filename, "x", "cattaneo_shear", "stick_half_width",
                            "Cattaneo's partial slip: a rigid cylinder on a rubber block", ["E", "nu", "R", "pressure", "mu", "h", "block"])


def fig_mindlin(name, filename):
    return fig_partial_slip(name, filename, "r", "mindlin_shear", "stick_radius",
                            "Mindlin's partial slip: two spheres (3D)", ["E", "nu", "R", "force", "mu", "h"])


def fig_mindlin_rigid(name, filename):
    return fig_partial_slip(name, filename, "r", "mindlin_shear", "stick_radius",
                            "Mindlin's partial slip: a rigid sphere on a rubber block (3D)",
                            ["E", "nu", "R", "force", "mu", "h", "block"])


def fig_oring_friction(names, filename):
    """The O-ring plates' force against the squeeze with and without friction."""
    if not read_csv(os.path.join(RESULTS, names[1], "force_squeeze.csv")):
        return None   # drawn for the friction run
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for name, label, style in zip(names, ("frictionless", "mu = 0.3"), ("o-", "s--")):
        rows = read_csv(os.path.join(RESULTS, name, "force_squeeze.csv"))
        if rows:
            ax.plot(column(rows, "c"), column(rows, "force_per_length"), style, ms=4, label=label)
    return finish(fig, ax, "squeeze c = delta / (2R)", "force per unit length (N/m)",
                  "O-ring between plates: force against squeeze, with and without friction", filename)


def fig_bar_impact(name, filename):
    """The contact stress against time with wave theory's square pulse, and the energies."""
    s, rows = summary(name), read_csv(os.path.join(RESULTS, name, "history.csv"))
    if not s or not rows:
        return None
    p = s["parameters"]
    c = (p["E"] * (1 - p["nu"]) / (p["rho"] * (1 + p["nu"]) * (1 - 2 * p["nu"]))) ** 0.5
    t0, tc, sigma = p["gap"] / p["v0"], 2 * p["L"] / c, p["rho"] * c * p["v0"]
    t = column(rows, "time") * 1e6
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    ax.plot(t, column(rows, "contact_force") / p["W"] / 1e9, "-", lw=1, label="computed")
    ax.plot([0, t0 * 1e6, t0 * 1e6, (t0 + tc) * 1e6, (t0 + tc) * 1e6, t[-1]], [0, 0, sigma / 1e9, sigma / 1e9, 0, 0],
            "k--", label="wave theory: rho c v0 for 2 L / c")
    ax.set_xlabel("time (us)")
    ax.set_ylabel("contact stress (GPa)")
    ax.set_title(f"Bar against a wall: contact stress\n{params_text(s, ['scheme', 'mass', 'n', 'v0'])}", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    e0 = float(rows[0]["total"])
    for key, style in (("kinetic", "-"), ("elastic", "-"), ("total", "k-")):
        ax2.plot(t, column(rows, key) / e0, style, lw=1, label=key)
    ax2.set_xlabel("time (us)")
    ax2.set_ylabel("energy / initial kinetic energy")
    ax2.set_title("Energies", fontsize=10)
    ax2.legend(fontsize=8)
    ax2.grid(alpha=0.3)
    return save(fig, filename)


def fig_sphere_impact(name, pairs, filename):
    """The contact force of the sphere's impact against time, with Hertz's t_c and F_max; and two spheres
    head on (the pairs' runs, axisymmetric and 3D, their time from the first touch): the same Hertz impact."""
    s, rows = summary(name), read_csv(os.path.join(RESULTS, name, "history.csv"))
    if not s or not rows:
        return None
    r = s["results"]
    tc, fmax = r["contact_time"]["reference"], r["peak_force"]["reference"]
    fig, ax = plt.subplots(figsize=(7, 4.2))
    t = column(rows, "time")
    ax.plot(t * 1e6, column(rows, "contact_force"), "o", ms=6, mfc="none", label="one sphere against a wall")
    for pair, marker, model in zip(pairs, ("x", "+"), ("axisymmetric", "3D quarters")):
        s2, rows2 = summary(pair), read_csv(os.path.join(RESULTS, pair, "history.csv"))
        if s2 and rows2:
            p = s2["parameters"]
            touch = p["gap"] / (2 * p["v0"])
            ax.plot((column(rows2, "time") - touch) * 1e6, column(rows2, "contact_force"), marker, ms=4,
                    label=f"two spheres head on, {model} (each at v0; from their touch)")
    ts = np.linspace(0, tc, 200)
    ax.plot(ts * 1e6, fmax * np.sin(np.pi * ts / tc) ** 1.5, "k--", lw=1,
            label="Hertz: t_c and F_max (the curve between them: F_max sin(pi t / t_c)^1.5)")
    return finish(fig, ax, "time (us)", "contact force (N)",
                  "Sphere impact: contact force\n" + params_text(s, ["R", "E", "nu", "rho", "v0", "scheme", "mass"]),
                  filename)


def fig_platen(name, filename):
    data = curve_figure(name, "force_displacement.csv")
    if not data:
        return None
    s, rows, fig, ax = data
    ax.plot(column(rows, "platen_displacement"), column(rows, "platen_force"), "o-", ms=4, label="platen force")
    ax.plot(column(rows, "platen_displacement"), column(rows, "floor_force"), "x", ms=7, label="floor force (multipliers)")
    return finish(fig, ax, "platen displacement", "force per unit depth",
                  "Rubber block on a wavy floor: platen force against displacement\n"
                  + params_text(s, ["C10", "nu", "n", "amplitude", "waves"]), filename)


def fig_indentation(names, filename):
    """The sphere's force against its depth: both models and Hertz's small-depth law."""
    data = curve_figure(names[0], "force_depth.csv")
    if not data:
        return None
    s, rows, fig, ax = data
    depth = column(rows, "depth")
    for name, style, label in zip(names, ("o-", "s--"), ("axisymmetric", "3D quarter")):
        r = summary(name)
        curve = read_csv(os.path.join(RESULTS, name, "force_depth.csv"))
        if r and curve:
            ax.plot(column(curve, "depth"), column(curve, "force"), style, ms=4, mfc="none",
                    label=f"{label}, h = R/{1 / r['parameters']['h']:.0f} ({r['ndof']} dofs)")
    ax.plot(depth, column(rows, "hertz_force"), "k:", label="Hertz: (4/3) E* R^1/2 delta^3/2")
    return finish(fig, ax, "depth delta", "force on the sphere",
                  "Rigid sphere indenting a Neo-Hookean block: force against depth\n"
                  + params_text(s, ["E", "nu", "R", "block"]), filename)


def floor_curve(s):
    """The platen block's wavy floor, for the deformed-body figure."""
    def draw(ax):
        p = s["parameters"]
        x = np.linspace(-0.25 * p["W"], 1.25 * p["W"], 400)
        ax.plot(x, -0.5 * p["amplitude"] * (1 - np.cos(2 * np.pi * p["waves"] * x / p["W"])), "k-", lw=1.5, label="rigid floor")
    return draw


def fig_oring_groove(name, filename):
    data = curve_figure(name, "face_forces.csv")
    if not data:
        return None
    s, rows, fig, ax = data
    closure = column(rows, "closure")
    for key, style in (("floor", "o-"), ("wall", "s--"), ("ceiling", "^-"), ("opposite_wall", "v--")):
        ax.plot(closure, column(rows, key), style, ms=4, mfc="none", label=key.replace("_", " "))
    return finish(fig, ax, "closure of the groove (m)", "force on the face (N/m)",
                  "O-ring in the closing groove: face forces\n" + params_text(s, ["C10", "nu", "R", "gap", "side"]), filename)


def seal_surfaces(name):
    """A seal run's surface files (surface_p00.csv, ...: one per step), in step order."""
    folder = os.path.join(RESULTS, name)
    return sorted(f for f in os.listdir(folder) if f.startswith("surface_p")) if os.path.isdir(folder) else []


def fig_seal_pressure(name, filename, title="O-ring seal", along="angle_deg",
                      xlabel="angle on the ring about its centre (degrees; fluid enters at -45, gap at 135)"):
    """The contact pressure along the sealing surface at several fluid pressures, the wetted part
    drawn at p: the fluid follows the contacts up to the fronts."""
    s = summary(name)
    steps = seal_surfaces(name) if s else []
    if not steps:
        return None
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    later = steps[1:]
    chosen = [steps[0]] + [later[round(i * (len(later) - 1) / 3)] for i in range(4)] if len(later) >= 4 else steps
    for i, f in enumerate(chosen):
        rows = read_csv(os.path.join(RESULTS, name, f))
        angle, contact = column(rows, along), column(rows, "contact_pressure")
        wet, fluid = column(rows, "wetted"), column(rows, "fluid_pressure")
        p = fluid.max() if wet.any() else 0.0
        line, = ax.plot(angle, contact, "-", lw=1.2, label=f"p = {p:g}: contact")
        if wet.any():
            ax.plot(np.where(wet > 0, angle, np.nan), np.where(wet > 0, fluid, np.nan), ":", lw=2.5, marker="o",
                    ms=3, color=line.get_color(), label=f"p = {p:g}: wetted")
    if along == "angle_deg":
        ax.set_xticks(range(-180, 181, 45))
    return finish(fig, ax, xlabel, "pressure on the surface (stress unit)",
                  title + ": contact pressure and the wetted surface\n" +
                  params_text(s, ["C10", "nu", "clearance", "corner", "W", "T", "squeeze", "h"]), filename)


def fig_seal_margin(name, filename):
    """Each face's peak contact pressure, the sealing margin and the extrusion against p."""
    data = curve_figure(name, "pressure_steps.csv")
    if not data:
        return None
    s, rows, fig, ax = data
    p = column(rows, "p")
    for key, style in (("mating_face_peak", "o-"), ("low_flank_peak", "s--"), ("floor_peak", "^:"),
                       ("high_flank_peak", "v:")):
        ax.plot(p, column(rows, key), style, ms=4, mfc="none", label=key.replace("_", " "))
    ax.plot(p, column(rows, "sealing_margin"), "k-", lw=2, label="sealing margin")
    ax.plot(p, p, color="0.6", lw=1, label="p")
    twin = ax.twinx()
    twin.plot(p, column(rows, "extrusion"), "r-x", label="extrusion into the gap")
    twin.set_ylabel("extrusion past the flank (length)", color="r")
    e = s["parameters"].get("clearance", 0)
    if e:
        twin.axhline(e / 2, color="r", ls="--", lw=0.8, label="half the clearance")
    twin.legend(fontsize=8, loc="lower right")
    return finish(fig, ax, "fluid pressure p", "peak contact pressure, margin (stress unit)",
                  "O-ring seal: contact pressures, sealing margin and extrusion against p\n" +
                  params_text(s, ["C10", "nu", "clearance", "corner"]), filename)


def fig_seal_stroke(name, filename):
    """The friction force on the ring against the mating face's stroke: the hysteresis loop, one
    line per cycle, with +- mu times the normal force (gross sliding) dotted."""
    data = curve_figure(name, "stroke.csv")
    if not data:
        return None
    s, rows, fig, ax = data
    x, f, n = column(rows, "position"), column(rows, "friction_force"), column(rows, "normal_force")
    cycle, leg = column(rows, "cycle"), column(rows, "leg")
    mu = s["parameters"].get("mu", 0)
    first = leg == 1
    ax.plot(x[first], f[first], "k:", lw=1, label="first leg (from the squeezed state)")
    for c in sorted(set(cycle[~first].astype(int))):
        pick = np.flatnonzero((cycle == c) & ~first)
        pick = np.concatenate(([pick[0] - 1], pick))   # from the end of the leg before: the loop closed
        ax.plot(x[pick], f[pick], "o-" if c == 1 else "-", ms=3, mfc="none", label=f"cycle {c}")
    ax.plot(x, mu * n, ".", color="0.5", ms=2, label="+- mu x normal force (gross sliding)")
    ax.plot(x, -mu * n, ".", color="0.5", ms=2)
    return finish(fig, ax, "stroke of the mating face (length)", "axial friction force on the ring (per revolution)",
                  "O-ring seal on a stroking rod: friction force against stroke\n" +
                  params_text(s, ["C10", "nu", "mu", "stroke", "radius", "seal"]), filename)


def fig_seal_extrusion(names, filename, label_key, title):
    """The extrusion into the gap against p for several runs (clearances, or meshes), each with half
    its clearance dashed and the pressure where it is reached (half_clearance_pressure) marked."""
    runs = [(n, summary(n), read_csv(os.path.join(RESULTS, n, "pressure_steps.csv"))) for n in names]
    runs = [(n, s, rows) for n, s, rows in runs if s and rows]
    if not runs:
        return None
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for n, s, rows in runs:
        par = s["parameters"]
        value = par.get(label_key, 1)
        text = f"{label_key} = {value:.4g}"
        if label_key == "refine":   # the elements at the gap: h / refine
            text = f"h = R/{par.get('R', 0.52) / par.get('h', 0.52 / 24):.0f}, R/{value * par.get('R', 0.52) / par.get('h', 0.52 / 24):.0f} at the gap"
        line, = ax.plot(column(rows, "p_over_G"), column(rows, "extrusion"), "o-", ms=3, label=text)
        e = s["parameters"].get("clearance", 0)
        ax.axhline(e / 2, color=line.get_color(), ls="--", lw=0.8)
        reached = s["results"].get("half_clearance_pressure", {}).get("computed")
        if reached:
            G = 2 * s["parameters"].get("C10", 1.2345)
            ax.plot([reached / G], [e / 2], "*", ms=12, color=line.get_color(),
                    label=f"e / 2 reached at {reached / G:.2f} G")
    return finish(fig, ax, "fluid pressure p / G", "extrusion past the flank's plane (length)",
                  title + "\n(dashed: half the clearance e; " + params_text(runs[0][1], ["C10", "nu", "corner"]) + ")",
                  filename, legend_at="upper left")


def fig_seal_deformed(name, filename):
    """The deformed ring at the last step, its wetted surface and the rigid faces with the gap."""
    s = summary(name)
    steps = seal_surfaces(name) if s else []
    if not steps:
        return None
    rows = read_csv(os.path.join(RESULTS, name, steps[-1]))
    x, y, wet = column(rows, "x"), column(rows, "y"), column(rows, "wetted")
    contact = column(rows, "contact_pressure")
    par = s["parameters"]
    rod = par.get("seal") == "rod"
    if par.get("dim") == "axi":   # the (r, z) of the piston seal, or the rod seal's, back to the plane groove's frame (seal.edp)
        x, y = y, (par.get("radius", 5.0) - x if rod else x - par.get("radius", 5.0))
    side, e, r = par.get("side", 1.0), par.get("clearance", 0.0), par.get("corner", 0.0)
    fig, ax = plt.subplots(figsize=(6, 6))
    closed_x, closed_y = np.append(x, x[0]), np.append(y, y[0])
    ax.plot(closed_x, closed_y, "k-", lw=1, label="deformed ring")
    ax.plot(np.where(wet > 0, x, np.nan), np.where(wet > 0, y, np.nan), "b-", lw=3, label="wetted")
    pressed = contact > 1e-6 * max(contact.max(), 1e-300)
    ax.plot(x[pressed], y[pressed], "o", color="darkorange", ms=3, label="in contact")
    t = np.linspace(0, np.pi / 2, 30)
    flank_x = [-0.15 * side, -r] + list(-r + r * np.sin(t)) + [0, 0]
    flank_y = [side - e, side - e] + list(side - e - r + r * np.cos(t)) + [side - e - r, 0]
    ax.plot(flank_x, flank_y, color="0.3", lw=2.5, label="groove (floor, flanks) and mating face")
    ax.plot([0, side], [0, 0], color="0.3", lw=2.5)
    ax.plot([side, side], [0, side], color="0.3", lw=2.5)
    ax.plot([-0.15 * side, side], [side, side], color="0.3", lw=2.5)
    ax.annotate("fluid in", (side, 0), (0.75 * side, -0.1 * side), arrowprops=dict(arrowstyle="->"), fontsize=9)
    ax.annotate("gap", (-0.05 * side, side - e / 2), (-0.15 * side, 1.08 * side), arrowprops=dict(arrowstyle="->"),
                fontsize=9)
    ax.set_aspect("equal")
    ax.set_xlim(-0.2 * side, 1.1 * side)
    ax.set_ylim(-0.15 * side, 1.15 * side)
    res = s["results"]
    p = res.get("fluid_pressure", {}).get("computed", 0)
    axi = par.get("dim") == "axi"
    return finish(fig, ax, "z" if axi else "x", ("radius - r" if rod else "r - radius") if axi else "y",
                  f"O-ring {('rod ' if rod else 'piston ') if axi else ''}seal at p = {p:g}: the wetted surface and the contacts\n" +
                  params_text(s, ["C10", "nu", "clearance", "corner"] + (["radius", "seal"] if axi else [])), filename)


def convergence_runs(case):
    folder = os.path.join(RESULTS, "convergence")
    runs = []
    if os.path.isdir(folder):
        for d in sorted(os.listdir(folder)):
            if d.startswith(case + "_a"):
                s = json.load(open(os.path.join(folder, d, "summary.json"))) if os.path.exists(os.path.join(folder, d, "summary.json")) else None
                if s:
                    runs.append((int(d.split("_a")[-1]), s))
    return sorted(runs)


def fraction_ticks(ax, denominators):
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xticks([1.0 / d for d in denominators])
    ax.set_xticklabels([f"1/{d}" for d in denominators])


def observed_order(h, e):
    if len(h) < 2 or min(e) <= 0:
        return float("nan")
    return np.polyfit(np.log(h), np.log(e), 1)[0]


def fig_convergence_hertz(filename):
    cases = [c for c in ("plane", "circle_vertical", "circle_exact") if len(convergence_runs(c)) >= 2]
    if not cases:
        return None
    fig, axes = plt.subplots(1, len(cases), figsize=(5.2 * len(cases), 4.2), squeeze=False)
    for ax, case in zip(axes[0], cases):
        runs = convergence_runs(case)
        h = np.array([1.0 / level for level, _ in runs])
        # a and p_max level off at the finite-disc limit (a few 1e-4), or at the 0.36 % the
        # psi' u1 term costs the exact form: no single slope describes them
        for key, style in (("a", "o-"), ("p_max", "s-")):
            e = np.array([s["results"][key]["rel_error"] for _, s in runs])
            ax.loglog(h, e, style, ms=4, label=key)
        e = np.array([s["results"]["pressure_l2_rel_error"]["computed"] for _, s in runs])
        ax.loglog(h, e, "^-", ms=4, label=f"L2 of p (observed order {observed_order(h, e):.2f})")
        fraction_ticks(ax, [level for level, _ in runs])
        ax.set_xlabel("element size in the contact zone h / a")
        ax.set_ylabel("relative error against Hertz")
        ax.set_title(f"Hertz {case.replace('_', ', ')}", fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.suptitle("Convergence of the Hertz benchmarks (P1, linear elasticity)", fontsize=10)
    return save(fig, filename)


def fig_convergence_clamped(filename):
    path = os.path.join(ROOT, "benchmarks", "reference", "clamped_square.json")
    if not os.path.exists(path):
        return None
    data = json.load(open(path))
    p2 = [r for r in data["runs"] if r["order"] == 2]
    h = np.array([1.0 / r["n"] for r in p2[:-1]])
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for key, style in (("contact_force", "o-"), ("pressure_at_y0.8", "s-"), ("pressure_at_y0.9", "^-"),
                       ("centre_of_pressure_y", "v-")):
        ref = data["reference"][key]["value"]
        e = np.array([abs(r["values"][key] - ref) / abs(ref) for r in p2[:-1]])
        if min(e) > 0:
            ax.loglog(h, e, style, ms=4, label=f"{key} (slope {observed_order(h, e):.2f})")
    fraction_ticks(ax, [r["n"] for r in p2[:-1]])
    return finish(fig, ax, "element size h (m)", "relative difference to the reference",
                  "Clamped square, P2: convergence towards the stored reference\n(the finest level, n = 200, is part of the reference)",
                  filename)


def fig_iterations(filename):
    fig, ax = plt.subplots(figsize=(6, 4.2))
    plotted = False
    for case, style in (("plane", "o-"), ("circle_vertical", "s-"), ("circle_exact", "^-")):
        runs = convergence_runs(case)
        if runs:
            ax.semilogx([s["ndof"] for _, s in runs], [s["ipopt_iterations"] for _, s in runs], style, label=f"Hertz {case}")
            plotted = True
    path = os.path.join(ROOT, "benchmarks", "reference", "clamped_square.json")
    if os.path.exists(path):
        runs = [r for r in json.load(open(path))["runs"] if r["order"] == 2]
        ax.semilogx([r["ndof"] for r in runs], [r["iterations"] for r in runs], "v-", label="clamped square P2")
        plotted = True
    if not plotted:
        plt.close(fig)
        return None
    ax.set_ylim(0, 25)
    return finish(fig, ax, "degrees of freedom", "IPOPT iterations", "IPOPT iterations against problem size (exact Hessian)", filename)


# ---------------------------------------------------------------- sections
def sections():
    """(title, benchmark names, figure builders) for each section of the report."""
    s = summary("hertz_circle_exact") or summary("hertz_circle_vertical") or {"parameters": {"R2": 1.2}}
    R2 = s["parameters"].get("R2", 1.2)
    plane = summary("hertz_plane")
    a = plane["results"]["a"]["reference"] if plane else 0.055
    circle_a = s["results"]["a"]["reference"] if "results" in s else 0.039
    groove = summary("oring_groove")
    side = groove["parameters"]["side"] if groove else 1.0
    indent = summary("indentation_axi")
    ip = indent["parameters"] if indent else {"R": 1.0, "block": 10.0, "depth": 0.2}
    sphere = circle(0, ip["block"] * ip["R"] + ip["R"] - ip["depth"], ip["R"], "rigid sphere")
    plates = summary("oring_plates")
    plate_y = plates["parameters"]["R"] * (1 - plates["parameters"]["cmax"]) if plates else 0.36
    platen = summary("platen_block")
    zoom = lambda r: (0, 2.5 * r, -0.4 * r, 1.6 * r)  # noqa: E731
    return [
        ("Hertz contact on a rigid plane (preprint 4.2.1)", ["hertz_plane", "hertz_plane_neohookean"],
         "A quarter disc pressed onto a rigid plane. Linear elasticity meets Hertz's half-width and peak pressure "
         "to a few 1e-4 (what is left is the finite disc and its far-field mesh), the contact force from IPOPT's "
         "multipliers equals the load to 1e-14 and nothing penetrates. Neo-Hookean with the same small-strain "
         "moduli sits 0.6 % away at this load: the contact strain is 3 %, and Hertz is a small-strain theory.", [
            lambda: fig_hertz_pressure(["hertz_plane", "hertz_plane_neohookean"], "hertz_plane_pressure.png",
                                       "Hertz, disc on a rigid plane: contact pressure\nE = 2.1e9 Pa, nu = 0.3, R = 1 m, f = 2.75e6 Pa, h = a/30"),
            lambda: fig_deformed("hertz_plane", "hertz_plane_deformed.png", "Hertz, disc on a rigid plane: von Mises stress",
                                 [hline(0, "rigid plane")], zoom=zoom(a))]),
        ("Hertz contact on a rigid cylinder (preprint 4.2.2)", ["hertz_circle_exact", "hertz_circle_linearized", "hertz_circle_vertical"],
         "The disc on a convex rigid cylinder given as a cubic spline. Hertz's own vertical gap meets Hertz like the "
         "plane; the exact form (42) and its linearisation (43) agree with each other to 6e-6 and sit 0.3-0.4 % "
         "from Hertz, because they keep the sliding term psi'(X1) u1 that Hertz drops (docs/benchmarks/hertz.md).", [
            lambda: fig_hertz_pressure(["hertz_circle_exact", "hertz_circle_linearized", "hertz_circle_vertical"],
                                       "hertz_circle_pressure.png",
                                       f"Hertz, disc on a rigid cylinder (spline): the three constraint forms\nE = 2.1e5 Pa, nu = 0.3, R1 = 1 m, R2 = {R2:g} m, f = 250 Pa, h = a/30"),
            lambda: fig_deformed("hertz_circle_exact", "hertz_circle_deformed.png",
                                 "Hertz, disc on a rigid cylinder, exact form (42): von Mises stress",
                                 [arc(R2, f"rigid cylinder R2 = {R2:g} m")], zoom=zoom(circle_a))]),
        ("3D Hertz: a hemisphere on a rigid plane", ["hertz_sphere", "hertz_sphere_axisymmetric"],
         "A quarter hemisphere of tetrahedra on a rigid plane: Hertz's point contact within 1 % on this coarse "
         "mesh (h = a/8); docs/performance.md has finer meshes. The same sphere from its 2D meridian "
         "section (-dim axi, the hoop stretch and the 2 pi r measure) meets Hertz within 0.21 % in under a "
         "second.", [
            lambda: fig_hertz_pressure(["hertz_sphere", "hertz_sphere_axisymmetric"], "hertz_sphere_pressure.png",
                                       "3D Hertz, hemisphere on a rigid plane: contact pressure against r\nE = 2.1e5 Pa, nu = 0.3, R = 1 m, f = 100 Pa",
                                       unit_x="r (m)"),
            lambda: fig_deformed("hertz_sphere", "hertz_sphere_deformed.png",
                                 "3D Hertz: von Mises stress on the symmetry plane y = 0", [hline(0, "rigid plane")],
                                 zoom=(0, 0.25, -0.04, 0.16), slice3d=True)]),
        ("Contact between two elastic bodies (two-body Hertz, preprint (49)-(50))",
         ["hertz_two_cylinders", "hertz_two_cylinders_swapped", "hertz_two_spheres"],
         "Two elastic cylinders (E2 = E1 / 3) and two elastic spheres pressed together through a contact pair "
         "(small sliding, averaged normal). The softer body is the slave by default; the swapped choice is the "
         "second run, 0.13 % away in a. The pair's force on the master is minus that on the slave to 1e-16, and "
         "each body balances on its own.", [
            lambda: fig_hertz_pressure(["hertz_two_cylinders", "hertz_two_cylinders_swapped"], "hertz_two_cylinders_pressure.png",
                                       "Two elastic cylinders: contact pressure on the slave side\nE1 = 2.1e5, E2 = 7e4 Pa, nu = 0.3, R1 = 1, R2 = 1.2 m, f = 250 Pa, h = a/30"),
            lambda: fig_deformed("hertz_two_cylinders", "hertz_two_cylinders_deformed.png",
                                 "Two elastic cylinders: von Mises stress on both bodies", [], zoom=(0, 0.25, -0.15, 0.1)),
            lambda: fig_hertz_pressure(["hertz_two_spheres"], "hertz_two_spheres_pressure.png",
                                       "Two elastic spheres (3D): contact pressure against r\nE1 = 2.1e5, E2 = 7e4 Pa, nu = 0.3, R1 = 1, R2 = 1.2 m, f = 100 Pa, h = a/8",
                                       unit_x="r (m)")]),
        ("O-ring between elastic flanges (two bodies, updated pairing)", ["oring_flange_steel", "oring_flange_soft"],
         "The plates of the O-ring case made deformable: a flange block W x T pushed down on the ring, the contact "
         "a pair made again on the deformed bodies at every step until it settles (finite sliding). A steel flange "
         "gives the rigid plates' force less what its own compression takes from the squeeze (7.7e-5 of the force, "
         "within 5 % of the run's first-order estimate); a soft housing (E = 40 MPa) dishes under the ring and "
         "carries a quarter less force.", [
            lambda: fig_oring_flange(["oring_flange_steel", "oring_flange_soft"], "oring_plates", "oring_flange_forces.png"),
            lambda: fig_deformed("oring_flange_soft", "oring_flange_soft_deformed.png",
                                 "O-ring under a soft flange (E = 40 MPa): von Mises stress on both bodies", [])]),
        ("The contact patch test: two blocks, non-matching meshes", ["patch_test"],
         "Two blocks of the same material, meshed independently, pressed by a uniform pressure: the exact state is a "
         "uniform stress, which P1 reproduces. Node to segment in one pass spreads the transmitted traction by 36 % and "
         "puts a spurious stress of 16 % of p in the blocks; in two passes (each side also the other's master, the "
         "driver's default) the pressure is uniform to 5e-10 and the stress exact to 2.4e-10, with or without friction.", []),
        ("Large sliding: a disc along an elastic block (updated pairing)", ["sliding_disc"],
         "A half disc pressed into an elastic block, then slid by a quarter of its radius: the contact crosses ten "
         "master segments. Balance, action = reaction, no penetration and a settled pairing are checked at every "
         "step. Frictionless, the sideways force stays near zero; the vertical force ripples as the contact nodes "
         "cross the block's facets, 0.5 % at h = R/40, 0.1 % at R/80.", [
            lambda: fig_sliding_disc("sliding_disc", "sliding_disc_forces.png")]),
        ("Coulomb friction: Cattaneo's and Mindlin's partial slip, exact stick, sliding",
         ["cattaneo", "cattaneo_rigid", "cattaneo_rigid_incompressible", "cattaneo_hold", "cattaneo_sliding", "mindlin_sphere", "mindlin_sphere_hold",
          "mindlin_rigid", "mindlin_rigid_incompressible", "mindlin_rigid_hold", "sliding_disc_friction", "oring_plates_friction",
          "hertz_sphere_friction", "hertz_sphere_axisymmetric_friction"],
         "Friction over a load step is a dissipation sum g |slip| with one slack per contact row in the condensed "
         "reduced problem, no smoothing; Coulomb's bounds g = mu N come from the multipliers by a fixed point. Two "
         "identical cylinders pressed and then sheared (dolfinx_contact's set-up) meet Cattaneo's stick zone and "
         "shear traction, and so does a rigid cylinder on a nearly incompressible block (the stabilised nodal form), two identical spheres Mindlin's stick radius and tangential displacement (3D), and so does a rigid sphere on "
         "a nearly or exactly incompressible block; held at 0.99 mu P "
         "for 50 steps the platen does not move (exact stick); driven past mu P "
         "every node slides with q = mu p. Coulomb's law is checked at every node of every step of every friction "
         "run (docs/benchmarks/friction.md).", [
            lambda: fig_cattaneo("cattaneo", "cattaneo_shear.png"),
            lambda: fig_cattaneo_rigid("cattaneo_rigid", "cattaneo_rigid_shear.png"),
            lambda: fig_mindlin("mindlin_sphere", "mindlin_shear.png"),
            lambda: fig_mindlin_rigid("mindlin_rigid_incompressible", "mindlin_rigid_shear.png"),
            lambda: fig_oring_friction(["oring_plates", "oring_plates_friction"], "oring_friction_force.png")]),
        ("Dynamics: a bar and a sphere against a rigid wall, two bars, two discs and two spheres head on (implicit time steps)",
         ["bar_impact", "sphere_impact", "sphere_impact_neohookean", "sphere_impact_rubber", "sphere_impact_incompressible",
          "sphere_impact_3d", "bars_head_on", "discs_head_on", "spheres_head_on", "spheres_head_on_3d"],
         "Each time step of Newmark's trapezoidal rule is one minimisation of the incremental potential (inertia plus "
         "stored energy) under the contact rows, warm from the predictor. An elastic bar flying at 100 m/s hits a rigid "
         "wall (Code_Aster SDNV100): with no mass on the contact nodes (redistributed to their neighbours) the contact "
         "stress is wave theory's square pulse rho c v0 for 2 L / c, the bar rebounds at v0 and the energy is kept "
         "to 1e-4; with mass on them the contact force chatters and the energy grows six-fold. A steel sphere meets Hertz's "
         "impact theory (contact time and peak force) within 1.5 %, a rubber one within 1.6 % (the nodal form; 1.8 % "
         "exactly incompressible, nu = 0.5); two "
         "equal bars, two equal discs and two equal spheres meeting head on exchange their velocities, the spheres "
         "again as Hertz's impact says (docs/benchmarks/dynamics.md).", [
            lambda: fig_bar_impact("bar_impact", "bar_impact_history.png"),
            lambda: fig_sphere_impact("sphere_impact", ["spheres_head_on", "spheres_head_on_3d"], "sphere_impact_force.png")]),
        ("Clamped square under its own weight (preprint 4.3)", ["clamped_square"],
         "A steel square clamped on one side bends onto a rigid wall under its own weight; the upper part presses, "
         "the lower part lifts off. No analytic answer exists: the references come from our own P2 mesh study "
         "(benchmarks/reference/clamped_square.json), and the weight carried by clamp and wall is exact.", [
            lambda: fig_clamped_pressure("clamped_square", "clamped_square_pressure.png"),
            lambda: fig_deformed("clamped_square", "clamped_square_deformed.png",
                                 "Clamped square on a rigid wall: von Mises stress", [vline(0, "rigid wall")])]),
        ("O-ring gasket (preprint section 5)", ["oring_groove", "oring_plates", "oring_torus"],
         "A nearly incompressible Neo-Hookean ring squeezed by moving rigid parts, held by contact alone. In the "
         "groove, the symmetric problem must give balanced opposite faces and floor = wall, which it does to 1e-15. "
         "Between plates the force is shown against Lindley's empirical law, which plane strain at nu = 0.499 "
         "exceeds by about 1 / (1 - nu^2): the bound is our own mesh study, not Lindley. As the torus it is "
         "(axisymmetric), free to expand radially, the ring meets Lindley to 0.4 % at c = 0.2: the plane-strain gap is "
         "the hoop constraint.", [
            lambda: fig_oring_groove("oring_groove", "oring_groove_forces.png"),
            lambda: fig_deformed("oring_groove", "oring_groove_deformed.png", "O-ring in the closed groove: von Mises stress",
                                 [hline(0, "rigid parts"), vline(0, None), hline(side, None), vline(side, None)]),
            lambda: fig_oring_plates("oring_plates", "oring_plates_force.png"),
            lambda: fig_oring_torus("oring_torus", "oring_plates", "oring_torus_force.png"),
            lambda: fig_deformed("oring_plates", "oring_plates_deformed.png",
                                 "O-ring between plates at c = 0.3 (quarter): von Mises stress", [hline(plate_y, "rigid plate")])]),
        ("O-ring seal under fluid pressure (pressure penetration)",
         ["seal", "seal_axisymmetric", "seal_rod", "seal_stroke", "seal_extrusion_e0.025", "seal_extrusion_e0.05", "seal_extrusion_e0.1",
          "seal_extrusion_e0.15", "seal_extrusion_e0.1_refine1", "seal_extrusion_e0.1_refine4", "gasket", "gasket_compressible"],
         "The ring of the groove above, squeezed, then a fluid from the corner where the high-pressure flank "
         "meets the floor, up to 2 G. The fluid wets the free surface it fills and follows each contact while "
         "the contact pressure at its front is below p (pressure penetration): it gets under the floor and the "
         "high-pressure flank, which the ring leaves, and stops at the mating face and the low-pressure flank, "
         "where the ring is pushed into the corner at the clearance gap. There the peak contact pressure rises "
         "with p (self-sealing), the sealing margin stays positive, and the ring starts to extrude into the gap: "
         "the pressure at which it has extruded half the clearance falls as the clearance opens (four clearances, "
         "the ring refined where it meets the gap; the widest's converges at first order as that refinement doubles). "
         "As a piston seal (axisymmetric) the fluid gets under the groove's "
         "floor only and pushes the ring onto the bore; as a rod seal (the groove in the housing) it gets behind the "
         "high-pressure flank only and the ring stays on the groove's floor and the rod; squeezed, both tend to plane "
         "strain at first order in R / r, with opposite signs. With friction (mu = 0.3) the rod stroked under the "
         "ring draws a hysteresis loop: partial slip after each reversal, then gross sliding at mu times the rod's "
         "radial contact force to round-off, each cycle the one before. "
         "Every step balances (contact, the rotation row and the fluid's follower force), to round-off where the "
         "condensed SQP solves it and to IPOPT's tolerance where it takes over (8e-11 at most); the "
         "fluid's load is exact on homogeneous states (tests/fluid_pressure_check.edp, docs/rubber.md). A flat "
         "gasket, a strip bonded to one plate and squeezed by the other, is the seal that can leak: nearly "
         "incompressible (W / T = 2) it holds to 5 G, its contacts rising with p; at nu = 0.3 it leaks between "
         "1.19 and 1.25 G (the leaking step bisected), 3.5 times its squeezed peak contact pressure (the elastic leak "
         "criterion is a lower bound).", [
            lambda: fig_seal_pressure("seal", "seal_contact_pressure.png"),
            lambda: fig_seal_margin("seal", "seal_margin.png"),
            lambda: fig_seal_deformed("seal", "seal_deformed.png"),
            lambda: fig_seal_extrusion(["seal_extrusion_e0.025", "seal_extrusion_e0.05", "seal_extrusion_e0.1",
                                        "seal_extrusion_e0.15"],
                                       "seal_extrusion.png", "clearance", "O-ring seal: extrusion into the clearance gap"),
            lambda: fig_seal_extrusion(["seal_extrusion_e0.1_refine1", "seal_extrusion_e0.1", "seal_extrusion_e0.1_refine4"],
                                       "seal_extrusion_mesh.png", "refine",
                                       "O-ring seal, e = 0.1: the extrusion as the ring is refined at the gap"),
            lambda: fig_seal_deformed("seal_axisymmetric", "seal_axisymmetric_deformed.png"),
            lambda: fig_seal_deformed("seal_rod", "seal_rod_deformed.png"),
            lambda: fig_seal_stroke("seal_stroke", "seal_stroke.png"),
            lambda: fig_seal_pressure("gasket_compressible", "gasket_contact_pressure.png", "Flat gasket (nu = 0.3)", "x_reference",
                                      "x along the gasket's top, reference (fluid from x = 0; it leaks at the right flank, x = W)")]),
        ("Rubber block pushed onto a wavy floor (displacement control)", ["platen_block"],
         "A Neo-Hookean block bonded to a rigid platen that moves down, resting on a rigid sinusoidal floor (a "
         "spline). Prescribed displacements reach each step through a linear predictor, so the block takes four "
         "steps at any refinement; the platen force converges at first order to the mesh-converged 0.6462, and it "
         "balances the floor's force from the multipliers to 1e-13.", [
            lambda: fig_platen("platen_block", "platen_block_force.png"),
            lambda: fig_deformed("platen_block", "platen_block_deformed.png", "Rubber block on a wavy floor: von Mises stress",
                                 [floor_curve(platen)] if platen else [])]),
        ("3D rubber contact: a rigid sphere indenting a block", ["indentation_axi", "indentation_3d"],
         "A rigid sphere pressed 0.2 R into a nearly incompressible Neo-Hookean block (nu = 0.499), through the "
         "exact form (42) of the sphere, in ten steps; two independent models of the same block, axisymmetric and "
         "a 3D quarter. At the first step's depth both meet Hertz (the axisymmetric model to 0.8 % on its default "
         "mesh); deeper, finite strain bends the curve below Hertz, and the 3D model meets the axisymmetric one to "
         "0.4 % at R/32 (docs/rubber.md: the mesh study; the report's 3D run is the coarse R/16).", [
            lambda: fig_indentation(["indentation_axi", "indentation_3d"], "indentation_force.png"),
            lambda: fig_deformed("indentation_axi", "indentation_deformed.png",
                                 "Indentation, axisymmetric section: von Mises stress", [sphere],
                                 zoom=(0, 1.2 * ip["R"], (ip["block"] - 1) * ip["R"], (ip["block"] + 0.3) * ip["R"]))]),
        ("Rubber at and near incompressibility: Rivlin's tube", ["rivlin_tube", "hertz_plane_nu0.4999"],
         "An incompressible Neo-Hookean tube inflated by a dead load: its deformed radii are known exactly at any strain. "
         "With -volumetric nodal (Jbar_n = 1 at every vertex as IPOPT constraints) the inner radius converges at second "
         "order and is within 4.2e-4 of (a - A) on the default mesh, where the element penalty form at nu = 0.4999 "
         "locks (3.5e-2). Linear Hertz at nu = 0.4999 with the nodal form meets Hertz within 0.13 %; the penalty form "
         "misses it by 17 %.", [
            lambda: fig_deformed("rivlin_tube", "rivlin_tube_deformed.png", "Rivlin's tube at nu = 0.5: von Mises stress", [])]),
        ("Hyperelastic cube (Code_Aster SSNV187, preprint 4.1)",
         [n for n, _, _ in BENCHMARKS if n.startswith("cube")] + ["cylinder_axisymmetric"],
         "A block under a dead-load pressure deforms homogeneously, so P1 must reproduce the exact solution, which the "
         "suite computes without finite elements: it does, to 1e-11, in 2D and 3D, supported or resting on a rigid "
         "foundation by contact. The 0.19 % from Code_Aster's incompressible value is the compressibility of "
         "nu = 0.499, not an error: at nu = 0.5 (-volumetric nodal) w meets Code_Aster's 0.034009 and 0.07818 to "
         "1e-9, and the pressure from the multipliers is the exact -tr(sigma)/3. Under the dead load the homogeneous state "
         "is stable only to 20-27 % compression (the free top corner buckles, docs/rubber.md); under a rigid platen "
         "(cube_2d_mooney_platen, 35 %) it is stable, and the platen's force is the pressure times the area to 1e-8.", [
            lambda: fig_deformed("cube_2d_neohookean", "cube_deformed.png",
                                 "Cube, Neo-Hookean, plane strain: von Mises stress (homogeneous)", [])]),
        ("Convergence and solver effort", [],
         "The Hertz refinement study (make convergence) and the clamped square's stored mesh study; IPOPT needs "
         "11 to 15 iterations whatever the size.", [
            lambda: fig_convergence_hertz("convergence_hertz.png"),
            lambda: fig_convergence_clamped("convergence_clamped.png"),
            lambda: fig_iterations("iterations_vs_dofs.png")]),
    ]




def verdict_tables():
    """(checked rows, informational rows, missing benchmarks, PASS count, FAIL count)."""
    checked, info, missing = [], [], []
    for name, _, _ in BENCHMARKS:
        s = summary(name)
        if s is None:
            missing.append(name)
            checked.append([name, "-", "-", "-", "-", "-", "-", "missing"])
            continue
        stored = stored_reference(name)
        if summary_failure(s):
            checked.append([name, "run", s["ipopt_status"], "-", "-", "-", summary_failure(s), "FAIL"])
        for q, r in s["results"].items():
            c = verdicts.check(name, q)
            reference, error, tolerance, verdict = verdicts.verdict(name, q, r, stored)
            ref = "-" if reference is None else f"{reference:.7g}"
            if verdict == "info":
                info.append([name, q, f"{r['computed']:.7g}", ref, c.note])
                continue
            err = "-" if error is None else f"{error:.2e}"
            checked.append([name, q, f"{r['computed']:.7g}", ref, c.kind, tolerance, err, verdict])
    passed = sum(r[-1] == "PASS" for r in checked)
    failed = sum(r[-1] in ("FAIL", "missing") for r in checked)
    return checked, info, missing, passed, failed


CHECK_HEADER = ["benchmark", "quantity", "computed", "reference", "reference kind", "tolerance", "error", "verdict"]
INFO_HEADER = ["benchmark", "quantity", "computed", "reference", "note"]
OVERVIEW_HEADER = ["benchmark family", "verdicts", "headline: computed against reference (error, bound)", "figure", "reproduce"]
KINDS_TEXT = ("Reference kinds: **exact**, an exact solution of the discrete problem or an exact identity (the "
              "applied load); **analytic**, a formula of the continuous problem (Hertz); **mesh-converged**, "
              "extrapolated from a mesh study of our own; **empirical**, an empirical law (Lindley's), held to our "
              "mesh study; **balance**, an equilibrium or symmetry identity that holds to the solver's tolerance. "
              "The tolerances are those `make test` holds the same runs to (scripts/verdicts.py). The error column "
              "is relative unless marked abs; for `value` checks it is the quantity itself.")

# The overview's row of each section (by the start of its title): a short name and the one or two
# quantities a reader checks first
HEADLINES = [
    ("Hertz contact on a rigid plane", "Hertz, rigid plane", [("hertz_plane", "a"), ("hertz_plane", "p_max")]),
    ("Hertz contact on a rigid cylinder", "Hertz, rigid cylinder", [("hertz_circle_vertical", "a"), ("hertz_circle_exact", "a")]),
    ("3D Hertz", "Hertz, 3D and axisymmetric sphere", [("hertz_sphere", "a"), ("hertz_sphere_axisymmetric", "a")]),
    ("Contact between two elastic bodies", "Two elastic bodies", [("hertz_two_cylinders", "a"), ("hertz_two_spheres", "a")]),
    ("O-ring between elastic flanges", "O-ring, elastic flanges", [("oring_flange_steel", "action_reaction_rel_error")]),
    ("Coulomb friction", "Coulomb friction (Cattaneo, Mindlin)", [("cattaneo", "stick_half_width"), ("mindlin_sphere", "stick_radius")]),
    ("Dynamics", "Dynamics: impact", [("bar_impact", "rebound_velocity"), ("sphere_impact", "peak_force")]),
    ("The contact patch test", "Contact patch test", [("patch_test", "pressure_spread"), ("patch_test", "stress_error_rel")]),
    ("Large sliding", "Large sliding", [("sliding_disc", "sideways_force_ratio")]),
    ("Clamped square", "Clamped square", [("clamped_square", "contact_force")]),
    ("O-ring gasket", "O-ring gasket", [("oring_plates", "force_c0.2"), ("oring_groove", "floor_wall_symmetry_rel_error")]),
    ("O-ring seal under fluid", "O-ring seal under fluid pressure", [("seal", "sealing_margin"), ("seal", "leaked")]),
    ("Rubber block pushed", "Block on a wavy floor", [("platen_block", "platen_force")]),
    ("3D rubber contact", "Indentation, axi and 3D", [("indentation_axi", "force_small_depth"), ("indentation_3d", "force_small_depth")]),
    ("Rubber at and near incompressibility", "Incompressible rubber", [("rivlin_tube", "outer_radius"), ("hertz_plane_nu0.4999", "a")]),
    ("Hyperelastic cube", "Hyperelastic cube", [("cube_2d_neohookean", "w"), ("cube_3d_neohookean", "w")]),
    ("Convergence and solver effort", "Convergence, solver effort", []),
]


def slug(title):
    """GitHub's anchor of a heading (lowercase, punctuation dropped, spaces to '-'); the HTML uses it too."""
    text = "".join(ch for ch in title.lower() if ch.isalnum() or ch in " -_")
    return text.replace(" ", "-")


def headline_of(title):
    return next(((short, quantities) for key, short, quantities in HEADLINES if title.startswith(key)), (title, []))


def headline_text(bench, quantity):
    """'a = 0.05507 against 0.05509 (3.2e-04, bound 3.0e-03)', or None when the run is missing."""
    s = summary(bench)
    if not s or quantity not in s["results"]:
        return None
    r = s["results"][quantity]
    reference, error, tolerance, verdict = verdicts.verdict(bench, quantity, r, stored_reference(bench))
    text = f"{quantity} = {r['computed']:.5g}"
    if reference is not None and verdicts.check(bench, quantity).measure != "value":
        text += f" against {reference:.5g}"
    if error is not None:
        text += f" ({error:.1e}, {tolerance})"
    return text + ("" if verdict in ("PASS", "info") else f" {verdict}")


def thumbnail(figure):
    """A small copy of a figure for the overview (figures/thumbs/), or None."""
    try:
        from PIL import Image
        os.makedirs(os.path.join(RESULTS, FIGURES, "thumbs"), exist_ok=True)
        image = Image.open(os.path.join(RESULTS, FIGURES, figure))
        image.thumbnail((240, 80))
        image.save(os.path.join(RESULTS, FIGURES, "thumbs", figure), optimize=True)
        return f"thumbs/{figure}"
    except Exception as exc:   # no Pillow, or an unreadable figure: the overview goes without
        print(f"report: no thumbnail of {figure}: {exc!r}", flush=True)
        return None


def assemble():
    """The report's parts: the verdict counts, the overview rows and the sections, each section with
    its figures, commands, its own verdict rows and informational rows (every benchmark lands in one
    section: those of no section in a last one)."""
    checked, info, absent, passed, failed = verdict_tables()
    parts = []
    placed = set()
    for title, names, about, builders in sections():
        parts.append({"title": title, "names": list(names), "about": about, "builders": builders})
        placed.update(names)
    others = [n for n, _, _ in BENCHMARKS if n not in placed]
    if others:
        parts.append({"title": "Other checks", "names": others, "about": "Benchmarks of no section above.", "builders": []})
    produced = []
    for part in parts:
        part["anchor"] = slug(part["title"])
        part["commands"] = [command(n) for n in part["names"] if command(n)]
        part["checked"] = [r for r in checked if r[0] in part["names"]]
        part["info"] = [r for r in info if r[0] in part["names"]]
        part["passed"] = sum(r[-1] == "PASS" for r in part["checked"])
        part["failed"] = sum(r[-1] in ("FAIL", "missing") for r in part["checked"])
        part["figures"] = []
        for build in part["builders"]:
            try:
                f = build()
            except Exception as exc:  # a figure that cannot be drawn is reported, not fatal
                print(f"report: figure failed in '{part['title']}': {exc!r}", flush=True)
                f = None
            if f:
                part["figures"].append(f)
                produced.append(f)
        part["thumbnail"] = thumbnail(part["figures"][0]) if part["figures"] else None
        part["short"], quantities = headline_of(part["title"])
        several = len({b for b, _ in quantities}) > 1   # name the run when the headlines come from two
        part["headlines"] = [(f"{b}: " if several else "") + t for b, t in ((b, headline_text(b, q)) for b, q in quantities) if t]
    verdict_line = f"**{passed} PASS, {failed} FAIL** over {len(checked)} checked quantities" + \
        (f" ({len(absent)} benchmarks not run)" if absent else "")
    return verdict_line, parts, produced, absent


def verdict_summary(part):
    """'9 PASS', '4 PASS, 6 FAIL', '2 PASS, 1 not run', 'not run' or '-' (no checked quantity)."""
    missing = sum(r[-1] == "missing" for r in part["checked"])
    failed = part["failed"] - missing
    if not part["checked"]:
        return "-"
    if missing == len(part["checked"]):
        return "not run"
    return ", ".join(t for t in (f"{part['passed']} PASS", f"{failed} FAIL" if failed else "",
                                 f"{missing} not run" if missing else "") if t)


def write_markdown(verdict_line, parts, absent):
    md = ["# Contact benchmarks: report", "", verdict_line, "", "## Overview", "",
          "| " + " | ".join(OVERVIEW_HEADER) + " |", "|" + "---|" * len(OVERVIEW_HEADER)]
    for part in parts:
        verdict = verdict_summary(part)
        if part["failed"]:
            verdict = f"**{verdict}**"
        thumb = f"<img src=\"{FIGURES}/{part['thumbnail']}\" height=\"40\">" if part["thumbnail"] else ""
        cmd = f"`{part['commands'][0]}`" if part["commands"] else ""
        md.append(f"| [{part['short']}](#{part['anchor']}) | {verdict} | {'; '.join(part['headlines'])} | {thumb} | {cmd} |")
    md += [""] + ([f"Not run: {', '.join(absent)}.", ""] if absent else []) + [KINDS_TEXT]
    for part in parts:
        md += ["", f"## {part['title']}", "", part["about"], ""]
        if part["commands"]:
            md += ["```sh"] + part["commands"] + ["```", ""]
        for f in part["figures"]:
            md += [f"![{f}]({FIGURES}/{f})", ""]
        if part["checked"]:
            md += [f"<details{' open' if part['failed'] else ''}><summary>Verdicts: {verdict_summary(part)}</summary>", "",
                   md_tables.table(CHECK_HEADER, part["checked"]), "", "</details>", ""]
        if part["info"]:
            md += [f"<details><summary>Informational quantities ({len(part['info'])})</summary>", "",
                   md_tables.table(INFO_HEADER, part["info"]), "", "</details>", ""]
    with open(os.path.join(RESULTS, "REPORT.md"), "w") as fh:
        fh.write("\n".join(md) + "\n")


def main():
    global RESULTS
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", default=RESULTS)
    RESULTS = os.path.abspath(parser.parse_args().results)
    verdict_line, parts, produced, absent = assemble()
    write_markdown(verdict_line, parts, absent)
    write_html(verdict_line, parts, absent)
    where = os.path.relpath(RESULTS, os.getcwd())
    where = RESULTS if where.startswith("..") else where
    print(f"report: {where}/report.html (self-contained: open it in a browser) and {where}/REPORT.md, {len(produced)} figures",
          flush=True)
    print("  " + verdict_line.replace("**", ""))
    width = max(len(p["short"]) for p in parts)
    for part in parts:
        print(f"  {part['short']:<{width}}  {verdict_summary(part):<16}  {'; '.join(part['headlines'])}")
    return 0


STYLE = ("body{font-family:sans-serif;max-width:1300px;margin:auto;padding:0 1em;font-size:14px}"
         "h1{font-size:20px;margin:8px 0 4px}h2{font-size:17px;margin-top:1.6em;border-top:1px solid #ccc;padding-top:.6em}"
         "p.counts{margin:2px 0 6px;font-weight:bold}p.counts.fail{color:#b00}"
         "table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #ccc;padding:2px 6px;vertical-align:middle}"
         "th{background:#eee}tr.fail{background:#f6c6c6}tr.fail td:first-child a{color:#900;font-weight:bold}"
         "#overview td{padding:1px 6px}#overview img{height:36px;display:block}"
         "#overview code{display:inline-block;max-width:330px;overflow:hidden;text-overflow:ellipsis;white-space:nowrap;"
         "vertical-align:middle;font-size:11px}"
         "nav{font-size:12px;margin:6px 0}nav a{margin-right:.8em}"
         "img.figure{max-width:100%;margin:8px 0}pre{background:#f4f4f4;padding:6px;overflow-x:auto}"
         "details{margin:6px 0}summary{cursor:pointer;font-weight:bold}")


def write_html(verdict_line, parts, absent):
    esc = html.escape
    counts = verdict_line.replace("**", "")
    failing = any(part["failed"] for part in parts)
    out = ["<!doctype html><html lang='en'><head><meta charset='utf-8'><title>Contact benchmarks: report</title>",
           f"<style>{STYLE}</style></head><body>",
           "<h1>Contact of hyperelastic bodies: benchmark report</h1>",
           f"<p class='counts{' fail' if failing else ''}' id='counts'>{esc(counts)}</p>",
           "<table id='overview'><tr>" + "".join(f"<th>{esc(h)}</th>" for h in OVERVIEW_HEADER) + "</tr>"]
    for part in parts:
        thumb = ""
        if part["thumbnail"]:
            data = base64.b64encode(open(os.path.join(RESULTS, FIGURES, part["thumbnail"]), "rb").read()).decode()
            thumb = f"<a href='#{part['anchor']}'><img alt='{esc(part['figures'][0])}' src='data:image/png;base64,{data}'></a>"
        cmd = part["commands"][0] if part["commands"] else ""
        out.append(f"<tr class='{'fail' if part['failed'] else 'pass'}' data-section='{part['anchor']}'>"
                   f"<td><a href='#{part['anchor']}'>{esc(part['short'])}</a></td><td>{esc(verdict_summary(part))}</td>"
                   f"<td>{'<br>'.join(esc(t) for t in part['headlines'])}</td><td>{thumb}</td>"
                   f"<td><code title='{esc(cmd)}'>{esc(cmd)}</code></td></tr>")
    out.append("</table>")
    if absent:
        out.append(f"<p>Not run: {esc(', '.join(absent))}.</p>")
    out.append("<nav id='contents'>Contents: " + "".join(f"<a href='#{p['anchor']}'>{esc(p['short'])}</a>" for p in parts) + "</nav>")
    out.append(f"<p>{esc(KINDS_TEXT.replace('**', ''))}</p>")
    for part in parts:
        out.append(f"<section id='{part['anchor']}'><h2>{esc(part['title'])}</h2><p>{esc(part['about'])}</p>")
        if part["commands"]:
            out.append("<pre>" + esc("\n".join(part["commands"])) + "</pre>")
        for f in part["figures"]:
            data = base64.b64encode(open(os.path.join(RESULTS, FIGURES, f), "rb").read()).decode()
            out.append(f"<img class='figure' alt='{esc(f)}' src='data:image/png;base64,{data}'>")
        for rows, header, label, opened in ((part["checked"], CHECK_HEADER, f"Verdicts: {verdict_summary(part)}", part["failed"] > 0),
                                            (part["info"], INFO_HEADER, f"Informational quantities ({len(part['info'])})", False)):
            if not rows:
                continue
            out.append(f"<details{' open' if opened else ''}><summary>{esc(label)}</summary><table><tr>"
                       + "".join(f"<th>{esc(h)}</th>" for h in header) + "</tr>")
            for r in rows:
                out.append(f"<tr class='{'fail' if r[-1] in ('FAIL', 'missing') else ''}'>" + "".join(f"<td>{esc(c)}</td>" for c in r) + "</tr>")
            out.append("</table></details>")
        out.append("</section>")
    out.append("</body></html>")
    with open(os.path.join(RESULTS, "report.html"), "w") as fh:
        fh.write("\n".join(out))


if __name__ == "__main__":
    sys.exit(main())
