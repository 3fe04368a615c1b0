#!/usr/bin/env python3
"""`make sweep`: randomized parameter sets for the Hertz plane, cube, O-ring plates, axisymmetric
sphere and two-cylinder drivers, each checked for what must hold whatever the data: IPOPT success, force balance
within the solver's tolerance -tol, penetration <= 1e-10 of the body size, no tensile contact pressure beyond the
solver tolerance (1e-6 of the peak pressure), and for Hertz (linear, a/R <= 0.08, nu <= 0.45:
above, P1 locks and the errors are only reported) and the cube their analytic errors within
the bounds of the tests (a, p_max 0.3 %, L2 of p 1 %; w 1e-8); for two bodies, action = reaction
to 1e-12, each body's balance to 1e-8, and with small sliding two-body Hertz within the tests'
bounds (0.5 %, L2 1.5 %; updated pairing adds the O(a/R) geometry Hertz drops). One case in seven is
hostile input (a non-finite, overflowing or malformed number, or a path with a quote, a control
character or a leading '-'): exit 2 with one error line naming the parameter, nothing written, nothing
run. One in seven is a hostile folder or state (issue 42): a hard link at an output's name (the
file outside untouched), a run's mesh read back from its output folder (kept), a FIFO, a link to
/dev/zero or a folder where a file is read (refused at once), a time run ended before its impact is
over (exit 4, no result against a reference), a -tol beyond 1e-5 (exit 2). Prints the worst case of
each check with the command that reproduces it, and writes results/sweep/sweep.json.
    sweep.py [--n 200] [--seed 20261122] [--jobs 2]
On a cluster (docs/scaling.md): the cases as a run list (scripts/run_list.py), one per job-array task,
each task's verdict in <out>/<case>/check.json, then their summary:
    sweep.py --n 200 --write-list runs.jsonl
    sweep.py --list runs.jsonl --index K [--out DIR]      (task K)
    sweep.py --list runs.jsonl --collect [--out DIR]"""

import argparse
import concurrent.futures
import csv
import json
import math
import os
import random
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from freefem import ROOT, read_summary, run_driver  # noqa: E402
import run_list  # noqa: E402


def draw_hertz(rng):
    E = 10 ** rng.uniform(7, 10)                   # 3 decades
    nu = rng.uniform(0.0, 0.4999)                  # up to the incompressible limit (nodal form from 0.45)
    R = rng.uniform(0.5, 2.0)
    a_over_R = rng.uniform(0.02, 0.08)             # small strain: where Hertz's theory holds
    f = (a_over_R * R) ** 2 * math.pi * E / (8 * R ** 2 * (1 - nu ** 2))
    a = a_over_R * R
    # the nodal form's contact pressure alternates node to node on coarse meshes (docs/rubber.md:
    # L2 of p 1.2 % at a/30, 0.5 % at a/45, 0.3 % at a/60 for nu = 0.499): finer there
    h = a / (rng.uniform(30, 45) if nu < 0.45 else rng.uniform(45, 60))
    return "benchmarks/hertz_plane.edp", ["-E", f"{E:.6g}", "-nu", f"{nu:.4f}", "-R", f"{R:.4f}",
                                          "-pressure", f"{f:.6g}", "-h", f"{h:.6g}"], R


def draw_cube(rng):
    material = rng.choice(["mooney", "neohookean"])
    C10 = 10 ** rng.uniform(-1, 1)
    C01 = 10 ** rng.uniform(-1, 1) if material == "mooney" else 0.0
    nu = 0.5 if rng.random() < 0.2 else rng.uniform(0.0, 0.4999)   # one in five exactly incompressible
    pressure = rng.uniform(0.05, 1.0) * (C10 + C01)
    dim = rng.choice(["2", "2", "3", "axi"])   # axi: the axisymmetric cylinder
    n = str(rng.randint(2, 3) if dim == "3" else rng.randint(3, 6))
    foundation = rng.choice(["0", "1"])
    return "benchmarks/cube.edp", ["-material", material, "-C10", f"{C10:.6g}", "-C01", f"{C01:.6g}", "-nu", f"{nu:.4f}",
                                   "-pressure", f"{pressure:.6g}", "-dim", dim, "-n", n, "-foundation", foundation], 1.0


def draw_oring(rng):
    C10 = 10 ** rng.uniform(-1, 1)
    nu = rng.uniform(0.3, 0.4999)
    cmax = rng.uniform(0.1, 0.3)
    R = 0.52
    h = R / rng.uniform(8, 14)
    return "benchmarks/oring.edp", ["-case", "plates", "-C10", f"{C10:.6g}", "-nu", f"{nu:.4f}", "-cmax", f"{cmax:.4f}",
                                    "-h", f"{h:.6g}", "-steps", "6"], R


def draw_sphere_axisymmetric(rng):
    E = 10 ** rng.uniform(4, 7)
    nu = rng.uniform(0.0, 0.4999)
    R = rng.uniform(0.5, 2.0)
    a_over_R = rng.uniform(0.05, 0.12)
    # a = (3 P R (1 - nu^2) / (4 E))^(1/3) with P = f pi R^2
    f = (a_over_R * R) ** 3 * 4 * E / (3 * R * (1 - nu ** 2) * math.pi * R ** 2)
    return "benchmarks/hertz_sphere.edp", ["-dim", "axi", "-E", f"{E:.6g}", "-nu", f"{nu:.4f}", "-R", f"{R:.4f}",
                                          "-pressure", f"{f:.6g}"], R


def draw_two_cylinders(rng):
    E1 = 10 ** rng.uniform(4, 7)
    E2 = E1 * 10 ** rng.uniform(-1, 1)
    nu1, nu2 = rng.uniform(0.0, 0.45), rng.uniform(0.0, 0.45)
    R1, R2 = rng.uniform(0.5, 2.0), rng.uniform(0.5, 2.0)
    R = R1 * R2 / (R1 + R2)
    E_star = 1 / ((1 - nu1 ** 2) / E1 + (1 - nu2 ** 2) / E2)
    a = rng.uniform(0.02, 0.06) * R                  # small strain, and the zone 1.5 a < min(R1, R2) / 2
    f = a ** 2 * math.pi * E_star / (8 * R * R1)     # a = sqrt(4 P R / (pi E*)), P = 2 f R1
    return "benchmarks/hertz_two_cylinders.edp", [
        "-E1", f"{E1:.6g}", "-E2", f"{E2:.6g}", "-nu1", f"{nu1:.4f}", "-nu2", f"{nu2:.4f}", "-R1", f"{R1:.4f}",
        "-R2", f"{R2:.4f}", "-pressure", f"{f:.6g}", "-slave", rng.choice(["softer", "upper", "lower"]),
        "-constraint", rng.choice(["small", "small", "updated"])], 2 * max(R1, R2)


# Hostile input (issue 26): one parameter of a driver given a value no parameter accepts. The run
# must stop before any work: exit 2, one `error:` line naming the parameter, no summary.json, and
# nothing run through a shell (the canary file `pwned` never appears).
HOSTILE_NUMBERS = ["inf", "-inf", "nan", "NaN", "1e400", "-1e400", "1e31", "-1e-31", "1" + "0" * 400, "0x10", "1,5",
                   "", " ", "--", "-1e", "1e+", "\u00b9", "1\n2", "$(touch${IFS}pwned)", "'; touch pwned; '"]
HOSTILE_PATHS = ["-rf", "--help", "o';touch${IFS}pwned;'", 'o";touch pwned;"', "o`touch${IFS}pwned`", "o\\x",
                 "o\nnew", "o\rret", "o\x01ctl", ""]
HOSTILE_PARAMS = {
    "benchmarks/cube.edp": (["C10", "nu", "pressure", "n", "steps", "tol"], ["out"]),
    "benchmarks/hertz_plane.edp": (["E", "nu", "R", "pressure", "h", "zone", "gap"], ["out", "mesh"]),
    "benchmarks/hertz_circle.edp": (["R2", "splinepoints", "pressure"], ["out", "splinefile"]),
    "benchmarks/hertz_sphere.edp": (["E", "pressure", "h", "candidates"], ["out", "mesh"]),
    "benchmarks/hertz_two_cylinders.edp": (["E1", "R2", "gap", "pressure"], ["out"]),
    "benchmarks/oring.edp": (["C10", "cmax", "h", "side"], ["out"]),
    "benchmarks/oring_torus.edp": (["meanradius", "C10", "cmax"], ["out"]),
    "benchmarks/sliding_disc.edp": (["E1", "press", "slide", "h"], ["out"]),
    "benchmarks/indentation.edp": (["E", "depth", "block", "h"], ["out"]),
    "benchmarks/cattaneo.edp": (["mu", "ratio", "pressure", "h", "travel", "hold"], ["out"]),
    "benchmarks/mindlin_sphere.edp": (["mu", "ratio", "force", "R", "h", "steps", "hold", "nu", "block"], ["out"]),
    "benchmarks/bar_impact.edp": (["dt", "tend", "v0", "rho", "n", "cfl", "every"], ["out"]),
    "benchmarks/sphere_impact.edp": (["v0", "R", "dt", "zone", "rho", "candidates"], ["out"]),
    "benchmarks/bars_head_on.edp": (["v0", "gap", "nA", "dt"], ["out"]),
    "benchmarks/discs_head_on.edp": (["v0", "gap", "R", "dt", "h"], ["out"]),
    "benchmarks/patch_test.edp": (["pressure", "n1", "n2", "mu"], ["out"]),
}


def draw_hostile(rng):
    script = rng.choice(sorted(HOSTILE_PARAMS))
    numeric, paths = HOSTILE_PARAMS[script]
    if rng.random() < 0.6:
        name, value = rng.choice(numeric), rng.choice(HOSTILE_NUMBERS)
    else:
        name, value = rng.choice(paths), rng.choice(HOSTILE_PATHS)
    return script, [f"-{name}", value], "hostile"


# Hostile folders and states (issue 42): what lies in the output folder or where an input is read,
# and runs that cannot reach what their references describe. Each kind with what it must give.
OUTPUT_NAMES = ["pressure.csv", "ipopt.opt", "summary.json", "hertz_plane.vtu",
                "ipopt_step00001.log"]
SPECIAL = ["fifo .outputs", "zero .outputs", "fifo pressure.csv", "fifo -mesh", "folder -mesh",
           "fifo -splinefile"]
READER = {"-mesh": "benchmarks/hertz_plane.edp", "-splinefile": "benchmarks/hertz_circle.edp"}


def draw_hostile_state(rng):
    kind = rng.choice(["link", "input", "special", "short", "tol"])
    if kind == "link":
        return "benchmarks/hertz_plane.edp", [rng.choice(OUTPUT_NAMES)], "hostile-link"
    if kind == "input":   # (a fixed coarse mesh: at h = 0.0274 its Hertz fit failed, exit 3)
        args = ["-h", "0.02", "-zone", "0.2", "-hmax", "0.3"]
        return "benchmarks/hertz_sphere.edp", args, "hostile-input"
    if kind == "special":
        what = rng.choice(SPECIAL)
        return READER.get(what.split()[1], "benchmarks/cube.edp"), what.split(), "hostile-special"
    if kind == "short":   # the bar meets the wall at 1e-5 s and leaves it at 7.9e-5 s
        args = ["-n", str(rng.randint(20, 60)), "-gap", "1e-3", "-every", "0",
                "-tend", f"{rng.uniform(2e-6, 6e-5):.3g}"]
        return "benchmarks/bar_impact.edp", args, "hostile-short"
    script = rng.choice(["benchmarks/hertz_plane.edp", "benchmarks/cube.edp",
                         "benchmarks/platen_block.edp"])
    return script, ["-tol", f"{10 ** rng.uniform(-4.9, -1):.3g}"], "hostile-tol"


DRAWS = [draw_hertz, draw_cube, draw_oring, draw_sphere_axisymmetric, draw_two_cylinders,
         draw_hostile, draw_hostile_state]


def check_hostile(script, args, out_dir):
    """A hostile case: exit 2, the first line an `error:` line naming the parameter, the only one,
    no summary.json, no canary file."""
    code, output, seconds = run_driver(script, args, None if args[0] == "-out" else out_dir)
    errors = [l for l in output.splitlines() if l.startswith("error:")]
    first = output.strip().splitlines()[0] if output.strip() else ""
    canary = any(os.path.exists(os.path.join(d, "pwned")) for d in (ROOT, os.path.dirname(os.path.abspath(out_dir))))
    left = os.path.exists(os.path.join(out_dir, "summary.json"))
    ok = code == 2 and len(errors) == 1 and first == errors[0] and args[0] in first and not left and not canary
    cmd = f"FreeFem++ {script} {' '.join(repr(a) for a in args)}"
    detail = f"exit {code}: {first[:120]}" + (" (canary file created)" if canary else "") + (" (summary left)" if left else "")
    return {"command": cmd, "failed": not ok, "detail": detail, "checks": {}, "seconds": seconds}


def check_hostile_state(script, args, kind, out_dir):
    """A hostile folder or state (draw_hostile_state): what each kind must give, nothing lost."""
    folder = out_dir if os.path.isabs(out_dir) else os.path.join(ROOT, out_dir)
    os.makedirs(folder, exist_ok=True)
    run_args, seconds, detail = [], 0.0, ""

    def plant(path):   # (a sweep run again into its folders: what it planted before goes first)
        if os.path.isdir(path) and not os.path.islink(path):
            os.rmdir(path)
        elif os.path.lexists(path):
            os.remove(path)
        return path
    if kind == "link":   # a hard link at an output's name: replaced, the file outside untouched
        victim = folder + ".outside"
        with open(victim, "w") as f:
            f.write("precious\n")
        os.link(victim, plant(os.path.join(folder, args[0])))
        code, output, seconds = run_driver(script, [], folder)
        ok = code == 0 and open(victim).read() == "precious\n"
        detail = f"exit {code}, the file outside {'untouched' if ok else 'changed'}"
    elif kind == "input":   # the run's own mesh read back from its output folder: kept, read
        code1, _, s1 = run_driver(script, args, folder)
        mesh = os.path.join(folder, "quarter_hemisphere.msh")
        before = open(mesh).read() if os.path.exists(mesh) else None
        run_args = ["-mesh", mesh]
        code, output, s2 = run_driver(script, run_args, folder)
        seconds = s1 + s2
        kept = before is not None and os.path.exists(mesh) and open(mesh).read() == before
        ok = code1 == 0 and code == 0 and kept
        detail = f"exits {code1}, {code}; the mesh {'kept' if ok else 'lost or changed'}"
    elif kind == "special":   # a FIFO, /dev/zero or a folder where a file is read: refused at once
        what, where = args
        target = plant(folder + ".input" if where.startswith("-") else os.path.join(folder, where))
        if what == "fifo":
            os.mkfifo(target)
        elif what == "zero":
            os.symlink("/dev/zero", target)
        else:
            os.makedirs(target)
        run_args = [where, target] if where.startswith("-") else []
        try:
            code, output, seconds = run_driver(script, run_args, folder, timeout=120)
        except subprocess.TimeoutExpired:
            code, output, seconds = "timeout", "", 120.0
        errors = [l for l in output.splitlines() if l.startswith("error:")]
        ok = (code == 2 and len(errors) == 1 and os.path.lexists(target)
              and read_summary(folder) is None)
        detail = f"exit {code}: {errors[:1]}"
    else:   # a short time run (exit 4, impact_over, no reference), a loose -tol (exit 2 naming it)
        code, output, seconds = run_driver(script, args, folder)
        s = read_summary(folder)
        if kind == "short":
            ok = code == 4 and s is not None and s["checks_failed"] == ["impact_over"] and all(
                q["reference"] is None for q in s["results"].values())
        else:
            ok = code == 2 and s is None and any(l.startswith("error:") and "-tol" in l
                                                 for l in output.splitlines())
        detail = f"exit {code}: {[l for l in output.splitlines() if l.startswith('error:')][:1]}"
    cmd = f"({kind}) FreeFem++ {script} {' '.join(repr(a) for a in (run_args or args))}"
    return {"command": cmd, "failed": not ok, "detail": detail, "checks": {}, "seconds": seconds}


def check_case(name, script, args, size, out_root, processes=1):
    """The case's run into <out_root>/<name> and its verdict, also written there as check.json."""
    out_dir = os.path.join(out_root, name)
    result = run_case(out_dir, script, args, size, processes)
    folder = out_dir if os.path.isabs(out_dir) else os.path.join(ROOT, out_dir)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "check.json"), "w") as f:
        json.dump(result, f, indent=1)
    return result


def run_case(out_dir, script, args, size, processes):
    if size == "hostile":
        return check_hostile(script, args, out_dir)
    if str(size).startswith("hostile-"):
        return check_hostile_state(script, args, size[len("hostile-"):], out_dir)
    code, output, seconds = run_driver(script, args, out_dir, processes=processes)
    s = read_summary(out_dir)
    cmd = f"FreeFem++ {script} {' '.join(args)}"
    checks = {}
    if code != 0 or s is None or s["ipopt_status"] != "Solve_Succeeded":
        last = output.strip().splitlines()[-1:] if output.strip() else [""]
        return {"command": cmd, "failed": True, "detail": f"exit {code}: {last[0]}", "checks": checks, "seconds": seconds}
    r = s["results"]
    if "force_balance_rel_error" in r:
        # the solve stops when the energy's gradient is below -tol relative to the forces: the balance,
        # a sum of those residuals, is within the same tolerance (O-ring at tol 1e-7: 1.05e-8 seen)
        checks["force_balance_over_tol"] = (r["force_balance_rel_error"]["computed"] / s["parameters"]["tol"], 1.0)
    if "max_penetration" in r:
        checks["penetration_over_size"] = (r["max_penetration"]["computed"] / size, 1e-10)
    rows = None
    pressure_csv = os.path.join(out_dir if os.path.isabs(out_dir) else os.path.join(ROOT, out_dir), "pressure.csv")
    if os.path.exists(pressure_csv):
        with open(pressure_csv) as f:
            rows = list(csv.DictReader(f))
        p = [float(row["pressure"]) for row in rows]
        checks["tensile_pressure_over_pmax"] = (max(0.0, -min(p)) / max(p), 1e-6)
    if script.endswith("hertz_plane.edp"):
        # the tests' Hertz bounds at every nu up to 0.4999 (the nodal form from nu = 0.45; the
        # penalty form locked: L2 of p 2.7 % at nu = 0.4845)
        checks["hertz_a"] = (r["a"]["rel_error"], 3e-3)
        checks["hertz_p_max"] = (r["p_max"]["rel_error"], 3e-3)
        checks["hertz_L2_p"] = (r["pressure_l2_rel_error"]["computed"], 1e-2)
    if script.endswith("cube.edp"):
        checks["cube_w"] = (r["w"]["rel_error"], 1e-8)
    if script.endswith("hertz_two_cylinders.edp"):
        checks["two_body_action_reaction"] = (r["action_reaction_rel_error"]["computed"], 1e-12)
        checks["two_body_balance"] = (max(r["upper_balance_rel_error"]["computed"], r["lower_balance_rel_error"]["computed"]), 1e-8)
        small = "updated" not in args
        prefix = "two_body_hertz" if small else "info_two_body_updated_hertz"
        checks[prefix + "_a"] = (r["a"]["rel_error"], 5e-3)
        checks[prefix + "_p_max"] = (r["p_max"]["rel_error"], 5e-3)
        checks[prefix + "_L2_p"] = (r["pressure_l2_rel_error"]["computed"], 1.5e-2)
    return {"command": cmd, "failed": False, "checks": checks, "seconds": seconds}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=200)
    parser.add_argument("--seed", type=int, default=20261122)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--out", default=os.path.join("results", "sweep"))
    parser.add_argument("--write-list", help="write the drawn cases as a run list and stop")
    parser.add_argument("--list", help="run the cases of this run list instead of drawing them")
    parser.add_argument("--index", type=int, help="with --list: only its case K (a job array's task)")
    parser.add_argument("--collect", action="store_true", help="with --list: summarise the cases' check.json")
    args = parser.parse_args()
    if args.list:   # a sweep case carries its size (sweep.py --write-list writes it)
        cases, chosen = run_list.load(args.list, args.index, required=("size",))
    else:
        rng = random.Random(args.seed)
        cases = [dict(zip(("script", "args", "size"), DRAWS[i % len(DRAWS)](rng)), name=f"case{i:04d}") for i in range(args.n)]
        chosen = cases
    if args.write_list:
        run_list.write(args.write_list, cases)
        return 0
    if args.collect:
        if not args.list:
            print("error: --collect needs the run list (--list)")
            return 2
        results = []
        for case in cases:
            path = os.path.join(args.out if os.path.isabs(args.out) else os.path.join(ROOT, args.out), case["name"], "check.json")
            if not os.path.exists(path):
                print(f"error: case {case['name']} has not run: no {path}")
                return 2
            results.append(json.load(open(path)))
        return summarise(results, args)
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(check_case, c["name"], c["script"], c["args"], c["size"], args.out, c.get("processes", 1))
                   for c in chosen]
        results = []
        for i, fut in enumerate(futures):
            results.append(fut.result())
            print(f"case {i + 1}/{len(chosen)}: {'FAILED' if results[-1]['failed'] else 'ok'} "
                  f"({results[-1]['seconds']:.1f} s) {results[-1]['command']}", flush=True)
    if args.index is not None:   # one task: its verdict is in check.json, the summary comes with --collect
        return 1 if results[0]["failed"] or any(not v <= b and not k.startswith("info_") for k, (v, b) in results[0]["checks"].items()) else 0
    return summarise(results, args)


def summarise(results, args):
    """The worst case of each check, the failed runs, sweep.json; 1 when any run failed or check was violated."""
    worst = {}
    for res in results:
        for name, (value, bound) in res["checks"].items():
            if name not in worst or value > worst[name][0]:
                worst[name] = (value, bound, res["command"])
    failed_runs = [res for res in results if res["failed"]]
    violations = sum(1 for res in results for name, (v, b) in res["checks"].items() if not v <= b and not name.startswith("info_"))
    origin = f"list {args.list}" if args.list else f"seed {args.seed}"
    print(f"\nsweep: {len(results)} cases ({origin}), {len(failed_runs)} failed runs, {violations} check violations")
    for name, (value, bound, cmd) in sorted(worst.items()):
        verdict = "ok" if value <= bound else ("beyond, not a check" if name.startswith("info_") else "VIOLATED")
        print(f"  worst {name}: {value:.2e} (bound {bound:.0e}) {verdict}\n    {cmd}")
    for res in failed_runs:
        print(f"  failed run: {res['detail']}\n    {res['command']}")
    out = args.out if os.path.isabs(args.out) else os.path.join(ROOT, args.out)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "sweep.json"), "w") as f:
        json.dump({"n": len(results), "seed": None if args.list else args.seed, "list": args.list,
                   "failed_runs": len(failed_runs), "violations": violations,
                   "worst": {k: {"value": v[0], "bound": v[1], "command": v[2]} for k, v in worst.items()},
                   "cases": results}, f, indent=1)
    return 1 if failed_runs or violations else 0


if __name__ == "__main__":
    sys.exit(main())
