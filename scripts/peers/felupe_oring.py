#!/usr/bin/python3
"""The O-ring between rigid plates computed with FElupe, as a peer of `benchmarks/oring.edp -case plates`.

Our driver squeezes the plane-strain cross-section of an O-ring (a disc of radius R, a quarter by
symmetry) between two rigid frictionless plates and reports the plate force per unit length against
Lindley's empirical law. This script sets up the same problem in FElupe (an independent Python
finite-element code) so that cost and accuracy can be compared at equal numbers of unknowns:

- geometry: the quarter disc x, y >= 0 of radius R (default 0.52); u_x = 0 on x = 0, u_y = 0 on y = 0;
- material: the Neo-Hookean law (48) of our suite with C01 = 0,
      psi = C10 (J^(-2/3) I1 - 3) + K/2 (J - 1)^2,  K = 2 C10 / (1 - 2 nu),
  C10 = 1.2345, nu = 0.499, in plane strain (I1 includes C33 = 1). FElupe's NeoHooke(mu, bulk) is the
  same energy with mu = 2 C10;
- loading: the rigid plate starts tangent to the disc at y = R and moves down by c R, c = cmax t,
  in `--steps` equal load steps (default 15, cmax = 0.3): the squeeze of the whole ring
  c = delta / (2R);
- output: the force per unit length of the whole ring, 2 x the force on the quarter, at c = 0.1,
  0.2 and 0.3, each against Lindley's F = E d (1.25 c^1.5 + 50 c^6), E = 6 C10, d = 2R: the
  "force_c0.x" entries of our summary.json.

Formulations (`--formulation`):
- `p1`: linear triangles (felupe.RegionTriangle), displacement only: the element-wise volumetric
  penalty, which locks as nu -> 1/2 (our `-volumetric penalty`);
- `mixed`: bilinear quads with a cell-wise constant pressure and volume ratio (Q1/P0, the
  three-field Hu-Washizu variation), locking-free like our default `-volumetric nodal`. By default
  FElupe's SolidBodyNearlyIncompressible, which condenses p and Jbar cell by cell (the global
  unknowns are the displacements only); `--mixed-variant threefield` keeps p and Jbar as global
  unknowns (felupe.FieldsMixed with NearlyIncompressible, the same discrete problem).

Mesh: FElupe's own quarter circle (felupe.Circle with one 90-degree section: a quad mesh, split
into triangles for `p1`). `--h` is the element size of the FreeFEM run to match: the number of
divisions is chosen so that the number of points is closest to that of our uniform quarter-ring
mesh of size h (`--n` sets the divisions directly). Circle's mesh is not uniform: it is finer
inside than on the arc. `--mesh-from FILE.msh` reads a FreeFEM mesh (savemesh format) instead, and
`--mesh-from freefem` makes the very mesh of our driver with FreeFem++ (include/mesh/quarter_ring_mesh.idp)
and reads it (`p1` only: it is made of triangles). On that mesh the `p1` variant is the same
discrete problem as `oring.edp -case plates -volumetric penalty`: the forces agree to about 1e-5,
the size of the contact penalty's penetration (measured at R/12 and R/24).

Contact: felupe.ContactRigidPlane, a node-to-surface penalty contact with a rigid plane attached to
an extra centre point whose displacement is prescribed; the candidates are the points of the arc.
Its penalty lambda_n is `--multiplier` times the mean normal diagonal stiffness of the solid at the
candidates (FElupe's stiffness-based multiplier, evaluated once per load step). A penalty lets the
plate penetrate by f / lambda_n: the reported `max_penetration` measures it, and the force can be
checked against a larger multiplier.

Solver: FElupe's Newton-Raphson (felupe.newtonraphson) with SciPy's sparse direct solver (its
default), one call per load step started from the previous step's solution, FElupe's default
tolerance unless `--tol` is given.

Output: one line `RESULT {json}` with the DOFs, the Newton iterations (total and per step), the
time of the Newton solves of the load-step loop (`solve_s`; `loop_s` adds the per-step bookkeeping),
the wall time of the process that runs inside the venv (`wall_s`: imports, meshing and the loop;
the venv check and re-exec before it take about 0.1 s more), and force_c0.1/0.2/0.3 as {computed, reference,
ratio}, plus the plate force taken two ways (contact reaction at the plate and support reaction
on y = 0: they agree at equilibrium) and the penetration.

Environment: run it with Debian's /usr/bin/python3. The script creates a virtual environment in
results/peers/venv (python3 -m venv, Debian's package python3-venv), installs felupe 11.3.0 into
it (or the closest version pip can get if that one cannot be installed), and runs itself again
inside it. Set OMP_NUM_THREADS=1 for timings comparable with a single-threaded FreeFEM run.

    /usr/bin/python3 scripts/peers/felupe_oring.py --h R/24 --formulation p1
    /usr/bin/python3 scripts/peers/felupe_oring.py --h 0.021666666666666667 --formulation mixed --steps 15
    /usr/bin/python3 scripts/peers/felupe_oring.py --h R/24 --formulation p1 --mesh-from freefem

Our driver's sizes are `-h R/k` as numbers: R/12 = 0.043333333333333335, R/24 = 0.021666666666666667,
R/48 = 0.010833333333333334 (give all the digits: the mesh's radial divisions are ceil(R/h), and
0.0433333 gives 13 where R/12 gives 12).
"""

import os
import sys
import time

WALL_START = time.perf_counter()

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))   # scripts/peers/ -> the suite
VENV = os.path.join(REPO, "results", "peers", "venv")
FELUPE_PIN = "11.3.0"
REEXEC_FLAG = "FELUPE_ORING_IN_VENV"


def _venv_python():
    return os.path.join(VENV, "bin", "python")


def _inside_venv():
    return os.path.realpath(sys.prefix) == os.path.realpath(VENV)


def _bootstrap():
    """Create the venv and install felupe if needed, then re-run this script inside it."""
    import subprocess

    python = _venv_python()
    if not os.path.exists(python):
        os.makedirs(os.path.dirname(VENV), exist_ok=True)
        print(f"creating the virtual environment {VENV}", file=sys.stderr)
        try:
            subprocess.run(["/usr/bin/python3", "-m", "venv", VENV], check=True)
        except (subprocess.CalledProcessError, FileNotFoundError) as error:
            sys.exit(f"error: cannot create the venv ({error}); on Debian: apt-get install -y python3-venv")
    # find the packages without importing them (an import of felupe costs most of a second)
    find = "import importlib.util as u, sys; sys.exit(not (u.find_spec('felupe') and u.find_spec('scipy')))"
    probe = subprocess.run([python, "-c", find], capture_output=True)
    if probe.returncode != 0:
        pip = [python, "-m", "pip", "install", "--disable-pip-version-check", "-q"]
        print(f"installing felupe=={FELUPE_PIN} into {VENV}", file=sys.stderr)
        if subprocess.run(pip + [f"felupe=={FELUPE_PIN}", "scipy"]).returncode != 0:
            print(f"felupe=={FELUPE_PIN} could not be installed; trying the closest available", file=sys.stderr)
            # the newest release of the same major version, else the newest at all
            major = FELUPE_PIN.split(".")[0]
            if subprocess.run(pip + [f"felupe>={major},<{int(major) + 1}", "scipy"]).returncode != 0:
                if subprocess.run(pip + ["felupe", "scipy"]).returncode != 0:
                    sys.exit("error: pip could not install felupe")
    env = dict(os.environ)
    env[REEXEC_FLAG] = "1"
    os.execve(python, [python, os.path.abspath(__file__)] + sys.argv[1:], env)


if not _inside_venv():
    if os.environ.get(REEXEC_FLAG):
        sys.exit(f"error: re-executed but not inside {VENV}")
    _bootstrap()

# ---------------------------------------------------------------------------------------------
# inside the venv from here on

import argparse
import json
import math
import platform
import subprocess
import tempfile

IMPORT_START = time.perf_counter()
import numpy as np
import scipy
import felupe as fem

IMPORT_S = time.perf_counter() - IMPORT_START


# The contact penalty's scale. FElupe's default, 1, lets the plate penetrate by 0.1-0.2 % of its
# travel and lowers the force at c = 0.3 by 0.25 % at R/12 and 0.11-0.15 % at R/24 (P1, Q1/P0),
# more than the discretisation error of our nodal runs; 100 brings both below 3e-5 at no cost in
# Newton iterations. The threefield variant's base (the u-u diagonal, without the bulk part) is about 200
# times smaller than the condensed variant's, hence its larger scale: the same penalty in effect.
DEFAULT_MULTIPLIER = 100.0
DEFAULT_MULTIPLIER_THREEFIELD = 2.0e4


def parse_args(argv):
    p = argparse.ArgumentParser(
        description="FElupe peer of `oring.edp -case plates` (see the module docstring)."
    )
    p.add_argument("--h", default=None,
                   help="element size of the FreeFEM mesh to match in points: a number or R/k, e.g. R/24 "
                        "(default R/24, the driver's)")
    p.add_argument("--formulation", choices=["p1", "mixed"], default="p1")
    p.add_argument("--mixed-variant", choices=["condensed", "threefield"], default="condensed",
                   help="mixed: SolidBodyNearlyIncompressible (p, Jbar condensed per cell) or "
                        "FieldsMixed + NearlyIncompressible (p, Jbar global unknowns)")
    p.add_argument("--steps", type=int, default=15)
    p.add_argument("--n", type=int, default=None,
                   help="felupe.Circle points per 45-degree edge (overrides the choice from --h)")
    p.add_argument("--mesh-from", default=None,
                   help="a FreeFEM .msh file of the quarter disc (labels 1: x = 0, 2: y = 0, 3: arc), "
                        "or 'freefem' to make our driver's mesh with FreeFem++ (p1 only)")
    p.add_argument("--multiplier", type=float, default=None,
                   help="contact penalty: times the mean normal diagonal stiffness at the candidates "
                        f"(default {DEFAULT_MULTIPLIER:g}; {DEFAULT_MULTIPLIER_THREEFIELD:g} with the threefield "
                        "variant, whose displacement block lacks the bulk stiffness)")
    p.add_argument("--tol", type=float, default=None, help="Newton tolerance (default FElupe's, sqrt(eps))")
    p.add_argument("--maxiter", type=int, default=30, help="Newton iterations per load step")
    p.add_argument("--R", type=float, default=0.52)
    p.add_argument("--C10", type=float, default=1.2345)
    p.add_argument("--nu", type=float, default=0.499)
    p.add_argument("--cmax", type=float, default=0.3)
    p.add_argument("--verbose", action="store_true", help="print each load step")
    a = p.parse_args(argv)
    if a.h is None:
        a.h = "R/24"
    text = a.h.replace(" ", "")
    try:
        a.h = a.R / float(text[2:]) if text.upper().startswith("R/") else float(text)
    except ValueError:
        p.error(f"--h must be a number or R/k, got {text!r}")
    if not (0 < a.h < a.R):
        p.error(f"--h must lie in (0, R = {a.R}), got {a.h}")
    if a.steps < 1:
        p.error("--steps must be >= 1")
    if not (0 < a.cmax < 0.9):
        p.error("--cmax must lie in (0, 0.9)")
    if not (-1 < a.nu < 0.5):
        p.error("--nu must lie in (-1, 0.5)")
    if a.multiplier is None:
        threefield = a.formulation == "mixed" and a.mixed_variant == "threefield"
        a.multiplier = DEFAULT_MULTIPLIER_THREEFIELD if threefield else DEFAULT_MULTIPLIER
    if a.multiplier <= 0:
        p.error("--multiplier must be > 0")
    if a.n is not None and a.n < 2:
        p.error("--n must be >= 2")
    if a.mesh_from is not None and a.formulation == "mixed":
        p.error("--mesh-from gives triangles: the mixed (Q1/P0) variant needs FElupe's quad mesh")
    return a


# ---------------------------------------------------------------------------------------------
# meshes


def freefem_points_estimate(R, h):
    """Points of our uniform quarter-ring mesh of size h (quarter_ring_mesh.idp): equilateral
    triangles of side h over the area, plus half a layer along the boundary. Within 6 % of the
    real counts (152/161, 565/573, 2175/2180 at R/12, R/24, R/48)."""
    area = math.pi * R * R / 4
    perimeter = (2 + math.pi / 2) * R
    return 2 / math.sqrt(3) * area / h**2 + perimeter / (2 * h) + 1


def circle_divisions(R, h):
    """felupe.Circle's n (points per 45-degree edge) whose quarter has the number of points
    closest to our mesh of size h: a quarter Circle has 3 m^2 + 3 m + 1 points, m = n - 1."""
    target = freefem_points_estimate(R, h)
    m = (-3 + math.sqrt(9 - 12 * (1 - target))) / 6
    candidates = [max(1, math.floor(m)), max(1, math.ceil(m))]
    best = min(candidates, key=lambda k: abs(3 * k * k + 3 * k + 1 - target))
    return best + 1


def circle_mesh(R, n):
    """FElupe's quarter disc (quads) and its boundary point sets."""
    mesh = fem.Circle(radius=R, centerpoint=(0.0, 0.0), n=n, sections=[0])
    x, y = mesh.points.T
    tol = 1e-9 * R
    sets = {
        "symmetry_x": np.where(np.abs(x) < tol)[0],
        "symmetry_y": np.where(np.abs(y) < tol)[0],
        "arc": np.where(np.abs(np.hypot(x, y) - R) < 1e-8 * R)[0],
    }
    return mesh, sets


def read_freefem_mesh(path):
    """A FreeFEM .msh (savemesh): 'nv nt nbe', nv lines 'x y label', nt lines 'i j k region',
    nbe lines 'i j label' (1-based). Returns the triangle mesh and the points of boundary labels
    1 (x = 0), 2 (y = 0) and 3 (arc), as our driver selects them."""
    with open(path) as f:
        tokens = f.read().split()
    nv, nt, nbe = (int(t) for t in tokens[:3])
    pos = 3
    vertices = np.array(tokens[pos:pos + 3 * nv], dtype=float).reshape(nv, 3)
    pos += 3 * nv
    triangles = np.array(tokens[pos:pos + 4 * nt], dtype=int).reshape(nt, 4)
    pos += 4 * nt
    edges = np.array(tokens[pos:pos + 3 * nbe], dtype=int).reshape(nbe, 3)
    points = vertices[:, :2].copy()
    cells = triangles[:, :3] - 1
    # FElupe's triangle expects counter-clockwise cells
    p0, p1, p2 = points[cells[:, 0]], points[cells[:, 1]], points[cells[:, 2]]
    area2 = (p1[:, 0] - p0[:, 0]) * (p2[:, 1] - p0[:, 1]) - (p1[:, 1] - p0[:, 1]) * (p2[:, 0] - p0[:, 0])
    flip = area2 < 0
    cells[flip] = cells[flip][:, [0, 2, 1]]
    mesh = fem.Mesh(points, cells, "triangle")

    def label_points(label):
        return np.unique(edges[edges[:, 2] == label, :2].ravel() - 1)

    sets = {"symmetry_x": label_points(1), "symmetry_y": label_points(2), "arc": label_points(3)}
    for name, value in sets.items():
        if len(value) == 0:
            sys.exit(f"error: {path}: no boundary edge with the label of {name}")
    return mesh, sets


def make_freefem_mesh(R, h):
    """Our driver's mesh (quarterRingMesh of include/mesh/quarter_ring_mesh.idp), made by FreeFem++
    in results/peers/meshes/ and read back."""
    folder = os.path.join(REPO, "results", "peers", "meshes")
    os.makedirs(folder, exist_ok=True)
    target = os.path.join(folder, f"quarter_ring_R{R!r}_h{h!r}.msh")
    if not os.path.exists(target):
        script = (
            'include "mesh/quarter_ring_mesh.idp"\n'
            f"real ringRadius = {R!r}, ringSize = {h!r};\n"
            "mesh Th;\n"
            "quarterRingMesh(Th, ringRadius, ringSize)\n"
            f'savemesh(Th, "{target}");\n'
        )
        with tempfile.NamedTemporaryFile("w", suffix=".edp", dir=folder, delete=False) as f:
            f.write(script)
            edp = f.name
        try:
            # from the repository root, where freefem++.pref gives the include path
            run = subprocess.run(["FreeFem++", "-nw", edp], cwd=REPO, capture_output=True, text=True)
        except FileNotFoundError:
            sys.exit("error: FreeFem++ not found (needed by --mesh-from freefem)")
        finally:
            os.unlink(edp)
        if run.returncode != 0 or not os.path.exists(target):
            sys.exit(f"error: FreeFem++ could not write the mesh:\n{run.stdout}\n{run.stderr}")
    return target


# ---------------------------------------------------------------------------------------------
# the problem


def lindley(C10, R, c):
    """Lindley's force per unit length: F = E d (1.25 c^1.5 + 50 c^6), E = 6 (C10 + C01), d = 2R."""
    return 6 * C10 * 2 * R * (1.25 * c**1.5 + 50 * c**6)


def main(argv):
    args = parse_args(argv)
    R, C10, nu = args.R, args.C10, args.nu
    mu = 2 * C10
    bulk = 2 * C10 / (1 - 2 * nu)

    # mesh and boundary sets
    t_setup = time.perf_counter()
    mesh_source = "felupe.Circle"
    n = None
    if args.mesh_from is not None:
        path = make_freefem_mesh(R, args.h) if args.mesh_from == "freefem" else args.mesh_from
        mesh, sets = read_freefem_mesh(path)
        mesh_source = f"freefem:{os.path.relpath(path, REPO) if path.startswith(REPO) else path}"
    else:
        n = args.n if args.n is not None else circle_divisions(R, args.h)
        mesh, sets = circle_mesh(R, n)
        if args.formulation == "p1":
            mesh = mesh.triangulate()
    body_points = mesh.npoints
    body_cells = mesh.ncells
    cell_type = mesh.cell_type
    # the plate's reference point (a point without cells), on the plate's line y = R
    mesh.add_points(np.array([[0.0, R]]))
    plate_point = mesh.npoints - 1

    if args.formulation == "p1":
        region = fem.RegionTriangle(mesh)
        field = fem.FieldContainer([fem.FieldPlaneStrain(region, dim=2)])
        solid = fem.SolidBody(fem.NeoHooke(mu=mu, bulk=bulk), field)
        element = "P1 triangles, displacement only"
    elif args.mixed_variant == "condensed":
        region = fem.RegionQuad(mesh)
        field = fem.FieldContainer([fem.FieldPlaneStrain(region, dim=2)])
        solid = fem.SolidBodyNearlyIncompressible(fem.NeoHooke(mu=mu), field, bulk=bulk)
        element = "Q1/P0 quads, p and Jbar condensed per cell (SolidBodyNearlyIncompressible)"
    else:
        region = fem.RegionQuad(mesh)
        field = fem.FieldsMixed(region, n=3, planestrain=True)
        solid = fem.SolidBody(fem.NearlyIncompressible(fem.NeoHooke(mu=mu), bulk=bulk), field)
        element = "Q1/P0 quads, p and Jbar global (FieldsMixed + NearlyIncompressible)"
    u = field[0]

    contact = fem.ContactRigidPlane(
        field,
        points=sets["arc"],
        centerpoint=plate_point,
        normal=[0.0, -1.0],
        multiplier=args.multiplier,
        items=[solid],
    )
    body = np.zeros(mesh.npoints, dtype=bool)
    body[:body_points] = True

    def on(points):
        mask = np.zeros(mesh.npoints, dtype=bool)
        mask[points] = True
        return mask & body

    plate_mask = np.arange(mesh.npoints) == plate_point
    boundaries = {
        "symmetry_x": fem.Boundary(u, mask=on(sets["symmetry_x"]), skip=(0, 1)),   # u_x = 0
        "symmetry_y": fem.Boundary(u, mask=on(sets["symmetry_y"]), skip=(1, 0)),   # u_y = 0
        "plate_x": fem.Boundary(u, mask=plate_mask, skip=(0, 1)),                   # the plate moves
        "plate_y": fem.Boundary(u, mask=plate_mask, skip=(1, 0)),                   # vertically only
    }
    ndof_displacement = 2 * body_points
    ndof_total = sum(f.values.size for f in field.fields) - 2   # without the plate point
    setup_s = time.perf_counter() - t_setup

    # dofs of the reactions: the plate's y and the supports on y = 0
    plate_dof = 2 * plate_point + 1
    support_dofs = 2 * sets["symmetry_y"] + 1

    newton_kwargs = dict(maxiter=args.maxiter, verbose=0)
    if args.tol is not None:
        newton_kwargs["tol"] = args.tol

    records = []
    forces = {}
    iterations = []
    solve_s = 0.0
    failure = None
    t_loop = time.perf_counter()
    for k in range(1, args.steps + 1):
        t = k / args.steps
        c = args.cmax * t
        boundaries["plate_y"].update(-c * R)
        dof0, dof1 = fem.dof.partition(field, boundaries)
        ext0 = fem.dof.apply(field, boundaries, dof0)
        t0 = time.perf_counter()
        try:
            res = fem.newtonraphson(items=[solid, contact], x0=field, dof0=dof0, dof1=dof1, ext0=ext0,
                                    **newton_kwargs)
        except Exception as error:   # FElupe raises NewtonConvergenceError (a ValueError)
            solve_s += time.perf_counter() - t0
            failure = f"step {k}: {type(error).__name__}: {error}"
            break
        solve_s += time.perf_counter() - t0
        if not res.success:
            failure = f"step {k}: Newton did not converge in {args.maxiter} iterations"
            break
        field.link(res.x)
        iterations.append(int(res.iterations))
        # the residual at the prescribed dofs holds the reactions
        residual = np.asarray(res.fun).ravel()
        plate_quarter = abs(residual[plate_dof])
        support_quarter = abs(residual[support_dofs].sum())
        gaps = (mesh.points[sets["arc"]] + u.values[sets["arc"]] - (mesh.points[plate_point] + u.values[plate_point]))
        penetration = max(0.0, float(np.max(gaps[:, 1])))   # gap = -(dy): penetration where dy > 0
        force = 2 * plate_quarter
        reference = lindley(C10, R, c)
        records.append({"c": c, "force_per_length": force, "support_force_per_length": 2 * support_quarter,
                        "lindley": reference, "ratio": force / reference, "iterations": int(res.iterations),
                        "max_penetration": penetration, "active_points": int(np.sum(gaps[:, 1] > 0))})
        for j in (1, 2, 3):
            if abs(c - 0.1 * j) < 1e-9:
                forces[f"force_c0.{j}"] = {"computed": force, "reference": reference, "ratio": force / reference,
                                           "rel_error": abs(force - reference) / reference}
        if args.verbose:
            print(f"  step {k:2d}  c = {c:.4f}  Newton {res.iterations:2d}  force {force:.6g}  "
                  f"(support {2 * support_quarter:.6g})  Lindley {reference:.6g}  ratio {force / reference:.5f}  "
                  f"penetration {penetration:.3g}", file=sys.stderr)
    loop_s = time.perf_counter() - t_loop

    last = records[-1] if records else {}
    result = {
        "code": "felupe",
        "felupe": fem.__version__,
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "python": platform.python_version(),
        "omp_num_threads": os.environ.get("OMP_NUM_THREADS"),
        "formulation": args.formulation,
        "mixed_variant": args.mixed_variant if args.formulation == "mixed" else None,
        "element": element,
        "mesh": mesh_source,
        "circle_n": n,
        "h": args.h,
        "R": R, "C10": C10, "nu": nu, "mu": mu, "bulk": bulk, "cmax": args.cmax, "steps": args.steps,
        "points": body_points,
        "cells": body_cells,
        "cell_type": cell_type,
        "ndof": ndof_displacement,
        "ndof_total": ndof_total,
        "free_dofs": int(len(dof1)),
        "candidates": int(len(sets["arc"])),
        "contact_multiplier_scale": args.multiplier,
        "contact_lambda_n": float(contact.multipliers.normal) if contact.multipliers is not None else None,
        "newton_tol": args.tol if args.tol is not None else float(np.sqrt(np.finfo(float).eps)),
        "newton_iterations": int(sum(iterations)),
        "step_iterations": iterations,
        "complete": failure is None,
        "failure": failure,
        "import_s": IMPORT_S,
        "setup_s": setup_s,
        "solve_s": solve_s,
        "loop_s": loop_s,
        "wall_s": time.perf_counter() - WALL_START,
        "results": forces,
        "final_support_force_per_length": last.get("support_force_per_length"),
        "max_penetration": last.get("max_penetration"),
        "max_penetration_rel_travel": (last["max_penetration"] / (args.cmax * R)) if last else None,
        "active_points": last.get("active_points"),
        "curve": records,
    }
    print("RESULT " + json.dumps(result), flush=True)
    return 0 if failure is None else 3


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
