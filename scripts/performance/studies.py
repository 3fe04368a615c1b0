#!/usr/bin/env python3
"""`make bench`: how fast the suite solves its problems, as ratios and iteration counts.
Studies (timings are medians of --repeat runs below 200k DOFs, single runs above):
 1. Hertz plane, P1 linear elasticity, refined from ~10k to ~1M DOFs: DOFs, contact candidates,
    IPOPT iterations, wall time split into mesh / IPOPT internals (MUMPS) / callbacks / rest,
    peak memory, errors of a and p_max.
 2. The cost of contact: the same disc supported instead of in contact, one direct MUMPS
    solve (scripts/performance/supported_disc.edp); ratio of the contact solve to it.
 3. Hyperelastic: the 3D Neo-Hookean cube without contact, IPOPT against plain Newton; and
    Neo-Hookean Hertz, IPOPT against plain Newton given the contact set IPOPT found
    (hertz_plane.edp -newton 1), with the difference of the two solutions.
 4. The 3D Hertz sphere at ~67k and ~200k DOFs (single runs).
 5. Two bodies: the two elastic cylinders (small sliding, and updated pairing) against the disc on
    the rigid cylinder (hertz_circle.edp -constraint linearized) at the same element size.
 6. With --peers (make bench PEERS=1): DOLFINx's SNES-VI on the Hertz meshes (study 1b), and FElupe
    on the O-ring plates (scripts/peers/felupe_oring.py) against ours at the same h.
 7. 3D rubber: the nodal form's saddle point factors against the element penalty form's on the 3D
    Neo-Hookean block on its foundation (factor entries per unknown), and the 3D indentation
    (benchmarks/indentation.edp -dim 3): DOFs, iterations per step, total time over the mean
    factorization time, peak memory; with --large also at h = R/48 (~290k DOFs, about an hour).
Writes performance.json and PERFORMANCE.md in results/performance (--out).
    scripts/performance/studies.py [--smoke] [--repeat 3] [--large] [--out results/performance]"""

import argparse
import csv
import json
import math
import os
import re
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))   # scripts/
from freefem import ROOT, read_summary  # noqa: E402
import md_tables  # noqa: E402

A_HERTZ = 0.0550867877   # Hertz half-width of the default hertz_plane (m)
A_SPHERE = 0.1005577     # of the default hertz_sphere (m)
OUT = "results/performance"      # --out
ONE_THREAD = dict(os.environ, OMP_NUM_THREADS="1")   # one OpenBLAS/OpenMP thread: how the peers run


def timed_run(script, args, out_dir, one_thread=False):
    """Runs FreeFem++ under GNU time: (summary, wall seconds, peak RSS in MB, output). one_thread: one
    OpenBLAS thread (OMP_NUM_THREADS=1), as the peers run, for the studies compared with them."""
    command = ["/usr/bin/time", "-f", "BENCH %e %M", "FreeFem++", "-nw", script] + args + ["-out", out_dir]
    proc = subprocess.run(command, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          env=ONE_THREAD if one_thread else None)
    m = re.findall(r"BENCH ([\d.]+) (\d+)", proc.stdout)
    wall, rss = (float(m[-1][0]), int(m[-1][1]) / 1024) if m else (float("nan"), float("nan"))
    return read_summary(out_dir), wall, rss, proc.stdout


def ipopt_cpu(out_dir):
    """CPU seconds inside IPOPT (MUMPS and the algorithm) and in our callbacks, all steps."""
    internal = callbacks = 0.0
    folder = os.path.join(ROOT, out_dir)
    for f in os.listdir(folder):
        if f.startswith("ipopt_step") and f.endswith(".log"):
            text = open(os.path.join(folder, f)).read()
            for value in re.findall(r"Total CPU secs in IPOPT \(w/o function evaluations\)\s*=\s*([\d.]+)", text):
                internal += float(value)
            for value in re.findall(r"Total CPU secs in NLP function evaluations\s*=\s*([\d.]+)", text):
                callbacks += float(value)
    return internal, callbacks


def median_runs(repeat, script, args, out_dir, one_thread=False):
    runs = [timed_run(script, args, out_dir, one_thread) for _ in range(repeat)]
    walls = [r[1] for r in runs]
    best = runs[walls.index(statistics.median_low(walls))]
    return best[0], statistics.median(walls), max(r[2] for r in runs), best[3]


def measured(label, repeat, script, args, out_dir, one_thread=False):
    """median_runs, or None after printing the failure with the end of the run's output."""
    s, wall, rss, output = median_runs(repeat, script, args, out_dir, one_thread)
    if s is None:
        print(f"{label}: FAILED\n" + output[-500:], flush=True)
        return None
    return s, wall, rss, output


def solve_seconds(summary):
    """Wall time of all the load steps' solves."""
    return sum(st["time_s"] for st in summary["steps"])


def peer_runs(command, repeat, wall_key):
    """A peer script (its last output line "RESULT {json}") run `repeat` times with one OpenMP thread:
    the run of median wall time, its wall time the median, or None after printing the failure."""
    runs = []
    for _ in range(repeat):
        proc = subprocess.run(command, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              env=ONE_THREAD)
        m = re.search(r"^RESULT (.*)$", proc.stdout, re.M)
        if proc.returncode != 0 or not m:
            print(f"{' '.join(command[1:])}: FAILED\n" + proc.stdout[-500:], flush=True)
            return None
        runs.append(json.loads(m.group(1)))
    walls = [r[wall_key] for r in runs]
    best = dict(runs[walls.index(statistics.median_low(walls))])
    best[wall_key] = statistics.median(walls)
    best["solve_s"] = statistics.median(r["solve_s"] for r in runs)
    return best


def dolfinx_run(h, repeat):
    """scripts/peers/dolfinx_hertz.py (DOLFINx SNES-VI, Debian's python3-dolfinx) on the same mesh."""
    return peer_runs(["/usr/bin/python3", "scripts/peers/dolfinx_hertz.py", "--h", repr(h)], repeat, "total_wall_s")


def hertz_study(levels, repeat, full_path_levels, peers):
    """Hertz plane: the condensed solve (the default), the full KKT path (-condense no) up to
    full_path_levels, and with peers the DOLFINx SNES-VI solve of the same mesh (then ours too with one
    OpenBLAS thread, as the peer runs)."""
    rows = []
    for level in levels:
        h = A_HERTZ / level
        reps = repeat if level <= 160 else 1
        out_dir = f"{OUT}/hertz_a{level}"
        run = measured(f"hertz a/{level}", reps, "benchmarks/hertz_plane.edp", ["-h", repr(h)], out_dir, peers)
        if run is None:
            continue
        s, wall, rss, output = run
        internal, callbacks = ipopt_cpu(out_dir)
        step = solve_seconds(s)
        candidates = int(re.search(r"(\d+) contact candidates", output).group(1))
        direct = measured(f"supported disc a/{level}", reps, "scripts/performance/supported_disc.edp", ["-h", repr(h)], f"{OUT}/direct_a{level}")
        solve = direct[0]["results"]["solve_time_s"]["computed"] if direct else float("nan")
        assembly = direct[0]["results"]["assembly_time_s"]["computed"] if direct else float("nan")
        row = {"level": f"a/{level}", "ndof": s["ndof"], "candidates": candidates, "iterations": s["ipopt_iterations"],
               "wall_s": wall, "mesh_s": s["results"]["mesh_time_s"]["computed"], "solve_step_s": step,
               "ipopt_internal_cpu_s": internal, "callbacks_cpu_s": callbacks,
               "rest_s": wall - step - s["results"]["mesh_time_s"]["computed"], "peak_rss_mb": rss,
               "a_error": s["results"]["a"]["rel_error"], "p_max_error": s["results"]["p_max"]["rel_error"],
               "direct_solve_s": solve, "direct_assembly_s": assembly,
               "contact_over_direct_solve": step / solve, "contact_over_assembly_and_solve": step / (solve + assembly),
               "l2_error": s["results"]["pressure_l2_rel_error"]["computed"],
               "condensed_dofs": s.get("solver", {}).get("condensed_dofs", 0),
               "condensation_s": s.get("solver", {}).get("condensation_time_s", float("nan")),
               "runs": reps}
        if level <= full_path_levels:
            full = measured(f"hertz a/{level} full KKT path", reps, "benchmarks/hertz_plane.edp",
                            ["-h", repr(h), "-condense", "no"], f"{OUT}/hertz_a{level}_full", peers)
            if full:
                row.update({"full_iterations": full[0]["ipopt_iterations"], "full_solve_s": solve_seconds(full[0]),
                            "full_wall_s": full[1], "full_l2_error": full[0]["results"]["pressure_l2_rel_error"]["computed"]})
        if peers:
            peer = dolfinx_run(h, reps)
            if peer:
                row.update({"dolfinx_ndof": peer["ndof"], "dolfinx_iterations": peer["snes_iterations"],
                            "dolfinx_solve_s": peer["solve_s"], "dolfinx_wall_s": peer["total_wall_s"],
                            "dolfinx_l2_error": peer["pressure_l2_rel_error"], "dolfinx_a_error": peer["a_rel_error"]
                            if "a_rel_error" in peer else float("nan"),
                            "dolfinx_over_ours_wall": peer["total_wall_s"] / wall})
        rows.append(row)
        print(f"hertz a/{level}: {row['ndof']} dofs, {row['iterations']} it., wall {wall:.1f} s (solve {step:.1f} s), "
              f"RSS {rss:.0f} MB; direct solve {solve:.2f} s + assembly {assembly:.2f} s", flush=True)
    return rows


def cube_study(ns, repeat):
    rows = []
    for n in ns:
        entry = {"n": n}
        for solver in ("ipopt", "newton"):
            out_dir = f"{OUT}/cube_n{n}_{solver}"
            # the element form: this study compares the solvers (the nodal form's cost is the
            # volumetric study's subject; with it the 3D Neo-Hookean cube takes 17-20 IPOPT iterations)
            # (-condense no: IPOPT itself; without contact rows the default is the condensed Newton)
            run = measured(f"cube n = {n} {solver}", repeat, "benchmarks/cube.edp",
                           ["-material", "neohookean", "-dim", "3", "-n", str(n), "-solver", solver,
                            "-volumetric", "penalty", "-condense", "no"], out_dir)
            if run is None:
                continue
            s, wall = run[0], run[1]
            entry.update({"ndof": s["ndof"], f"{solver}_iterations": s["ipopt_iterations"],
                          f"{solver}_solve_s": solve_seconds(s), f"{solver}_wall_s": wall,
                          f"{solver}_w_error": s["results"]["w"]["rel_error"]})
        if "newton_solve_s" in entry and "ipopt_solve_s" in entry:
            entry["ipopt_over_newton"] = entry["ipopt_solve_s"] / entry["newton_solve_s"]
            rows.append(entry)
            print(f"cube 3D n = {n}: {entry['ndof']} dofs, IPOPT {entry['ipopt_iterations']} it. {entry['ipopt_solve_s']:.1f} s, "
                  f"Newton {entry['newton_iterations']} it. {entry['newton_solve_s']:.1f} s", flush=True)
    return rows


def hertz_newton_study(levels, repeat):
    rows = []
    for level in levels:
        out_dir = f"{OUT}/hertz_nh_a{level}"
        run = measured(f"hertz Neo-Hookean a/{level}", repeat, "benchmarks/hertz_plane.edp",
                       ["-material", "neohookean", "-newton", "1", "-h", repr(A_HERTZ / level)], out_dir)
        if run is None:
            continue
        s = run[0]
        r = s["results"]
        row = {"level": f"a/{level}", "ndof": s["ndof"], "ipopt_iterations": s["ipopt_iterations"],
               "ipopt_solve_s": solve_seconds(s),
               "newton_iterations": int(r["newton_iterations"]["computed"]), "newton_solve_s": r["newton_time_s"]["computed"],
               "rel_difference": r["newton_vs_ipopt_rel_difference"]["computed"], "a_error": r["a"]["rel_error"]}
        row["ipopt_over_newton"] = row["ipopt_solve_s"] / row["newton_solve_s"]
        row["contact_solve"] = "condensed SQP" if "condensed_dofs" in s.get("solver", {}) else "IPOPT, whole problem"
        full = measured(f"hertz Neo-Hookean a/{level} full", repeat, "benchmarks/hertz_plane.edp",
                        ["-material", "neohookean", "-condense", "no", "-h", repr(A_HERTZ / level)], out_dir + "_full")
        if full:
            row.update({"full_iterations": full[0]["ipopt_iterations"], "full_solve_s": solve_seconds(full[0]),
                        "full_over_newton": solve_seconds(full[0]) / row["newton_solve_s"]})
        rows.append(row)
        print(f"hertz Neo-Hookean a/{level}: {row['ndof']} dofs, IPOPT {row['ipopt_iterations']} it. {row['ipopt_solve_s']:.1f} s, "
              f"Newton on the known contact set {row['newton_iterations']} it. {row['newton_solve_s']:.1f} s", flush=True)
    return rows


ORING_CONVERGED = 1.3128   # computed / Lindley at c = 0.2, mesh-converged (docs/rubber.md)


def volumetric_study(oring_levels, hertz_levels, repeat):
    """The nodal volumetric treatment against the element penalty form at nu = 0.499: IPOPT
    iterations, solve time and accuracy on the O-ring plates (15 steps) and Neo-Hookean Hertz."""
    rows = []
    cases = [("oring plates", f"R/{d}", "benchmarks/oring.edp", ["-case", "plates", "-h", repr(0.52 / d)]) for d in oring_levels]
    cases += [("hertz Neo-Hookean nu=0.499", f"a/{level}", "benchmarks/hertz_plane.edp",
               ["-material", "neohookean", "-nu", "0.499", "-h", repr(0.0500434 / level)]) for level in hertz_levels]
    for case, level, script, args in cases:
        for form in ("penalty", "nodal"):
            out_dir = f"{OUT}/volumetric_{case.split()[0]}_{level.replace('/', '')}_{form}"
            run = measured(f"{case} {level} {form}", repeat, script, args + ["-volumetric", form], out_dir)
            if run is None:
                continue
            r = run[0]["results"]
            error = (abs(r["force_c0.2"]["computed"] / r["force_c0.2"]["reference"] - ORING_CONVERGED) / ORING_CONVERGED
                     if case.startswith("oring") else r["a"]["rel_error"])
            rows.append({"case": case, "level": level, "form": form, "ndof": run[0]["ndof"],
                         "iterations": run[0]["ipopt_iterations"], "solve_s": solve_seconds(run[0]), "error": error})
            print(f"{case} {level} {form}: {run[0]['ndof']} dofs, {run[0]['ipopt_iterations']} it., "
                  f"{solve_seconds(run[0]):.1f} s, error {error:.1e}", flush=True)
    return rows


def sphere_study(levels, axisymmetric_levels=()):
    """3D Hertz sphere at the given levels, then the same sphere from its meridian section."""
    rows = []
    for level, axisymmetric in [(l, False) for l in levels] + [(l, True) for l in axisymmetric_levels]:
        out_dir = f"{OUT}/sphere_a{level}" + ("_axisymmetric" if axisymmetric else "")
        run = measured(f"sphere a/{level}", 1, "benchmarks/hertz_sphere.edp",
                       ["-h", repr(A_SPHERE / level)] + (["-dim", "axi"] if axisymmetric else []), out_dir)
        if run is None:
            continue
        s, wall, rss, _ = run
        internal, callbacks = ipopt_cpu(out_dir)
        rows.append({"level": f"a/{level}" + (" (axisymmetric)" if axisymmetric else ""), "ndof": s["ndof"],
                     "iterations": s["ipopt_iterations"], "wall_s": wall,
                     "solve_step_s": solve_seconds(s), "ipopt_internal_cpu_s": internal,
                     "callbacks_cpu_s": callbacks, "peak_rss_mb": rss,
                     "a_error": s["results"]["a"]["rel_error"], "p_max_error": s["results"]["p_max"]["rel_error"]})
        print(f"sphere a/{level}: {s['ndof']} dofs, {s['ipopt_iterations']} it., wall {wall:.1f} s, RSS {rss:.0f} MB", flush=True)
    return rows


def rubber_3d_study(cube_ns, indentation_levels):
    """Issue 25's 3D rubber measures: the factor entries per unknown of the nodal form's saddle point
    matrix against the element penalty form's on the same 3D block (Neo-Hookean, on its foundation),
    and the 3D indentation's cost in factorizations."""
    fill, indentation = [], []
    for n in cube_ns:
        row = {"n": n}
        for form in ("penalty", "nodal"):
            run = measured(f"3D block n = {n} {form}", 1, "benchmarks/cube.edp",
                           ["-material", "neohookean", "-dim", "3", "-n", str(n), "-foundation", "1", "-volumetric", form],
                           f"{OUT}/rubber_block_n{n}_{form}")
            if run is None:
                continue
            s, wall, rss, _ = run
            r = s["results"]
            row.update({"ndof": s["ndof"], f"{form}_entries": s["solver"]["condensation_factor_entries"],
                        f"{form}_per_unknown": s["solver"]["factor_entries_per_unknown"], f"{form}_wall_s": wall,
                        f"{form}_rss_mb": rss, f"{form}_w_error": r["w"]["rel_error"]})
        if "penalty_per_unknown" in row and "nodal_per_unknown" in row:
            row["ratio_per_unknown"] = row["nodal_per_unknown"] / row["penalty_per_unknown"]
            fill.append(row)
            print(f"3D block n = {n}: {row['ndof']} dofs, factor entries per unknown {row['penalty_per_unknown']:.0f} (penalty), "
                  f"{row['nodal_per_unknown']:.0f} (nodal saddle point): x{row['ratio_per_unknown']:.2f}", flush=True)
    # each level four times: the default (-krylov step: one factorization a load step, after its first
    # Newton step by GMRES on the last step's factors; issue 43), the chord steps alone as before it
    # (-krylov no: the stale tangent's own step where -reuse allows, mixed from the last ones, else a
    # factorization), Newton's steps by GMRES at every iteration (-krylov yes), and the default with
    # double precision factors (-factors double, as before issue 43's single precision)
    for level in indentation_levels:
        for solver, extra in (("step", []), ("no", []), ("yes", []), ("step, double", ["-factors", "double"])):
            folder = f"{OUT}/indentation_3d_R{level}_{solver.replace(', ', '_').replace(' ', '')}"
            run = measured(f"indentation 3D h = R/{level} -krylov {solver}", 1, "benchmarks/indentation.edp",
                           ["-dim", "3", "-h", repr(1.0 / level), "-krylov", solver.split(",")[0]] + extra, folder)
            if run is None:
                continue
            s, wall, rss, _ = run
            t, r = s["timings"], s["results"]
            indentation.append({"level": f"R/{level}", "solver": solver, "ndof": s["ndof"], "wall_s": wall, "peak_rss_mb": rss,
                                "iterations": [step["iterations"] for step in s["steps"]],
                                "per_step": [(step["iterations"], step["krylov_iterations"], step["factorizations"],
                                              step["shifted_iterations"]) for step in s["steps"]],
                                "factorizations": t["factorizations"], "factorization_mean_s": t["factorization_mean"],
                                "krylov_iterations": t["krylov_iterations"],
                                "total_over_factorization": t["total"] / t["factorization_mean"] if t["factorization_mean"] > 0 else float("nan"),
                                "per_unknown": s["solver"]["factor_entries_per_unknown"], "force": r["force"]["computed"],
                                "forces": read_column(f"{folder}/force_depth.csv", "force"),
                                "force_small_depth_error": r["force_small_depth"]["rel_error"]})
            print(f"indentation 3D R/{level} -krylov {solver}: {s['ndof']} dofs, {t['factorizations']} factorizations of "
                  f"{t['factorization_mean']:.2f} s, {t['krylov_iterations']} GMRES iterations, wall {wall:.0f} s, RSS {rss:.0f} MB", flush=True)
    return fill, indentation


def read_column(path, name):
    """One column of a CSV file, as floats ([] when the file is missing)."""
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [float(row[name]) for row in csv.DictReader(f)]


def indentation_steps_table(rows):
    """The finest level's runs step by step, before (-krylov no: the chord steps alone) and after (the
    default -krylov step): SQP iterations, GMRES iterations, factorizations and shifted iterations,
    and the force's relative difference at each depth; then -krylov yes and -factors double in a line."""
    finest = [r for r in rows if r["level"] == (rows[-1]["level"] if rows else None)]
    runs = {r["solver"]: r for r in finest}
    if not {"step", "no"} <= set(runs):
        return "(the finest level's -krylov step and -krylov no runs did not both complete)"
    after, before = runs["step"], runs["no"]
    table = md_tables.table(("step", "before (-krylov no): SQP", "factorizations", "shifted", "after (-krylov step): SQP",
                             "GMRES", "factorizations", "shifted", "force, after / before - 1"),
                            [(k + 1, *[a[i] for i in (0, 2, 3)], *b, f"{fb / fa - 1:.1e}")
                             for k, (a, b, fa, fb) in enumerate(zip(before["per_step"], after["per_step"], before["forces"], after["forces"]))])
    text = (f"{table}\n\n{after['level']}: wall {before['wall_s']:.0f} s before (-krylov no, {before['factorizations']} "
            f"factorizations) and {after['wall_s']:.0f} s after (-krylov step, {after['factorizations']}, "
            f"{after['krylov_iterations']} GMRES iterations): x{before['wall_s'] / after['wall_s']:.2f}")
    for solver, what in (("yes", "-krylov yes"), ("step, double", "-factors double")):
        other = runs.get(solver)
        if other:
            worst = max((abs(b / a - 1) for a, b in zip(after["forces"], other["forces"])), default=float("nan"))
            plural = "" if other["factorizations"] == 1 else "s"
            text += (f"; {what} {other['wall_s']:.0f} s, {other['factorizations']} factorization{plural} of "
                     f"{other['factorization_mean_s']:.2f} s, {other['krylov_iterations']} GMRES iterations, its forces "
                     f"{worst:.1e} from the default's")
    return text


A_TWO_CYLINDERS = 0.0775818960   # Hertz half-width of the default hertz_two_cylinders (m)


def two_body_study(levels, repeat):
    """Two elastic cylinders against one disc on a rigid cylinder, the same element size h."""
    rows = []
    for level in levels:
        h = repr(A_TWO_CYLINDERS / level)
        runs = {}
        for key, script, extra in (("pair", "benchmarks/hertz_two_cylinders.edp", []),
                                   ("updated", "benchmarks/hertz_two_cylinders.edp", ["-constraint", "updated"]),
                                   ("rigid", "benchmarks/hertz_circle.edp", ["-constraint", "linearized"])):
            reps = repeat if level <= 60 else 1   # a/120: 126k DOFs, the updated pairing ~50 s a run
            run = measured(f"two bodies a/{level} {key}", reps, script, ["-h", h] + extra, f"{OUT}/two_bodies_a{level}_{key}")
            if run is not None:
                runs[key] = run
        if len(runs) < 3:
            continue
        pair, updated, rigid = runs["pair"][0], runs["updated"][0], runs["rigid"][0]
        row = {"level": f"a/{level}", "ndof": pair["ndof"], "iterations": pair["ipopt_iterations"],
               "solve_step_s": solve_seconds(pair), "wall_s": runs["pair"][1], "a_error": pair["results"]["a"]["rel_error"],
               "updated_iterations": updated["ipopt_iterations"], "updated_solve_s": solve_seconds(updated),
               "updated_resolves": updated["results"]["pairing_resolves"]["computed"],
               "rigid_ndof": rigid["ndof"], "rigid_iterations": rigid["ipopt_iterations"], "rigid_solve_s": solve_seconds(rigid)}
        row["pair_over_rigid_per_dof"] = (row["solve_step_s"] / row["ndof"]) / (row["rigid_solve_s"] / row["rigid_ndof"])
        rows.append(row)
        print(f"two bodies a/{level}: {row['ndof']} dofs, {row['iterations']} it., solve {row['solve_step_s']:.1f} s; "
              f"updated {row['updated_iterations']} it. ({row['updated_resolves']:.0f} re-solves); rigid {row['rigid_ndof']} dofs, "
              f"{row['rigid_iterations']} it., solve {row['rigid_solve_s']:.1f} s", flush=True)
    return rows


def friction_study(repeat, smoke=False):
    """The cost of friction: each friction run against the frictionless run of the same driver and mesh
    (IPOPT iterations, friction solves: Coulomb's fixed-point passes, wall time). Cattaneo's and
    Mindlin's rigid set-ups (their own mu, 0.2) against their -mu 0 runs: the normal load alone, as a
    frictionless body cannot carry their tangential load."""
    rows = []
    # rubber on rigid parts (issue 40): both runs in the stabilised nodal form, friction's default
    rubber = ["-material", "neohookean", "-nu", "0.4999", "-volumetric", "stabilised"]
    stabilised = ["-volumetric", "stabilised"]
    # (label, script, args, mu): mu = 0.3 but for the rigid set-ups' own 0.2
    cases = (("Hertz plane (rigid, 2D)", "benchmarks/hertz_plane.edp", [], "0.3"),
             ("two cylinders (pair, 2D)", "benchmarks/hertz_two_cylinders.edp", [], "0.3"),
             ("sphere (axisymmetric)", "benchmarks/hertz_sphere.edp", ["-dim", "axi"], "0.3"),
             ("sphere (3D, h = a/8)", "benchmarks/hertz_sphere.edp", [], "0.3"),
             ("O-ring plates (Neo-Hookean SQP, 15 steps)", "benchmarks/oring.edp", ["-case", "plates"], "0.3"),
             ("rubber on a rigid cylinder (Hertz plane, Neo-Hookean, nu 0.4999)", "benchmarks/hertz_plane.edp", rubber,
              "0.3"),
             ("rubber squeezed 20 % by a rigid punch (nu 0.499, 5 steps)", "tests/punch_squeeze.edp", stabilised, "0.3"),
             ("Cattaneo, rigid cylinder on the block (nu 0.4999, a/60, mu 0.2; mu 0: the normal load alone)",
              "benchmarks/cattaneo.edp", ["-setup", "rigid"] + stabilised, "0.2"),
             ("Mindlin, rigid sphere on the block (3D, nu 0.4999, a/10, mu 0.2; mu 0: the normal load alone)",
              "benchmarks/mindlin_sphere.edp", ["-setup", "rigid"] + stabilised, "0.2"))
    for label, script, args, mu in cases[:1 if smoke else len(cases)]:
        key = re.sub(r"\W+", "_", label).strip("_").lower()
        plain = measured(f"friction {label}: mu 0", repeat, script, args + ["-mu", "0"], f"{OUT}/friction_{key}_plain")
        rough = measured(f"friction {label}: mu {mu}", repeat, script, args + ["-mu", mu], f"{OUT}/friction_{key}_mu")
        if plain is None or rough is None:
            continue
        p, r = plain[0], rough[0]
        row = {"case": label, "ndof": p["ndof"], "plain_iterations": p["ipopt_iterations"], "plain_wall_s": plain[1],
               "iterations": r["ipopt_iterations"], "passes": r["results"]["friction_solves"]["computed"],
               "steps": len(r["steps"]), "wall_s": rough[1], "mu": float(mu)}
        row["wall_ratio"] = row["wall_s"] / row["plain_wall_s"]
        row["iteration_ratio"] = row["iterations"] / max(row["plain_iterations"], 1)
        rows.append(row)
        print(f"friction {label}: {row['ndof']} dofs; mu 0: {row['plain_iterations']} it., {row['plain_wall_s']:.1f} s; "
              f"mu {mu}: {row['iterations']} it., {row['passes']:.0f} friction solves, {row['wall_s']:.1f} s "
              f"(x{row['wall_ratio']:.1f})", flush=True)
    return rows


def dynamics_study(levels, repeat):
    """The bar against the wall (benchmarks/bar_impact.edp, Newmark, redistributed mass): per time step,
    IPOPT's iterations (mean, max) and the wall time; the time steps' share of the run."""
    rows = []
    for n in levels:
        run = measured(f"bar impact n = {n}", repeat, "benchmarks/bar_impact.edp", ["-n", str(n), "-every", "0"], f"{OUT}/bar_impact_n{n}")
        if run is None:
            continue
        s = run[0]
        iterations = [st["iterations"] for st in s["steps"]]
        rows.append({"n": n, "ndof": s["ndof"], "steps": int(s["results"]["time_steps"]["computed"]),
                     "mean_iterations": sum(iterations) / len(iterations), "max_iterations": max(iterations),
                     "step_s": solve_seconds(s) / len(s["steps"]), "wall_s": run[1],
                     "rebound_error": s["results"]["rebound_velocity"]["rel_error"]})
        r = rows[-1]
        print(f"bar impact n = {n}: {r['ndof']} dofs, {r['steps']} steps, {r['mean_iterations']:.1f} IPOPT it. per step "
              f"(max {r['max_iterations']}), {1e3 * r['step_s']:.1f} ms per step, wall {r['wall_s']:.1f} s", flush=True)
    return rows


ORING_R = 0.52   # oring.edp's default radius


def felupe_study(divisions, repeat):
    """The O-ring plates (15 steps to c = 0.3): ours (the default nodal form) against FElupe's P1 and
    locking-free Q1/P0 (scripts/peers/felupe_oring.py, its own venv under results/peers) at each h = R/k."""
    rows = []
    for k in divisions:
        h = ORING_R / k
        run = measured(f"oring plates R/{k}", repeat, "benchmarks/oring.edp", ["-case", "plates", "-h", repr(h)],
                       f"{OUT}/peers_oring_R{k}", one_thread=True)
        if run is None:
            continue
        s = run[0]
        row = {"level": f"R/{k}", "ndof": s["ndof"], "iterations": s["ipopt_iterations"], "solve_s": solve_seconds(s),
               "wall_s": run[1], "force": s["results"]["force_c0.3"]["computed"] / s["results"]["force_c0.3"]["reference"]}
        for formulation in ("p1", "mixed"):
            best = peer_runs(["/usr/bin/python3", "scripts/peers/felupe_oring.py", "--h", f"R/{k}", "--formulation", formulation],
                             repeat, "wall_s")
            if best:
                force = best["results"]["force_c0.3"]
                row.update({f"{formulation}_ndof": best["ndof"], f"{formulation}_iterations": best["newton_iterations"],
                            f"{formulation}_solve_s": best["solve_s"], f"{formulation}_wall_s": best["wall_s"],
                            f"{formulation}_force": force["computed"] / force["reference"]})
        rows.append(row)
        print(f"oring plates R/{k}: ours {row['ndof']} dofs {row['solve_s']:.2f} s; FElupe P1 {row.get('p1_solve_s', float('nan')):.2f} s, "
              f"mixed {row.get('mixed_solve_s', float('nan')):.2f} s", flush=True)
    return rows


def slope(rows, x, y):
    pts = [(math.log(r[x]), math.log(r[y])) for r in rows if r[y] > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sum((p[0] - mx) ** 2 for p in pts)


def main():
    global OUT
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--smoke", action="store_true", help="the smallest level of each study only")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--out", default=OUT)
    parser.add_argument("--peers", action="store_true", help="also the DOLFINx SNES-VI solve of the Hertz plane (python3-dolfinx)")
    parser.add_argument("--large", action="store_true", help="also the 3D indentation at h = R/48 (~290k DOFs, about an hour)")
    args = parser.parse_args()
    OUT = args.out
    start = time.time()
    repeat = 1 if args.smoke else args.repeat
    def study(function, *arguments):
        """A study's rows; a study that crashes is reported and leaves the others' results standing."""
        try:
            return function(*arguments)
        except Exception:
            import traceback
            traceback.print_exc()
            return []
    hertz = study(hertz_study, [20] if args.smoke else [40, 80, 160, 320, 480], repeat, 20 if args.smoke else 160, args.peers)
    cube = study(cube_study, [3] if args.smoke else [8, 12], repeat)
    hertz_newton = study(hertz_newton_study, [10] if args.smoke else [40, 80, 160], repeat)
    sphere = study(sphere_study, [8] if args.smoke else [24, 36], [8] if args.smoke else [30, 60, 120])
    volumetric = study(volumetric_study, [12] if args.smoke else [12, 24, 48], [10] if args.smoke else [20, 40, 80], repeat)
    two_bodies = study(two_body_study, [10] if args.smoke else [30, 60, 120], repeat)
    peers_oring = study(felupe_study, [12] if args.smoke else [12, 24, 48], repeat) if args.peers else []
    rubber = study(rubber_3d_study, [3] if args.smoke else [8, 14],
                   [8] if args.smoke else ([16, 32, 48] if args.large else [16, 32])) or ([], [])
    rubber_fill, rubber_indentation = rubber
    friction = study(friction_study, repeat, args.smoke)
    dynamics = study(dynamics_study, [50] if args.smoke else [100, 200, 400], repeat)
    growth = slope(hertz, "ndof", "solve_step_s")
    data = {"hertz_plane": hertz, "hertz_time_growth_exponent": growth, "cube_ipopt_vs_newton": cube,
            "hertz_neohookean_ipopt_vs_newton": hertz_newton,
            "hertz_sphere": sphere, "volumetric": volumetric, "two_bodies": two_bodies, "felupe_oring": peers_oring,
            "rubber_3d_fill": rubber_fill, "rubber_3d_indentation": rubber_indentation, "friction": friction, "dynamics": dynamics,
            "smoke": args.smoke, "repeat": repeat, "total_s": time.time() - start}
    out = os.path.join(ROOT, OUT)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "performance.json"), "w") as f:
        json.dump(data, f, indent=1)
    t1 = md_tables.table(("h", "DOFs", "candidates", "IPOPT it.", "wall (s)", "mesh (s)", "solve (s)", "IPOPT internal CPU (s)",
                         "callbacks CPU (s)", "peak RSS (MB)", "a err", "p_max err", "direct solve (s)", "contact / direct solve",
                         "contact / (assembly + solve)"),
                        [(r["level"], r["ndof"], r["candidates"], r["iterations"], f"{r['wall_s']:.1f}", f"{r['mesh_s']:.1f}",
                          f"{r['solve_step_s']:.1f}", f"{r['ipopt_internal_cpu_s']:.1f}", f"{r['callbacks_cpu_s']:.1f}",
                          f"{r['peak_rss_mb']:.0f}", f"{r['a_error']:.1e}", f"{r['p_max_error']:.1e}", f"{r['direct_solve_s']:.2f}",
                          f"{r['contact_over_direct_solve']:.1f}", f"{r['contact_over_assembly_and_solve']:.1f}") for r in hertz])
    t1b = md_tables.table(("h", "DOFs", "condensed onto", "condensation (s)", "solve (s)", "wall (s)", "L2(p) err",
                          "full KKT path: IPOPT it.", "solve (s)", "wall (s)", "full / condensed solve",
                          "DOLFINx: DOFs", "SNES it.", "solve (s)", "wall (s)", "L2(p) err", "DOLFINx / ours, wall"),
                         [(r["level"], r["ndof"], f"{r['condensed_dofs']:.0f}", f"{r['condensation_s']:.1f}", f"{r['solve_step_s']:.2f}",
                           f"{r['wall_s']:.1f}", f"{r['l2_error']:.3e}",
                           r.get("full_iterations", "-"), f"{r['full_solve_s']:.2f}" if "full_solve_s" in r else "-",
                           f"{r['full_wall_s']:.1f}" if "full_wall_s" in r else "-",
                           f"{r['full_solve_s'] / r['solve_step_s']:.1f}" if "full_solve_s" in r else "-",
                           r.get("dolfinx_ndof", "-"), r.get("dolfinx_iterations", "-"),
                           f"{r['dolfinx_solve_s']:.2f}" if "dolfinx_solve_s" in r else "-",
                           f"{r['dolfinx_wall_s']:.1f}" if "dolfinx_wall_s" in r else "-",
                           f"{r['dolfinx_l2_error']:.3e}" if "dolfinx_l2_error" in r else "-",
                           f"{r['dolfinx_over_ours_wall']:.2f}" if "dolfinx_over_ours_wall" in r else "-") for r in hertz])
    t2 = md_tables.table(("n", "DOFs", "IPOPT it.", "IPOPT solve (s)", "Newton it.", "Newton solve (s)", "IPOPT / Newton"),
                        [(r["n"], r["ndof"], r["ipopt_iterations"], f"{r['ipopt_solve_s']:.1f}", r["newton_iterations"],
                          f"{r['newton_solve_s']:.1f}", f"{r['ipopt_over_newton']:.2f}") for r in cube])
    t2b = md_tables.table(("h", "DOFs", "contact solve", "it.", "solve (s)", "Newton it.", "Newton solve (s)", "contact solve / Newton",
                          "U difference, rel. to max U", "a err", "IPOPT, whole problem: it.", "solve (s)", "/ Newton"),
                         [(r["level"], r["ndof"], r["contact_solve"], r["ipopt_iterations"], f"{r['ipopt_solve_s']:.2f}", r["newton_iterations"],
                           f"{r['newton_solve_s']:.2f}", f"{r['ipopt_over_newton']:.2f}", f"{r['rel_difference']:.1e}",
                           f"{r['a_error']:.1e}", r.get("full_iterations", "-"),
                           f"{r['full_solve_s']:.2f}" if "full_solve_s" in r else "-",
                           f"{r['full_over_newton']:.2f}" if "full_over_newton" in r else "-") for r in hertz_newton])
    t3 = md_tables.table(("h", "DOFs", "IPOPT it.", "wall (s)", "solve (s)", "peak RSS (MB)", "a err", "p_max err"),
                        [(r["level"], r["ndof"], r["iterations"], f"{r['wall_s']:.1f}", f"{r['solve_step_s']:.1f}",
                          f"{r['peak_rss_mb']:.0f}", f"{r['a_error']:.1e}", f"{r['p_max_error']:.1e}") for r in sphere])
    t4 = md_tables.table(("case", "h", "form", "DOFs", "IPOPT it.", "solve (s)", "error"),
                        [(r["case"], r["level"], r["form"], r["ndof"], r["iterations"], f"{r['solve_s']:.1f}", f"{r['error']:.1e}")
                         for r in volumetric])
    t5 = md_tables.table(("h", "DOFs", "IPOPT it.", "solve (s)", "a err", "updated: it.", "re-solves", "solve (s)",
                         "rigid: DOFs", "IPOPT it.", "solve (s)", "two bodies / rigid, solve time per DOF"),
                        [(r["level"], r["ndof"], r["iterations"], f"{r['solve_step_s']:.2f}", f"{r['a_error']:.1e}",
                          r["updated_iterations"], f"{r['updated_resolves']:.0f}", f"{r['updated_solve_s']:.2f}", r["rigid_ndof"],
                          r["rigid_iterations"], f"{r['rigid_solve_s']:.2f}", f"{r['pair_over_rigid_per_dof']:.2f}")
                         for r in two_bodies])
    def felupe_cells(r, f):
        if f + "_solve_s" not in r:
            return ("-",) * 5
        return (r[f + "_ndof"], r[f + "_iterations"], f"{r[f + '_solve_s']:.2f}", f"{r[f + '_wall_s']:.2f}", f"{r[f + '_force']:.5f}")
    t6 = md_tables.table(("h", "DOFs", "it.", "solve (s)", "wall (s)", "F/Lindley at c = 0.3", "FElupe P1: DOFs", "Newton it.",
                         "solve (s)", "wall (s)", "F/Lindley", "Q1/P0: DOFs", "Newton it.", "solve (s)", "wall (s)", "F/Lindley",
                         "ours / P1, solve", "ours / Q1/P0, solve"),
                        [(r["level"], r["ndof"], r["iterations"], f"{r['solve_s']:.2f}", f"{r['wall_s']:.2f}", f"{r['force']:.5f}")
                         + felupe_cells(r, "p1") + felupe_cells(r, "mixed")
                         + (f"{r['solve_s'] / r['p1_solve_s']:.2f}" if "p1_solve_s" in r else "-",
                            f"{r['solve_s'] / r['mixed_solve_s']:.2f}" if "mixed_solve_s" in r else "-")
                         for r in peers_oring]) if peers_oring else "(make bench PEERS=1)"
    t7 = md_tables.table(("n", "DOFs", "penalty: factor entries", "per unknown", "wall (s)", "nodal saddle point: factor entries",
                         "per unknown", "wall (s)", "per unknown, nodal / penalty"),
                        [(r["n"], r["ndof"], f"{r['penalty_entries']:.3g}", f"{r['penalty_per_unknown']:.0f}", f"{r['penalty_wall_s']:.1f}",
                          f"{r['nodal_entries']:.3g}", f"{r['nodal_per_unknown']:.0f}", f"{r['nodal_wall_s']:.1f}",
                          f"{r['ratio_per_unknown']:.2f}") for r in rubber_fill])
    t8 = md_tables.table(("h", "-krylov", "DOFs", "SQP iterations per step", "factorizations", "mean (s)", "GMRES it.",
                         "wall (s)", "wall / factorization", "factor entries per unknown", "peak RSS (MB)", "force at 0.2 R",
                         "F / Hertz - 1 at 0.02 R"),
                        [(r["level"], r["solver"], r["ndof"], " ".join(str(i) for i in r["iterations"]), r["factorizations"],
                          f"{r['factorization_mean_s']:.2f}", r["krylov_iterations"], f"{r['wall_s']:.0f}",
                          f"{r['total_over_factorization']:.0f}", f"{r['per_unknown']:.0f}", f"{r['peak_rss_mb']:.0f}",
                          f"{r['force']:.5f}", f"{r['force_small_depth_error']:.1e}") for r in rubber_indentation])
    t8b = indentation_steps_table(rubber_indentation)
    t9 = md_tables.table(("case", "DOFs", "mu 0: IPOPT it.", "wall (s)", "mu > 0: IPOPT it.", "friction solves",
                         "load steps", "wall (s)", "iterations, mu > 0 / mu 0", "wall, mu > 0 / mu 0"),
                        [(r["case"], r["ndof"], r["plain_iterations"], f"{r['plain_wall_s']:.1f}", r["iterations"],
                          f"{r['passes']:.0f}", r["steps"], f"{r['wall_s']:.1f}", f"{r['iteration_ratio']:.1f}",
                          f"{r['wall_ratio']:.1f}") for r in friction])
    t10 = md_tables.table(("n", "DOFs", "time steps", "IPOPT it. per step (mean)", "max", "ms per step", "wall (s)",
                          "rebound velocity error"),
                         [(r["n"], r["ndof"], r["steps"], f"{r['mean_iterations']:.1f}", r["max_iterations"],
                           f"{1e3 * r['step_s']:.1f}", f"{r['wall_s']:.1f}", f"{r['rebound_error']:.1e}") for r in dynamics])
    text = (f"Hertz plane (P1, linear), solve time growing like DOFs^{growth:.2f}:\n\n{t1}\n\n"
            f"Hertz plane: the condensed solve (default), the full KKT path (-condense no) and "
            f"DOLFINx's SNES-VI on the same mesh (make bench PEERS=1; both with one OpenBLAS thread)\n\n{t1b}\n\n"
            f"3D Neo-Hookean cube, no contact: IPOPT against plain Newton\n\n{t2}\n\n"
            f"Neo-Hookean Hertz plane: the contact solve (the condensed SQP by default; IPOPT on the whole problem with "
            f"-condense no) against plain Newton given the contact set it found\n\n{t2b}\n\n"
            f"3D Hertz sphere (two OpenBLAS threads: the factorization's dense fronts use both cores)\n\n{t3}\n\n"
            f"Volumetric treatment at nu = 0.499 (error: O-ring, of computed / Lindley at c = 0.2 against the "
            f"mesh-converged {ORING_CONVERGED}; Hertz, of a against Hertz)\n\n{t4}\n\n"
            f"Two elastic cylinders (small sliding; updated pairing) against one disc on a rigid cylinder, same h\n\n{t5}\n\n"
            f"O-ring between plates (15 steps to c = 0.3, nu = 0.499): ours (nodal form) against FElupe's P1 and Q1/P0 "
            f"(scripts/peers/felupe_oring.py); converged F/Lindley at c = 0.3: 1.3260\n\n{t6}\n\n"
            f"3D rubber: factor entries of the nodal form's saddle point matrix against the element penalty form's, "
            f"3D Neo-Hookean block on its foundation, nu = 0.499\n\n{t7}\n\n"
            f"3D indentation (benchmarks/indentation.edp -dim 3, 10 steps to 0.2 R)\n\n{t8}\n\n"
            f"3D indentation at the finest h, per load step: SQP iterations, GMRES iterations, factorizations and "
            f"iterations on a shifted tangent, before (-krylov no) and after (-krylov step, the default)\n\n{t8b}\n\n"
            f"Friction (mu = 0.3; the rigid set-ups' 0.2) against the frictionless run of the same driver and mesh\n\n{t9}\n\n"
            f"Dynamics: the bar against a wall (Newmark, redistributed mass), per time step\n\n{t10}")
    print("\n" + text)
    md_tables.write(os.path.join(out, "PERFORMANCE.md"), "Performance: timing studies", text)
    return 0 if (hertz and cube and hertz_newton and sphere and volumetric and two_bodies and rubber_fill and rubber_indentation and friction
                 and dynamics and (peers_oring or not args.peers)) else 1


if __name__ == "__main__":
    sys.exit(main())
