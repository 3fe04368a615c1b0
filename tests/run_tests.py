#!/usr/bin/env python3
"""`make test`: the test suite. Each test asserts numbers against a named reference;
the last line is `N passed, N failed` and the exit code is non-zero on any failure."""

import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
from freefem import ROOT, read_summary, run_driver  # noqa: E402

RESULTS = []
TMP = tempfile.mkdtemp(prefix="contact-tests-")


def record(name, ok, detail=""):
    RESULTS.append(ok)
    print(f"{'PASS' if ok else 'FAIL'}  {name}  {detail}", flush=True)


def check(name, condition, detail=""):
    record(name, bool(condition), detail)


def out(name):
    return os.path.join(TMP, re.sub(r"\W+", "_", name))


# ---------------------------------------------------------------- derivatives
def test_law_derivatives():
    """Every law's P and A against central differences of psi and P (fd_laws.edp):
    truncation ~h^2 = 1e-10, so 1e-8 is what the method allows with margin."""
    code, output, _ = run_driver("tests/fd_laws.edp", [], None)
    lines = [l for l in output.splitlines() if l.startswith("fd_laws dim=")]
    check("fd_laws: 6 law/dimension checks ran", len(lines) == 6, f"{len(lines)} lines")
    for line in lines:
        check("fd_laws " + " ".join(line.split()[1:3]), line.endswith("PASS"), line)
    check("fd_laws exit code", code == 0, f"exit {code}")


def test_obstacle_derivatives():
    """Gradient and Hessian of every obstacle g(x) against central differences
    (fd_obstacles.edp, h = 1e-5: truncation ~1e-10, tolerance 1e-8)."""
    code, output, _ = run_driver("tests/fd_obstacles.edp", [], None)
    lines = [l for l in output.splitlines() if l.startswith("fd_obstacles obstacle=")]
    check("fd_obstacles: 5 obstacle checks ran", len(lines) == 5, f"{len(lines)} lines")
    for line in lines:
        check("fd_obstacles " + line.split()[1], line.endswith("PASS"), line)
    check("fd_obstacles exit code", code == 0, f"exit {code}")


# ---------------------------------------------------------------- cube
def cube_case(label, args, tol=1e-8):
    """The block under dead-load pressure is a homogeneous deformation: P1 reproduces
    it exactly, so the only error left is IPOPT's tolerance (-tol 1e-9 by default)."""
    o = out(label)
    code, output, _ = run_driver("benchmarks/cube.edp", args, o)
    s = read_summary(o)
    if code != 0 or s is None:
        record(label, False, f"exit {code}: {output.strip().splitlines()[-3:]}")
        return None
    w = s["results"]["w"]
    check(f"{label}: |w - w_exact|/w_exact <= {tol}", w["rel_error"] <= tol,
          f"w={w['computed']:.10g} exact={w['reference']:.10g} rel={w['rel_error']:.2e}")
    lat = s["results"]["lateral_displacement"]
    check(f"{label}: lateral displacement exact to {tol}", lat["rel_error"] <= tol, f"rel={lat['rel_error']:.2e}")
    check(f"{label}: IPOPT status", s["ipopt_status"] == "Solve_Succeeded", s["ipopt_status"])
    return s


def test_cube():
    expected = {"mooney": 0.0340725, "neohookean": 0.0783308}   # preprint / issue, 6 digits
    for material in ("mooney", "neohookean"):
        for dim, n in (("2", "6"), ("3", "3")):
            s = cube_case(f"cube {dim}D {material}", ["-material", material, "-dim", dim, "-n", n])
            if s is None:
                continue
            w_exact = s["results"]["w"]["reference"]
            check(f"cube {dim}D {material}: exact solution is the preprint's {expected[material]}",
                  abs(w_exact - expected[material]) < 5e-8, f"{w_exact:.8f}")
            if dim == "2":
                ca = s["results"]["w_vs_code_aster_incompressible"]["rel_error"]
                check(f"cube {dim}D {material}: 0.19 % from Code_Aster's incompressible value",
                      abs(ca - 0.0019) < 0.0001, f"{ca:.5f}")


def test_cube_second_parameter_set():
    """Non-default data and 3 load steps: same exactness, one record per step."""
    for material, extra in (("mooney", ["-C10", "0.5", "-C01", "0.8"]), ("neohookean", ["-C10", "2.0"])):
        for dim, n in (("2", "5"), ("3", "2")):
            args = ["-material", material, "-dim", dim, "-n", n, "-nu", "0.45", "-pressure", "0.3", "-steps", "3"] + extra
            s = cube_case(f"cube {dim}D {material} nu=0.45 p=0.3 3 steps", args)
            if s is not None:
                check(f"cube {dim}D {material} 3 steps: three step records, load 1/3, 2/3, 1",
                      [round(st["load_factor"], 12) for st in s["steps"]] == [round(1 / 3, 12), round(2 / 3, 12), 1.0])


def test_cube_on_foundation():
    """The block resting on the rigid plane y = 0 (contact instead of u_y = 0) has the same
    exact solution; the contact force from IPOPT's multipliers must carry the whole load
    (pressure x top area) and nothing may sink into the plane."""
    for material in ("mooney", "neohookean"):
        for dim, n in (("2", "6"), ("3", "3")):
            label = f"cube {dim}D {material} on foundation"
            s = cube_case(label, ["-material", material, "-dim", dim, "-n", n, "-foundation", "1"])
            if s is None:
                continue
            f = s["results"]["contact_force"]
            check(f"{label}: contact force = applied load to 1e-10", f["rel_error"] <= 1e-10,
                  f"{f['computed']:.12g} vs {f['reference']:.12g}, rel={f['rel_error']:.1e}")
            p = s["results"]["max_penetration"]["computed"]
            check(f"{label}: penetration <= 1e-10 x block height", p <= 1e-10, f"{p:.1e}")


def test_output_contract():
    o = out("contract")
    code, _, _ = run_driver("benchmarks/cube.edp", ["-n", "2"], o)
    s = read_summary(o) or {}
    for key in ("benchmark", "parameters", "ndof", "ipopt_status", "ipopt_iterations", "wall_time_s", "results"):
        check(f"summary.json has '{key}'", key in s)
    params = s.get("parameters", {})
    check("summary.json lists every parameter", all(k in params for k in
          ("material", "C10", "C01", "nu", "pressure", "dim", "n", "steps", "out")), str(sorted(params)))
    vtu = os.path.join(o, "cube.vtu")
    text = open(vtu, errors="replace").read() if os.path.exists(vtu) else ""
    check("cube.vtu holds displacement, J, von Mises",
          all(f'Name="{n}"' in text for n in ("displacement", "J", "von_Mises")))
    logs = [f for f in os.listdir(o) if f.startswith("ipopt_step")] if os.path.isdir(o) else []
    check("IPOPT log is in the output folder", len(logs) == 1, str(logs))


def test_working_folder_untouched():
    """ff-Ipopt writes ipopt.out and reads ipopt.opt in the working folder: a hostile
    ipopt.opt (max_iter 0) must be ignored and nothing written next to it."""
    work = out("workdir")
    os.makedirs(work)
    with open(os.path.join(work, "freefem++.pref"), "w") as f:
        f.write('loadpath += "/usr/lib/freefem++"\nincludepath += "%s/include"\nverbosity = 0\n' % ROOT)
    with open(os.path.join(work, "ipopt.opt"), "w") as f:
        f.write("max_iter 0\n")
    before = set(os.listdir(work))
    code, output, _ = run_driver(os.path.join(ROOT, "benchmarks/cube.edp"), ["-n", "2"], os.path.join(work, "o"), cwd=work)
    after = set(os.listdir(work)) - {"o"}
    check("ipopt.opt in the working folder is not read", code == 0, output.strip().splitlines()[-1:])
    check("no stray files in the working folder", after == before, str(after - before))


# ---------------------------------------------------------------- bad input
def expect_error(label, args, word, out_dir=None):
    o = out_dir or out("bad-" + label)
    code, output, _ = run_driver("benchmarks/cube.edp", args, None if out_dir else o)
    first = output.strip().splitlines()[0] if output.strip() else ""
    check(f"bad input {label}: non-zero exit", code != 0, f"exit {code}")
    check(f"bad input {label}: one-line error naming {word}", first.startswith("error:") and word in first, first)
    check(f"bad input {label}: no summary.json", read_summary(o) is None)


def test_bad_input():
    expect_error("nu = 0.5", ["-nu", "0.5"], "-nu")
    expect_error("nu = 0.7", ["-nu", "0.7"], "-nu")
    expect_error("C10 < 0", ["-C10", "-1"], "-C10")
    expect_error("C10 + C01 = 0", ["-C10", "0", "-C01", "0"], "-C10")
    expect_error("pressure not a number", ["-pressure", "abc"], "-pressure")
    expect_error("dim 4", ["-dim", "4"], "-dim")
    expect_error("unknown parameter -nuu", ["-nuu", "0.3"], "-nuu")
    expect_error("unknown material", ["-material", "rubber"], "-material")
    expect_error("n = 0", ["-n", "0"], "-n")
    expect_error("out with a blank", ["-out", os.path.join(TMP, "a b")], "-out", out_dir=os.path.join(TMP, "a b"))
    expect_error("a parameter given twice", ["-nu", "0.3", "-nu", "0.4"], "-nu")


def test_ipopt_failure_is_reported():
    """An IPOPT status other than success: one line with the status name, non-zero exit."""
    o = out("maxiter")
    code, output, _ = run_driver("benchmarks/cube.edp", ["-maxiter", "1"], o)
    errors = [l for l in output.splitlines() if l.startswith("error:")]
    check("IPOPT failure: non-zero exit", code != 0, f"exit {code}")
    check("IPOPT failure: one error line with the status name",
          len(errors) == 1 and "Maximum_Iterations_Exceeded" in errors[0], str(errors))
    s = read_summary(o)
    check("IPOPT failure: summary.json records the status and the 1 iteration done",
          s is not None and s["ipopt_status"] == "Maximum_Iterations_Exceeded" and s["ipopt_iterations"] == 1,
          str(s and (s["ipopt_status"], s["ipopt_iterations"])))


def main():
    tests = [test_law_derivatives, test_obstacle_derivatives, test_cube, test_cube_second_parameter_set, test_cube_on_foundation,
             test_output_contract,
             test_working_folder_untouched, test_bad_input, test_ipopt_failure_is_reported]
    only = sys.argv[1:]
    for test in tests:
        if only and not any(o in test.__name__ for o in only):
            continue
        print(f"== {test.__name__}", flush=True)
        try:
            test()
        except Exception as exc:  # a crashing test is a failing test
            record(test.__name__, False, f"exception: {exc!r}")
    shutil.rmtree(TMP, ignore_errors=True)
    passed = sum(RESULTS)
    failed = len(RESULTS) - passed
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
