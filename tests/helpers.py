"""What the tests share: the soft check, each test's scratch folders, running a driver, and the
helpers several test files use. A test makes many checks; each is one `check(name, condition,
detail)`: all of a test's checks run and are printed, and the test fails at its end if any failed
(tests/conftest.py), so one wrong number does not hide the others."""

import csv  # noqa: F401 (the test files use these through `from helpers import *`)
import json  # noqa: F401
import os
import re
import shutil  # noqa: F401
import subprocess  # noqa: F401
import sys
import tempfile
import time  # noqa: F401

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from freefem import ROOT, read_summary, run_driver, run_ok  # noqa: E402,F401
import verdicts  # noqa: E402,F401

# one scratch folder per process (pytest-xdist runs tests in two processes), removed at the end
TMP = tempfile.mkdtemp(prefix="contact-tests-")
CHECKS = []      # the current test's checks: (name, ok, detail)


def record(name, ok, detail=""):
    CHECKS.append((name, ok, detail))
    print(f"{'PASS' if ok else 'FAIL'}  {name}  {detail}", flush=True)


def check(name, condition, detail=""):
    record(name, bool(condition), detail)


def out(name):
    return os.path.join(TMP, re.sub(r"\W+", "_", name))


def run_summary(label, script, args):
    """Runs a driver into its own folder; its summary, or None (recorded as a failure)."""
    o = out(label)
    code, output, _ = run_driver(script, args, o)
    s = read_summary(o)
    if code != 0 or s is None:
        record(label, False, f"exit {code}: {output.strip().splitlines()[-3:]}")
        return None
    return s


def check_script_cases(name, expected, prefix=None, processes=1):
    """Runs tests/<name>.edp (on `processes` MPI processes when > 1), which prints one '<name>
    dim=... PASS|FAIL' line per case (or one line starting with `prefix` and ending in PASS or FAIL)
    and exits 1 on a failure: each line is a check, and so are the count and the exit code."""
    code, output, _ = run_driver(f"tests/{name}.edp", [], None, processes=processes)
    if prefix is None:
        lines = [l for l in output.splitlines() if l.startswith(f"{name} dim=")]
    else:
        lines = [l for l in output.splitlines() if l.startswith(prefix) and l.rstrip().endswith(("PASS", "FAIL"))]
    check(f"{name}: {expected} cases ran", len(lines) == expected, f"{len(lines)} lines")
    for line in lines:
        check(f"{name} " + " ".join(line.split()[1:3]), line.endswith("PASS"), line)
    check(f"{name} exit code", code == 0, f"exit {code}")


def registered_laws(include_dir=os.path.join(ROOT, "include")):
    """The law names listed in include/laws/registry.idp (read here, independently of FreeFEM)."""
    text = open(os.path.join(include_dir, "laws", "registry.idp")).read()
    body = re.search(r"^macro registeredLaws\(apply\)(.*?)// EOM", text, re.M | re.S).group(1)
    return re.findall(r"apply\((\w+)\)", body)


def suite_copy(name):
    """A copy of include/ in a work folder of its own, with a freefem++.pref that reads it."""
    work = out(name)
    include = os.path.join(work, "include")
    shutil.copytree(os.path.join(ROOT, "include"), include)
    with open(os.path.join(work, "freefem++.pref"), "w") as f:
        f.write(f'loadpath += "/usr/lib/freefem++"\nloadpath += "{ROOT}/plugin"\nincludepath += "{include}"\nverbosity = 0\n')
    return work, include


def planted_suite(name, rel, old, new):
    """A copy of include/ (suite_copy) with `old` replaced by `new` in include/<rel>: the work folder, and
    whether `old` was there (a test checks it, so that a renamed line cannot make the copy the original)."""
    work, include = suite_copy(name)
    path = os.path.join(include, rel)
    text = open(path).read()
    with open(path, "w") as f:
        f.write(text.replace(old, new))
    return work, old in text


def registered_obstacles(include_dir=os.path.join(ROOT, "include")):
    """The obstacle kinds listed in include/contact/obstacles.idp (read here, independently of FreeFEM)."""
    text = open(os.path.join(include_dir, "contact", "obstacles.idp")).read()
    body = re.search(r"^macro registeredObstacles\(apply\)(.*?)// EOM", text, re.M | re.S).group(1)
    return re.findall(r"apply\((\w+)\)", body)


def cube_case(label, args, tol=verdicts.bound("cube_2d_mooney", "w")):
    """The block under dead-load pressure is a homogeneous deformation: P1 reproduces
    it exactly, so the only error left is IPOPT's tolerance (-tol 1e-9 by default)."""
    s = run_summary(label, "benchmarks/cube.edp", args)
    if s is None:
        return None
    w = s["results"]["w"]
    check(f"{label}: |w - w_exact|/w_exact <= {tol}", w["rel_error"] <= tol,
          f"w={w['computed']:.10g} exact={w['reference']:.10g} rel={w['rel_error']:.2e}")
    lat = s["results"]["lateral_displacement"]
    check(f"{label}: lateral displacement exact to {tol}", lat["rel_error"] <= tol, f"rel={lat['rel_error']:.2e}")
    check(f"{label}: IPOPT status", s["ipopt_status"] == "Solve_Succeeded", s["ipopt_status"])
    return s


def homogeneous_case(label, args):
    """A cube run that must land on the exact homogeneous state: the lateral displacement (and w under
    the dead load; the platen imposes it) to 1e-8 and J uniform to 1e-8 (P1 reproduces the state
    exactly: what is left is the solver's tolerance, -tol 1e-9), the energy never below the exact
    state's by more than the solver's tolerance (1e-9 of its size: at nu = 0.5 the constraints hold to
    IPOPT's tolerance, and the energy dipped by 1.3e-10), and with the platen its force = the pressure
    times the top's area to 1e-8."""
    s = run_summary(label, "benchmarks/cube.edp", args)
    if s is None:
        return None
    r = s["results"]
    worst = max(r["w"]["rel_error"], r["lateral_displacement"]["rel_error"], r["J_spread"]["computed"])
    if "platen_force" in r:
        worst = max(worst, r["platen_force"]["rel_error"])
    e, ex = r["energy"]["computed"], r["energy_exact_state"]["computed"]
    check(f"{label}: the exact homogeneous state to 1e-8, energy not below it", worst <= 1e-8 and e >= ex - 1e-9 * abs(ex),
          f"worst {worst:.1e}, energy {e:.12g} vs exact {ex:.12g}")
    return s


def hertz_case(label, script, args, bound_a=verdicts.bound("hertz_plane", "a"),
               bound_l2=verdicts.bound("hertz_plane", "pressure_l2_rel_error"), size=lambda p: p["R"]):
    """Runs a Hertz driver; a and p_max (fit of p^2 against x^2, docs/benchmarks/hertz.md) within bound_a of
    Hertz's formulas (measured 3e-4 .. 1.6e-3 over the cases below: the finite disc, its far
    field at hmax = R/20 and h = a/30, docs/benchmarks/hertz.md), L2 of p within bound_l2 (edge of contact: ~0.2 % .. 0.7 % at h = a/30),
    force balance <= 1e-8 (solver tolerance 1e-8 on scaled stationarity: measured ~1e-13)
    and no penetration beyond 1e-10 R (bound relaxation is off: measured 0); R is size(parameters)."""
    s = run_summary(label, script, args)
    if s is None:
        return None
    r = s["results"]
    R = size(s["parameters"])
    check(f"{label}: IPOPT status", s["ipopt_status"] == "Solve_Succeeded", s["ipopt_status"])
    if bound_a is not None:
        for q in ("a", "p_max"):
            check(f"{label}: {q} within {bound_a:.1%} of Hertz", r[q]["rel_error"] <= bound_a,
                  f"{q}={r[q]['computed']:.6g} Hertz={r[q]['reference']:.6g} rel={r[q]['rel_error']:.2e}")
    if bound_l2 is not None:
        l2 = r["pressure_l2_rel_error"]["computed"]
        check(f"{label}: L2 error of p within {bound_l2:.1%}", l2 <= bound_l2, f"{l2:.2e}")
    fb = r["force_balance_rel_error"]["computed"]
    check(f"{label}: force balance <= 1e-8", fb <= 1e-8, f"{fb:.1e}")
    cf = r["contact_force"]["rel_error"]
    check(f"{label}: contact force = applied load to 1e-8", cf <= 1e-8, f"{cf:.1e}")
    pen = r["max_penetration"]["computed"]
    check(f"{label}: penetration <= 1e-10 R", pen <= 1e-10 * R, f"{pen:.1e}")
    return s


def same_plate_forces(label, condensed, full):
    """The O-ring plate forces at c = 0.1, 0.2, 0.3 of a condensed run equal the full path's to 1e-9."""
    for q in ("force_c0.1", "force_c0.2", "force_c0.3"):
        c, f = condensed["results"][q]["computed"], full["results"][q]["computed"]
        check(f"{label}: {q} = the full path's to 1e-9", abs(c - f) <= 1e-9 * abs(f), f"{c:.13g} vs {f:.13g}")


def read_pressure_csv(label):
    path = os.path.join(out(label), "pressure.csv")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows


def png_size(path):
    """(width, height) of a PNG file, or None when it is not one."""
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


def headless_env():
    """The environment of a machine without a display."""
    return {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}


def error_lines(output):
    return [l for l in output.splitlines() if l.startswith("error:")]


def two_body_case(label, script, args, bound_a, bound_l2):
    """A two-body Hertz run: hertz_case's checks against the two-body Hertz values (penetration
    relative to the bodies' size 2 max(R1, R2)), then action = reaction between the bodies (exact by construction: 1e-12), each
    body's own balance and the global one to 1e-8 (the solver's tolerance), the load carried to the
    master body to 1e-8, no penetration of slave nodes beyond 1e-10 of the body size, no tensile
    pressure beyond 1e-6 p_max (IPOPT's complementarity)."""
    s = hertz_case(label, script, args, bound_a, bound_l2, size=lambda p: 2 * max(p["R1"], p["R2"]))
    if s is None:
        return None
    r = s["results"]
    ar = r["action_reaction_rel_error"]["computed"]
    check(f"{label}: action = reaction between the bodies to 1e-12", ar <= 1e-12, f"{ar:.1e}")
    for q in ("upper_balance_rel_error", "lower_balance_rel_error"):
        v = r[q]["computed"]
        check(f"{label}: {q} <= 1e-8", v <= 1e-8, f"{v:.1e}")
    check(f"{label}: master force = applied load to 1e-8", r["master_force"]["rel_error"] <= 1e-8,
          f"{r['master_force']['rel_error']:.1e}")
    rows = read_pressure_csv(label) or []
    tensile = min((float(row["pressure"]) for row in rows), default=-1e300)
    check(f"{label}: pressure.csv, no tensile pressure beyond 1e-6 p_max", rows and tensile >= -1e-6 * r["p_max"]["reference"],
          f"{tensile:.2e}")
    return s


def check_no_tensile_pressure(label):
    """The run's pressure.csv: no tensile pressure beyond 1e-6 of its peak (IPOPT's complementarity)."""
    rows = read_pressure_csv(label) or []
    pressures = [float(row["pressure"]) for row in rows]
    check(f"{label}: no tensile pressure beyond 1e-6 of the peak", pressures and min(pressures) >= -1e-6 * max(pressures),
          f"{min(pressures) if pressures else None}")


def flange_checks(label, s, size):
    """What every O-ring flange run must hold: action = reaction (exact by construction), each
    body's balance and the global one to 1e-8 (the solver's tolerance), no penetration and a
    settled pairing within 1e-10 of the size, no tensile pressure beyond 1e-6 of the peak."""
    r = s["results"]
    check(f"{label}: IPOPT converged every step", s["ipopt_status"] == "Solve_Succeeded" and s["complete"], s["ipopt_status"])
    check(f"{label}: action = reaction to 1e-12", r["action_reaction_rel_error"]["computed"] <= 1e-12,
          f"{r['action_reaction_rel_error']['computed']:.1e}")
    for q in ("ring_balance_rel_error", "flange_balance_rel_error", "force_balance_rel_error"):
        check(f"{label}: {q} <= 1e-8", r[q]["computed"] <= 1e-8, f"{r[q]['computed']:.1e}")
    for q, scale in (("max_penetration", size), ("pairing_change_rel", 1.0)):
        check(f"{label}: {q} <= 1e-10 of the size", r[q]["computed"] <= 1e-10 * scale, f"{r[q]['computed']:.1e}")
    check_no_tensile_pressure(label)
    # activity from the multipliers (issue 26): the last step's pressure.csv had every row inactive
    # with non-zero pressures, and the half-width reported 0
    rows = read_pressure_csv(label) or []
    peak = max((float(row["pressure"]) for row in rows), default=0)
    # active: a multiplier above 1e-6 of the largest (contact/report.idp); the pressure is the multiplier
    # over the node's share of the boundary, which differs from node to node by a factor of a few
    mislabelled = [row for row in rows if (float(row["pressure"]) > 1e-4 * peak and row["active"] != "1")
                   or (row["active"] == "1" and not float(row["pressure"]) > 0)]
    check(f"{label}: pressure.csv: every row above 1e-4 of the peak pressure active, every active row pressed",
          rows and peak > 0 and not mislabelled, f"{len(mislabelled)} of {len(rows)} rows disagree")
    with open(os.path.join(out(label), "force_squeeze.csv")) as f:
        last = list(csv.DictReader(f))[-1]
    check(f"{label}: the last step's contact half-width is positive", float(last["contact_half_width"]) > 0,
          last["contact_half_width"])
