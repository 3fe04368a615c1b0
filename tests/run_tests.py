#!/usr/bin/env python3
"""`make test`: the test suite. Each test asserts numbers against a named reference;
the last line is `N passed, N failed` and the exit code is non-zero on any failure."""

import csv
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from freefem import ROOT, read_summary, run_driver  # noqa: E402
import verdicts  # noqa: E402

RESULTS = []
TMP = tempfile.mkdtemp(prefix="contact-tests-")


def record(name, ok, detail=""):
    RESULTS.append(ok)
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


# ---------------------------------------------------------------- derivatives
def check_script_cases(name, expected, prefix=None):
    """Runs tests/<name>.edp, which prints one '<name> dim=... PASS|FAIL' line per case (or one line
    starting with `prefix` and ending in PASS or FAIL) and exits 1 on a failure: each line is a
    check, and so are the count and the exit code."""
    code, output, _ = run_driver(f"tests/{name}.edp", [], None)
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
    line = re.search(r"^macro registeredLaws\(apply\)(.*)// EOM", text, re.M).group(1)
    return re.findall(r"apply\((\w+)\)", line)


def test_law_derivatives():
    """Every registered law's P and A against central differences of psi and P (fd_laws.edp),
    in 2D and 3D: truncation ~h^2 = 1e-10, so 1e-8 is what the method allows with margin. The
    expected cases come from the registry, so a new law is checked without touching this file."""
    laws = registered_laws()
    check_script_cases("fd_laws", 2 * len(laws) + 2)   # + two materials on two regions (2 checks)
    code, output, _ = run_driver("tests/fd_laws.edp", [], None)
    for law in laws:
        check(f"fd_laws: law {law} checked in 2D and 3D",
              all(f"fd_laws dim={d} law={law} " in output for d in (2, 3)))


def test_new_law_recipe():
    """The README's recipe for a new law, followed in a copy of include/: one new file (here the
    Mooney-Rivlin law renamed plantedLaw, with one planted error in d2W/dJ2) and one registration
    entry. The finite-difference test must pick the new law up with its own parameters and catch
    the planted error in its Hessian only, while the registered laws still pass."""
    work = out("new law")
    include = os.path.join(work, "include")
    shutil.copytree(os.path.join(ROOT, "include"), include)
    law = open(os.path.join(include, "laws", "mooneyRivlin.idp")).read()
    for old, new in (("mooneyRivlin", "plantedLaw"), ("MooneyRivlin", "PlantedLaw"), ("lawC10", "plantedC10"),
                     ("lawC01", "plantedC01")):
        law = law.replace(old, new)   # a law of its own: its own names and parameters
    planted = law.replace("28./9*plantedC01", "28./8*plantedC01")
    check("new law: the planted error is in the file", planted != law)
    with open(os.path.join(include, "laws", "plantedLaw.idp"), "w") as f:
        f.write(planted)
    registry = os.path.join(include, "laws", "registry.idp")
    text = open(registry).read()
    with open(registry, "w") as f:
        f.write(text.replace("apply(linearElastic) // EOM", "apply(linearElastic) apply(plantedLaw) // EOM"))
    check("new law: registered", "plantedLaw" in registered_laws(include))
    with open(os.path.join(work, "freefem++.pref"), "w") as f:
        f.write(f'loadpath += "/usr/lib/freefem++"\nloadpath += "{ROOT}/plugin"\nincludepath += "{include}"\nverbosity = 0\n')
    code, output, _ = run_driver(os.path.join(ROOT, "tests", "fd_laws.edp"), [], None, cwd=work)
    lines = [l for l in output.splitlines() if l.startswith("fd_laws dim=")]
    planted_lines = [l for l in lines if "law=plantedLaw " in l]
    check("new law: checked in 2D and 3D with the others", len(lines) == 2 * len(registered_laws(include)) + 2
          and len(planted_lines) == 2, f"{len(lines)} lines")
    check("new law: the planted Hessian error is caught (FAIL), the gradient passes",
          len(planted_lines) == 2 and all(l.endswith("FAIL") and float(re.search(r"gradient_rel_error=(\S+)", l).group(1)) <= 1e-8
                                          for l in planted_lines), str(planted_lines))
    check("new law: the registered laws still pass", all(l.endswith("PASS") for l in lines if l not in planted_lines))
    check("new law: fd_laws exits non-zero", code != 0, f"exit {code}")


def suite_copy(name):
    """A copy of include/ in a work folder of its own, with a freefem++.pref that reads it."""
    work = out(name)
    include = os.path.join(work, "include")
    shutil.copytree(os.path.join(ROOT, "include"), include)
    with open(os.path.join(work, "freefem++.pref"), "w") as f:
        f.write(f'loadpath += "/usr/lib/freefem++"\nloadpath += "{ROOT}/plugin"\nincludepath += "{include}"\nverbosity = 0\n')
    return work, include


def test_law_recipe_from_docs():
    """Issue 25: docs/adding_a_law.md followed literally. Its Yeoh example file is written to
    include/laws/yeoh.idp in a copy of the suite and registered as the page says; the finite-difference
    test checks it in 2D and 3D (1e-8, as every law); and with C20 = C30 = 0 it is the Neo-Hookean law,
    so the O-ring plates (a non-homogeneous, nearly incompressible problem where a law that kept its
    own volumetric term would lock) give Neo-Hookean's plate force under the default volumetric form at
    nu = 0.4999 and 0.5: both runs solve the same problem to -tol 1e-10, bound 1e-9 (measured: equal
    to all 16 digits). A copy of the file without its setVolumetricModulus call is refused: exit 2,
    one error line naming setVolumetricModulus."""
    doc = open(os.path.join(ROOT, "docs", "adding_a_law.md")).read()
    m = re.search(r"<!-- law file: (\S+) -->\n```freefem\n(.*?)```", doc, re.S)
    check("law recipe: docs/adding_a_law.md holds the example law file", m is not None)
    if m is None:
        return
    work, include = suite_copy("law recipe yeoh")
    law_text = m.group(2)
    with open(os.path.join(work, m.group(1)), "w") as f:
        f.write(law_text)
    registry = os.path.join(include, "laws", "registry.idp")
    text = open(registry).read()
    with open(registry, "w") as f:
        f.write(text.replace(") // EOM", ") apply(yeoh) // EOM", 1))
    check("law recipe: yeoh registered", "yeoh" in registered_laws(include))
    code, output, _ = run_driver(os.path.join(ROOT, "tests", "fd_laws.edp"), [], None, cwd=work)
    lines = [l for l in output.splitlines() if l.startswith("fd_laws dim=") and "law=yeoh " in l]
    check("law recipe: the Yeoh law's P and A against finite differences in 2D and 3D (1e-8)",
          len(lines) == 2 and all(l.endswith("PASS") for l in lines) and code == 0, str(lines))
    driver = open(os.path.join(ROOT, "benchmarks", "oring.edp")).read()
    yeoh_driver = driver.replace('setMooneyRivlin("neohookean", C10, 0, nu);', "setYeoh(C10, 0, 0, nu);")
    check("law recipe: the O-ring driver's law line replaced", yeoh_driver != driver)
    with open(os.path.join(work, "oring_yeoh.edp"), "w") as f:
        f.write(yeoh_driver)
    common = ["-case", "plates", "-cmax", "0.2", "-steps", "5", "-tol", "1e-10"]
    for nu in ("0.4999", "0.5"):
        o_yeoh, o_nh = out(f"law recipe yeoh nu {nu}"), out(f"law recipe neohookean nu {nu}")
        code_y, _, _ = run_driver(os.path.join(work, "oring_yeoh.edp"), common + ["-nu", nu], o_yeoh, cwd=work)
        code_n, _, _ = run_driver("benchmarks/oring.edp", common + ["-nu", nu], o_nh)
        y, n = read_summary(o_yeoh), read_summary(o_nh)
        if code_y != 0 or code_n != 0 or y is None or n is None:
            check(f"law recipe nu={nu}: both runs complete", False, f"exit {code_y}, {code_n}")
            continue
        fy, fn = y["results"]["force_c0.2"]["computed"], n["results"]["force_c0.2"]["computed"]
        check(f"law recipe nu={nu}: Yeoh with C20 = C30 = 0 gives Neo-Hookean's plate force to 1e-9",
              abs(fy - fn) <= 1e-9 * fn, f"{fy:.16g} vs {fn:.16g}")
    forgetful = law_text.replace("  setVolumetricModulus((nu == 0.5 ? 0. : 2*C10/(1 - 2*nu)), nu);\n", "")
    check("law recipe: the copy without setVolumetricModulus differs", forgetful != law_text)
    with open(os.path.join(work, m.group(1)), "w") as f:
        f.write(forgetful)
    o = out("law recipe forgetful")
    code, output, _ = run_driver(os.path.join(work, "oring_yeoh.edp"), common, o, cwd=work)
    errors = [l for l in output.splitlines() if l.startswith("error:")]
    check("law recipe: a law without setVolumetricModulus is refused (exit 2, one line naming it, no summary)",
          code == 2 and len(errors) == 1 and "setVolumetricModulus" in errors[0] and not os.path.exists(os.path.join(o, "summary.json")),
          f"exit {code}: {errors}")


def test_linear_stiffness():
    """Linear elasticity's Hessian from its Lame form against the generic tangent assembly
    (stiffness_check.edp), P1 and P2 in 2D, P1 in 3D and axisymmetric, whole and as the lower
    triangle (plugin/fast_assembly.cpp on P1 tetrahedra, also with moduli varying per
    element against the varf), and a hyperelastic law's tangent and internal forces in plane
    strain from the plugin against their varfs: the same forms, so equal to rounding (1e-12)."""
    check_script_cases("stiffness_check", 9)


def registered_obstacles(include_dir=os.path.join(ROOT, "include")):
    """The obstacle kinds listed in include/contact/obstacles.idp (read here, independently of FreeFEM)."""
    text = open(os.path.join(include_dir, "contact", "obstacles.idp")).read()
    line = re.search(r"^macro registeredObstacles\(apply\)(.*)// EOM", text, re.M).group(1)
    return re.findall(r"apply\((\w+)\)", line)


def test_obstacle_derivatives():
    """Gradient and Hessian of every registered obstacle kind's g(x) against central differences,
    and of a disc and a shifted disc (fd_obstacles.edp, h = 1e-5: truncation ~1e-10, tolerance 1e-8).
    The expected cases come from the registry, so a new kind is checked without touching this file."""
    code, output, _ = run_driver("tests/fd_obstacles.edp", [], None)
    lines = [l for l in output.splitlines() if l.startswith("fd_obstacles obstacle=")]
    expected = len(registered_obstacles()) + 2
    check(f"fd_obstacles: {expected} obstacle checks ran", len(lines) == expected, f"{len(lines)} lines")
    for line in lines:
        check("fd_obstacles " + line.split()[1], line.endswith("PASS"), line)
    check("fd_obstacles exit code", code == 0, f"exit {code}")


# ---------------------------------------------------------------- cube
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
    (pressure x top area), the forces must balance and nothing may sink into the plane."""
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
            # every component of applied + contact + reactions sums to zero (a sum over a stepped
            # slice that dropped the last node's z made this 5e-3 in 3D while the contact force held)
            b = s["results"]["force_balance_rel_error"]["computed"]
            check(f"{label}: force balance <= 1e-8", b <= 1e-8, f"{b:.1e}")


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


def test_cube_homogeneous_default_form():
    """Issue 25: the default volumetric form on the compressed block, 1 % to 35 % compression, 2D, axisymmetric
    and 3D, Mooney-Rivlin and Neo-Hookean, nu 0.45 to 0.5, supported or on the rigid foundation, on the
    structured mesh and with its interior vertices moved at random by up to 0.3 of the spacing. Under
    the rigid platen (displacement control) the exact state is stable to Biot's limit and every run must
    land on it (35 % in 4 load steps: in one, IPOPT on the whole axisymmetric block on the foundation
    ended in another state, which the run reported with exit 4). Under the dead load (the preprint's loading) it is stable only to 20-26 % on these
    meshes (tests/stability_check.edp): up to 20 % every run must land on it; at 28 % the block
    buckles at its free top corner, and the run must say so (exit 4, the tangent's negative eigenvalue
    at the exact state) instead of reporting the buckled state against the exact one."""
    for dim in ("2", "axi"):
        for material in ("mooney", "neohookean"):
            for nu in ("0.45", "0.499", "0.4999", "0.5"):
                for foundation in ("0", "1"):
                    for perturb in ("0", "0.3"):
                        for c, steps in (("0.01", "1"), ("0.35", "4")):
                            homogeneous_case(f"cube {dim} {material} nu={nu} foundation={foundation} perturb={perturb} platen {c}",
                                             ["-dim", dim, "-material", material, "-nu", nu, "-foundation", foundation,
                                              "-perturb", perturb, "-load", "platen", "-compression", c, "-steps", steps])
                        homogeneous_case(f"cube {dim} {material} nu={nu} foundation={foundation} perturb=0.3 dead load 0.2",
                                         ["-dim", dim, "-material", material, "-nu", nu, "-foundation", foundation,
                                          "-perturb", "0.3", "-compression", "0.2"])
    for material in ("mooney", "neohookean"):
        for nu in ("0.4999", "0.5"):
            for perturb in ("0", "0.3"):
                for c, steps in (("0.01", "1"), ("0.35", "4")):
                    homogeneous_case(f"cube 3D {material} nu={nu} perturb={perturb} platen {c}",
                                     ["-dim", "3", "-n", "3", "-material", material, "-nu", nu, "-perturb", perturb,
                                      "-load", "platen", "-compression", c, "-steps", steps])
            homogeneous_case(f"cube 3D {material} nu={nu} perturb=0.3 dead load 0.2",
                             ["-dim", "3", "-n", "3", "-material", material, "-nu", nu, "-perturb", "0.3", "-compression", "0.2"])
    # past the dead-loaded block's instability: exit 4, one error line, the state named unstable
    for args in (["-pressure", "12"], ["-material", "neohookean", "-compression", "0.28"]):
        o = out(f"cube buckled {args}")
        code, output, _ = run_driver("benchmarks/cube.edp", args, o)
        s = read_summary(o)
        errors = [l for l in output.splitlines() if l.startswith("error:")]
        check(f"cube dead load {' '.join(args)}: exit 4, the homogeneous state named unstable (a negative eigenvalue there)",
              code == 4 and len(errors) == 1 and "unstable" in errors[0] and s is not None and s["complete"]
              and s["checks_failed"] == ["homogeneous_state"]
              and s["results"]["exact_state_negative_eigenvalues"]["computed"] >= 1, f"exit {code}: {errors}")


def test_indentation():
    """Issue 25, the 3D rubber contact benchmark (benchmarks/indentation.edp): a rigid sphere pressed
    0.2 R into a Neo-Hookean block (nu = 0.499) in 10 steps, axisymmetric and 3D. The axisymmetric
    model on its default mesh (h = R/40): at the first step's depth 0.02 R the force within 2 % of
    Hertz's (measured 0.77 %: finite strain and the block's size account for -0.4 % at that depth,
    the mesh for the rest; docs/rubber.md) and the contact radius within 2 % of (R delta)^(1/2)
    (measured 0.8 %); force balance 1e-8 of the force; no penetration at the nodes (1e-10 R); the
    bottom pushed everywhere (no check failed); the curve rising. The 3D quarter on two coarse meshes
    (h = R/8, R/16): converging to the axisymmetric model's force at 0.2 R at better than first order
    (the R/16 gap less than half the R/8 one; measured 4.9 % and 1.3 %, 0.38 % at R/32) and within 2 %
    at R/16."""
    axi = run_summary("indentation axisymmetric", "benchmarks/indentation.edp", [])
    if axi is None:
        return
    r = axi["results"]
    check("indentation axi: force at 0.02 R within 2 % of Hertz", r["force_small_depth"]["rel_error"] <= 0.02,
          f"{r['force_small_depth']['rel_error']:.2e}")
    check("indentation axi: contact radius at 0.02 R within 2 % of (R delta)^(1/2)",
          r["contact_radius_small_depth"]["rel_error"] <= 0.02, f"{r['contact_radius_small_depth']['rel_error']:.2e}")
    check("indentation axi: force balance <= 1e-8 of the force, no penetration at the nodes (1e-10 R)",
          r["force_balance_rel_error"]["computed"] <= 1e-8 and r["max_penetration"]["computed"] <= 1e-10,
          f"{r['force_balance_rel_error']['computed']:.1e}, {r['max_penetration']['computed']:.1e}")
    check("indentation axi: complete, no check failed, J > 0", axi["complete"] and axi["checks_failed"] == []
          and r["J_min"]["computed"] > 0, str(axi["checks_failed"]))
    with open(os.path.join(out("indentation axisymmetric"), "force_depth.csv")) as f:
        rows = list(csv.DictReader(f))
    forces = [float(row["force"]) for row in rows]
    check("indentation axi: force_depth.csv has the 10 steps, the force rising with the depth",
          len(rows) == 10 and all(b > a for a, b in zip(forces, forces[1:])), f"{len(rows)} rows")
    reference = r["force"]["computed"]
    gaps = {}
    for h in ("0.125", "0.0625"):
        s = run_summary(f"indentation 3D h={h}", "benchmarks/indentation.edp", ["-dim", "3", "-h", h])
        if s is None:
            return
        gaps[h] = abs(s["results"]["force"]["computed"] - reference) / reference
        check(f"indentation 3D h={h}: force balance <= 1e-8, no penetration, no check failed",
              s["results"]["force_balance_rel_error"]["computed"] <= 1e-8 and s["results"]["max_penetration"]["computed"] <= 1e-10
              and s["checks_failed"] == [])
    check("indentation 3D: converging to the axisymmetric force at 0.2 R (gap at R/16 < half the gap at R/8, and <= 2 %)",
          gaps["0.0625"] < 0.5 * gaps["0.125"] and gaps["0.0625"] <= 0.02, f"{gaps['0.125']:.2e} -> {gaps['0.0625']:.2e}")


def test_oring_plates_deep():
    """Issue 25: the O-ring plates pushed to c = 0.4 (20 steps): complete, balanced (1e-8), nothing
    penetrates, J > 0, the pressure field smooth (checkerboard index <= 0.05; 0.5 and more for a
    checkerboard), the forces at c = 0.1..0.3 those of the default run (15 steps to 0.3) to the
    solver's tolerance (1e-6), and the final state a stable equilibrium: no negative eigenvalue of the
    tangent with the plate's active nodes held normally (solve/stability.idp); the default run at
    c = 0.3 likewise."""
    deep = run_summary("oring plates c=0.4", "benchmarks/oring.edp", ["-case", "plates", "-cmax", "0.4", "-steps", "20"])
    base = run_summary("oring plates default for deep", "benchmarks/oring.edp", ["-case", "plates"])
    if not (deep and base):
        return
    r = deep["results"]
    check("oring plates c=0.4: complete, balance <= 1e-8, no penetration, J > 0, smooth pressure (index <= 0.05)",
          deep["complete"] and r["force_balance_rel_error"]["computed"] <= 1e-8 and r["max_penetration"]["computed"] <= 1e-10 * 0.52
          and r["J_min"]["computed"] > 0 and r["pressure_checkerboard_index"]["computed"] <= 0.05,
          f"checkerboard {r['pressure_checkerboard_index']['computed']:.3f}")
    for q in ("force_c0.1", "force_c0.2", "force_c0.3"):
        a, b = r[q]["computed"], base["results"][q]["computed"]
        check(f"oring plates c=0.4: {q} = the default run's to 1e-6", abs(a - b) <= 1e-6 * b, f"{a:.10g} vs {b:.10g}")
    for label, s in (("c=0.4", deep), ("c=0.3 (default)", base)):
        neg = s["results"]["tangent_negative_eigenvalues"]["computed"]
        check(f"oring plates {label}: a stable equilibrium (no negative eigenvalue, active nodes held)", neg == 0, f"{neg:g}")


def test_stability_check():
    """Issue 25, the stability check (tests/stability_check.edp): the default form's tangent at the exact
    homogeneous state has no negative eigenvalue under the platen at 0, 10, 28 and 35 % compression
    (2D, axisymmetric, 3D; both laws; nu 0.499, 0.4999, 0.5) nor under the dead load at 10 %; and the
    dead load's critical compression is the compressible block's (nu = 0.3, plain P1) to 1 % on
    n = 6, 12, 24, and falls with n: the block's own instability, not a mode of the form."""
    check_script_cases("stability_check", 95, prefix="stability_check ")


def test_output_contract():
    o = out("contract")
    # IPOPT on the whole problem (without contact rows the default is the condensed Newton, no IPOPT)
    code, _, _ = run_driver("benchmarks/cube.edp", ["-n", "2", "-condense", "no"], o)
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
    # its values (written from the arrays by plugin/vtu_writer.cpp, float32): the block's deformation
    # is homogeneous, so the largest |u_y| is the summary's w, J is J_min in every element and the
    # largest von Mises is the summary's, each to float32 rounding (6e-8; bound 1e-6)
    if text:
        from vtu import read_vtu
        import numpy as np
        points, cells, types, pdata, cdata = read_vtu(vtu)
        r = s.get("results", {})
        dim = 3 if s.get("parameters", {}).get("dim") == 3 else 2
        w = r.get("w", {}).get("computed", float("nan"))
        check("cube.vtu: one displacement per vertex", len(points) == s.get("ndof", 0) // dim, f"{len(points)} points")
        check("cube.vtu: largest |u_y| = w to 1e-6", abs(np.abs(pdata["displacement"][:, 1]).max() - w) <= 1e-6 * w,
              f"{np.abs(pdata['displacement'][:, 1]).max():.9g} vs {w:.9g}")
        jmin = r.get("J_min", {}).get("computed", float("nan"))
        check("cube.vtu: J = J_min in every element to 1e-6", np.abs(cdata["J"] - jmin).max() <= 1e-6, f"{np.abs(cdata['J'] - jmin).max():.1e}")
        vm = r.get("von_mises_max", {}).get("computed", float("nan"))
        check("cube.vtu: largest von Mises = the summary's to 1e-6", abs(cdata["von_Mises"].max() - vm) <= 1e-6 * vm,
              f"{cdata['von_Mises'].max():.9g} vs {vm:.9g}")
    logs = [f for f in os.listdir(o) if f.startswith("ipopt_step")] if os.path.isdir(o) else []
    check("IPOPT log is in the output folder", len(logs) == 1, str(logs))


def test_working_folder_untouched():
    """ff-Ipopt writes ipopt.out and reads ipopt.opt in the working folder: a hostile
    ipopt.opt (max_iter 0) must be ignored and nothing written next to it."""
    work = out("workdir")
    os.makedirs(work)
    with open(os.path.join(work, "freefem++.pref"), "w") as f:
        f.write('loadpath += "/usr/lib/freefem++"\nloadpath += "%s/plugin"\nincludepath += "%s/include"\nverbosity = 0\n'
                % (ROOT, ROOT))
    with open(os.path.join(work, "ipopt.opt"), "w") as f:
        f.write("max_iter 0\n")
    before = set(os.listdir(work))
    code, output, _ = run_driver(os.path.join(ROOT, "benchmarks/cube.edp"), ["-n", "2"], os.path.join(work, "o"), cwd=work)
    after = set(os.listdir(work)) - {"o"}
    check("ipopt.opt in the working folder is not read", code == 0, output.strip().splitlines()[-1:])
    check("no stray files in the working folder", after == before, str(after - before))


# ---------------------------------------------------------------- Hertz
def hertz_case(label, script, args, bound_a=verdicts.bound("hertz_plane", "a"),
               bound_l2=verdicts.bound("hertz_plane", "pressure_l2_rel_error"), size=lambda p: p["R"]):
    """Runs a Hertz driver; a and p_max (fit of p^2 against x^2, README) within bound_a of
    Hertz's formulas (measured 3e-4 .. 1.6e-3 over the cases below: the finite disc, its far
    field at hmax = R/20 and h = a/30, README), L2 of p within bound_l2 (edge of contact: ~0.2 % .. 0.7 % at h = a/30),
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


def test_condensed_path():
    """The condensed solve (include/solve/condensed_solve.idp) against the full KKT path on the same
    problems: the interior dofs are eliminated exactly, so both paths find the same minimiser up to
    IPOPT's tolerance (1e-8 on the scaled KKT error): a, p_max and the contact force to 1e-6 relative,
    the L2 error of p (relative to p_max) to 1e-6 absolute (measured: at most 9e-9 and 2e-8); each
    path's own force balance to 1e-8 and no penetration (hertz_case's checks)."""
    cases = [("hertz plane", "benchmarks/hertz_plane.edp", [], "hertz_plane"),
             ("hertz plane 3 steps", "benchmarks/hertz_plane.edp", ["-steps", "3"], "hertz_plane"),
             ("hertz circle linearized", "benchmarks/hertz_circle.edp", ["-constraint", "linearized"], "hertz_circle_exact"),
             # the exact form (42) on the cylinder: curved rows, linearised at every SQP iterate
             ("hertz circle exact", "benchmarks/hertz_circle.edp", ["-constraint", "exact"], "hertz_circle_exact"),
             ("hertz sphere 3D", "benchmarks/hertz_sphere.edp", ["-h", "0.0125"], "hertz_sphere"),
             ("two cylinders", "benchmarks/hertz_two_cylinders.edp", [], None)]
    for label, script, args, verdict in cases:
        runs = {}
        for choice in ("yes", "no"):
            name = f"condensed path {label} -condense {choice}"
            if verdict:
                runs[choice] = hertz_case(name, script, args + ["-condense", choice],
                                          bound_a=verdicts.bound(verdict, "a"), bound_l2=None)
            else:
                runs[choice] = run_summary(name, script, args + ["-condense", choice])
        condensed, full = runs["yes"], runs["no"]
        if not (condensed and full):
            continue
        check(f"condensed path {label}: condensed onto the contact dofs only",
              0 < condensed["results"]["condensed_dofs"]["computed"] < condensed["ndof"] / 5
              and "condensed_dofs" not in full["results"],
              f"{condensed['results']['condensed_dofs']['computed']:.0f} of {condensed['ndof']}")
        for q in ("a", "p_max", "contact_force"):
            c, f = condensed["results"][q]["computed"], full["results"][q]["computed"]
            check(f"condensed path {label}: {q} = the full path's to 1e-6", abs(c - f) <= 1e-6 * abs(f), f"{c:.10g} vs {f:.10g}")
        c, f = condensed["results"]["pressure_l2_rel_error"]["computed"], full["results"]["pressure_l2_rel_error"]["computed"]
        check(f"condensed path {label}: L2 error of p = the full path's to 1e-6", abs(c - f) <= 1e-6, f"{c:.8e} vs {f:.8e}")
    # hyperelastic: the condensed SQP (a tangent condensed per iteration) against IPOPT on the full
    # problem. Neo-Hookean Hertz at the driver's tolerance 1e-8: 1e-6 as above (measured 3e-7 at a/40).
    # The O-ring plates (15 displacement-controlled steps, nodal volumetric form) at -tol 1e-10 in both
    # paths: the plate forces to 1e-9 (measured 2e-13; at the driver's 1e-7 the full path's barrier
    # leaves 9e-7 at c = 0.3)
    nh = {c: hertz_case(f"condensed path hertz Neo-Hookean -condense {c}", "benchmarks/hertz_plane.edp",
                        ["-material", "neohookean", "-condense", c], bound_a=verdicts.bound("hertz_plane_neohookean", "a"),
                        bound_l2=None) for c in ("auto", "no")}
    if all(nh.values()):
        for q in ("a", "p_max", "contact_force"):
            c, f = nh["auto"]["results"][q]["computed"], nh["no"]["results"][q]["computed"]
            check(f"condensed path hertz Neo-Hookean: {q} = the full path's to 1e-6", abs(c - f) <= 1e-6 * abs(f), f"{c:.10g} vs {f:.10g}")
        c, f = nh["auto"]["results"]["pressure_l2_rel_error"]["computed"], nh["no"]["results"]["pressure_l2_rel_error"]["computed"]
        check("condensed path hertz Neo-Hookean: L2 error of p = the full path's to 1e-6", abs(c - f) <= 1e-6, f"{c:.8e} vs {f:.8e}")
    oring = {c: run_summary(f"condensed path O-ring plates -tol 1e-10 -condense {c}", "benchmarks/oring.edp",
                            ["-case", "plates", "-tol", "1e-10", "-condense", c]) for c in ("auto", "no")}
    if all(oring.values()):
        check("condensed path O-ring plates: the condensed SQP ran (condensed dofs reported)",
              "condensed_dofs" in oring["auto"]["results"] and "condensed_dofs" not in oring["no"]["results"])
        same_plate_forces("condensed path O-ring plates", oring["auto"], oring["no"])
    # R/36: the compressed ring's tangent turns indefinite from c = 0.22 on; the SQP shifts it on its
    # diagonal and must finish every step itself (no hand-over to the whole problem) at the full
    # path's forces to 1e-9 (measured: 3e-11; both at -tol 1e-10)
    h36 = repr(0.52 / 36)
    o = out("condensed path O-ring plates R/36 -tol 1e-10 -condense auto")
    code, output, _ = run_driver("benchmarks/oring.edp", ["-case", "plates", "-h", h36, "-tol", "1e-10"], o)
    shifted = read_summary(o) if code == 0 else None
    check("condensed path O-ring plates R/36: the SQP shifted an indefinite tangent, and no step fell back",
          shifted is not None and "indefinite tangent: shifted" in output and "condensed SQP stopped" not in output,
          f"exit {code}; {[l for l in output.splitlines() if 'shifted' in l or 'stopped' in l][:3]}")
    full = run_summary("condensed path O-ring plates R/36 -tol 1e-10 -condense no", "benchmarks/oring.edp",
                       ["-case", "plates", "-h", h36, "-tol", "1e-10", "-condense", "no"])
    if shifted and full:
        same_plate_forces("condensed path O-ring plates R/36", shifted, full)
    # without contact rows the SQP is Newton's method on the factorized tangent; in 3D with the nodal
    # form it factorizes the sparse saddle point matrix (body/volumetric.idp): the cube's w equals the
    # full path's and the exact solution to 1e-8 (the tests' bound for the cube), both laws
    for material in ("mooney", "neohookean"):
        cube = {c: run_summary(f"condensed path cube 3D {material} -condense {c}", "benchmarks/cube.edp",
                               ["-dim", "3", "-material", material, "-condense", c]) for c in ("yes", "no")}
        if all(cube.values()):
            c, f = cube["yes"]["results"]["w"], cube["no"]["results"]["w"]
            check(f"condensed path cube 3D {material}: the saddle point form was factorized",
                  cube["yes"]["results"].get("condensed_dofs", {}).get("computed") == 0
                  and "factor_entries_per_unknown" in cube["yes"]["results"] and "condensed_dofs" not in cube["no"]["results"])
            check(f"condensed path cube 3D {material}: w = the full path's and the exact one to 1e-8",
                  abs(c["computed"] - f["computed"]) <= 1e-8 * f["computed"] and c["rel_error"] <= 1e-8,
                  f"{c['computed']:.12g} vs {f['computed']:.12g}, exact {c['reference']:.12g}")
    # -condense yes where the condensation does not apply: known once the problem is set up, so the
    # driver's header line comes first; then one error line naming -condense, exit 2, no summary.json
    for script, args in (("benchmarks/hertz_two_cylinders.edp", ["-constraint", "updated"]),
                         ("benchmarks/hertz_plane.edp", ["-material", "neohookean", "-nu", "0.5"])):
        o = out(f"condensed path refused {script} {args}")
        code, output, _ = run_driver(script, args + ["-condense", "yes"], o)
        errors = [l for l in output.splitlines() if l.startswith("error:")]
        check(f"condensed path: -condense yes refused for {os.path.basename(script)} {' '.join(args)}",
              code == 2 and len(errors) == 1 and "-condense" in errors[0] and not os.path.exists(os.path.join(o, "summary.json")),
              f"exit {code}: {errors}")
    clamped = {c: run_summary(f"condensed path clamped square -condense {c}", "benchmarks/clamped_square.edp", ["-condense", c])
               for c in ("yes", "no")}
    if all(clamped.values()):
        pressures = [k for k in clamped["no"]["results"] if k.startswith("pressure_at_") or k == "pressure_max"]
        worst = max(abs(clamped["yes"]["results"][k]["computed"] - clamped["no"]["results"][k]["computed"])
                    / abs(clamped["no"]["results"]["pressure_max"]["computed"]) for k in pressures)
        check("condensed path clamped square (P2): wall pressures = the full path's to 1e-6 of the peak",
              pressures and worst <= 1e-6, f"{len(pressures)} values, worst {worst:.1e}")


def read_pressure_csv(label):
    path = os.path.join(out(label), "pressure.csv")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows


def test_hertz_plane():
    s = hertz_case("hertz plane", "benchmarks/hertz_plane.edp", [])
    rows = read_pressure_csv("hertz plane") or []
    columns = ["s", "x_ref", "y_ref", "x_def", "y_def", "gap", "active", "pressure", "reference_pressure"]
    check("hertz plane: pressure.csv has the documented columns, one row per candidate node",
          s is not None and len(rows) == s["results"]["active_nodes"]["computed"] + sum(r["active"] == "0" for r in rows)
          and list(rows[0].keys() if rows else []) == columns, str(list(rows[0].keys()) if rows else []))
    xs = [float(r["s"]) for r in rows]
    check("hertz plane: pressure.csv sorted by s = x", xs == sorted(xs) and all(float(r["s"]) == float(r["x_ref"]) for r in rows))
    moved = [abs(float(r["y_def"]) - float(r["y_ref"])) for r in rows]
    check("hertz plane: pressure.csv's deformed positions differ from the reference ones (the disc moves down)",
          rows and max(moved) > 0, f"{max(moved, default=0):.2e}")
    tensile = min((float(r["pressure"]) for r in rows), default=0)
    pmax = s["results"]["p_max"]["reference"] if s else 1
    check("hertz plane: no tensile contact pressure (beyond 1e-6 p_max)", tensile >= -1e-6 * pmax, f"{tensile:.2e}")
    vtu = os.path.join(out("hertz plane"), "hertz_plane.vtu")
    check("hertz plane: hertz_plane.vtu written", os.path.exists(vtu) and os.path.getsize(vtu) > 0)
    hertz_case("hertz plane E=7e10 nu=0.2 p=3e7 R=0.5", "benchmarks/hertz_plane.edp",
               ["-E", "7e10", "-nu", "0.2", "-pressure", "3e7", "-R", "0.5"])


def test_hertz_circle():
    """The vertical-gap form is Hertz's own contact condition: it must meet the same bounds
    as the plane. (42) and (43) keep the term -psi'(X1) u1 that Hertz neglects: it moves a
    and p_max by ~0.4 % at nu = 0.3, R2 = 1.2 (measured; it scales with (1 - 2 nu) and
    1 / R2), so they are held to the issue's 1 %."""
    hertz_case("hertz circle vertical gap", "benchmarks/hertz_circle.edp", ["-constraint", "vertical"])
    hertz_case("hertz circle vertical gap E=1e6 nu=0.25 p=1000 R2=2", "benchmarks/hertz_circle.edp",
               ["-constraint", "vertical", "-E", "1e6", "-nu", "0.25", "-pressure", "1000", "-R2", "2"])
    runs = {}
    for form in ("exact", "linearized"):
        for spline in ("1", "0"):
            label = f"hertz circle {form} spline={spline}"
            runs[(form, spline)] = hertz_case(label, "benchmarks/hertz_circle.edp", ["-constraint", form, "-spline", spline],
                                              bound_a=verdicts.bound("hertz_circle_exact", "a"), bound_l2=None)
    if all(runs.values()):
        a = {k: v["results"]["a"]["computed"] for k, v in runs.items()}
        d = abs(a[("exact", "1")] - a[("linearized", "1")]) / a[("exact", "1")]
        check("hertz circle: (42) and (43) agree to 1e-4 (they differ at second order in psi' u1; measured 6e-6)",
              d <= 1e-4, f"{d:.1e}")
        d = abs(a[("exact", "1")] - a[("exact", "0")]) / a[("exact", "0")]
        check("hertz circle: spline obstacle = analytic arc to 1e-5 (101 knots: curvature error ~2e-5)", d <= 1e-5, f"{d:.1e}")
    hertz_case("hertz circle exact E=1e6 nu=0.25 p=1000 R2=2", "benchmarks/hertz_circle.edp",
               ["-E", "1e6", "-nu", "0.25", "-pressure", "1000", "-R2", "2"],
               bound_a=verdicts.bound("hertz_circle_exact", "a"), bound_l2=None)


def test_hertz_hyperelastic():
    """Hyperelastic laws with the small-strain moduli of (E, nu) tend to linear elasticity
    as the strain vanishes: at 1/100 of the preprint's load (contact strain p_max / E ~ 3e-3)
    Neo-Hookean and Mooney-Rivlin give the linear a and p_max on the same mesh to 1e-3
    (measured 5e-4: the finite-strain effect, O(strain))."""
    lin = hertz_case("hertz plane linear, load / 100", "benchmarks/hertz_plane.edp", ["-pressure", "2.75e4"])
    for material in ("neohookean", "mooney"):
        s = hertz_case(f"hertz plane {material}, load / 100", "benchmarks/hertz_plane.edp",
                       ["-pressure", "2.75e4", "-material", material], bound_a=None, bound_l2=None)
        if s and lin:
            for q in ("a", "p_max"):
                c, ref = s["results"][q]["computed"], lin["results"][q]["computed"]
                check(f"hertz plane {material}: {q} = linear elasticity's to 1e-3", abs(c - ref) / ref <= 1e-3,
                      f"{c:.6g} vs {ref:.6g}")


# ---------------------------------------------------------------- clamped square, sphere
def test_clamped_square():
    """No analytic solution: the default run (P2, n = 25) against benchmarks/reference/clamped_square.json
    (P2 n = 25..200, Richardson; scripts/clamped_square_reference.py). Each bound is about 1.5x
    the measured error of n = 25 against the reference: contact force 6.5e-4, pressure at
    y = 0.8, 0.9, 0.95 up to 1.6e-3, centre of pressure 9e-5 (absolute); the separation point
    is located to half a node spacing (0.01). p(0.7) is left out: it lies within one element of
    the separation point (n = 25 is 9 % off there). Force balance and weight are exact to the
    solver tolerance."""
    with open(os.path.join(ROOT, "benchmarks", "reference", "clamped_square.json")) as f:
        ref = json.load(f)["reference"]
    s = run_summary("clamped square", "benchmarks/clamped_square.edp", [])
    if s is None:
        return
    r = s["results"]
    quantities = ["contact_force", "clamp_reaction_x", "pressure_at_y0.8", "pressure_at_y0.9", "pressure_at_y0.95",
                  "centre_of_pressure_y", "separation_y"]
    for q in quantities:
        kind, bound = verdicts.check("clamped_square", q).measure, verdicts.bound("clamped_square", q)
        c, v = r[q]["computed"], ref[q]["value"]
        err = abs(c - v) / (abs(v) if kind == "rel" else 1)
        check(f"clamped square: {q} = reference to {bound:g} ({kind})", err <= bound, f"{c:.7g} vs {v:.7g}: {err:.1e}")
    check("clamped square: the upper part presses, the lower part lifts off (p(0.6) = 0 < p(0.8) < p(0.95))",
          abs(r["pressure_at_y0.6"]["computed"]) < 1e-6 * r["pressure_at_y0.95"]["computed"]
          and 0 < r["pressure_at_y0.8"]["computed"] < r["pressure_at_y0.95"]["computed"])
    w = r["weight_carried"]
    check("clamped square: clamp + contact carry the weight 76518 N/m to 1e-8", w["rel_error"] <= 1e-8, f"{w['rel_error']:.1e}")
    fb = r["force_balance_rel_error"]["computed"]
    check("clamped square: force balance <= 1e-8 of the weight", fb <= 1e-8, f"{fb:.1e}")
    pen = r["max_penetration"]["computed"]
    check("clamped square: penetration < 1e-10 m", pen < 1e-10, f"{pen:.1e}")
    check("clamped square: IPOPT status", s["ipopt_status"] == "Solve_Succeeded", s["ipopt_status"])


def test_hertz_sphere():
    """3D: a hemisphere on the plane, coarse mesh (h = a/8, ~5k dofs): a and p_max within 3 %
    of Hertz (measured 1.3 % and 0.9 %; 0.45 % / 0.08 % at h = a/16)."""
    hertz_case("hertz sphere", "benchmarks/hertz_sphere.edp", [], bound_a=verdicts.bound("hertz_sphere", "a"), bound_l2=None)


# ---------------------------------------------------------------- O-ring
def test_oring_groove():
    """The ring squeezed into the closing groove (4 load steps). The problem and the mesh are
    symmetric about y = x, so opposite faces balance and floor = wall to the solver tolerance
    (measured 1e-11 .. 1e-16; bound 1e-8), the symmetry tie carries no force, nothing
    penetrates, and no element inverts."""
    o = out("oring groove")
    s = run_summary("oring groove", "benchmarks/oring.edp", ["-case", "groove", "-steps", "4"])
    if s is None:
        return
    r = s["results"]
    check("oring groove: IPOPT converged every step", s["ipopt_status"] == "Solve_Succeeded" and s["complete"], s["ipopt_status"])
    for q in ("floor_ceiling_balance_rel_error", "walls_balance_rel_error", "floor_wall_symmetry_rel_error",
              "force_balance_rel_error"):
        v = r[q]["computed"]
        check(f"oring groove: {q} <= 1e-8", v <= 1e-8, f"{v:.1e}")
    tie = r["tie_force"]["computed"] / r["floor_force"]["computed"]
    check("oring groove: the symmetry tie carries <= 1e-8 of the face force", tie <= 1e-8, f"{tie:.1e}")
    check("oring groove: the ring is squeezed (face force > 0, contact width > 0)",
          r["floor_force"]["computed"] > 0 and r["floor_contact_width"]["computed"] > 0)
    pen = r["max_penetration"]["computed"]
    check("oring groove: penetration <= 1e-10 R", pen <= 1e-10 * 0.52, f"{pen:.1e}")
    check("oring groove: J > 0 everywhere", r["J_min"]["computed"] > 0, f"{r['J_min']['computed']:.4f}")
    check("oring groove: one face-force row per step in face_forces.csv",
          os.path.exists(os.path.join(o, "face_forces.csv")) and len(open(os.path.join(o, "face_forces.csv")).readlines()) == 5)


def test_oring_plates():
    """Plates, quarter model, c up to 0.3, with the default nodal volumetric treatment. Lindley's
    law is empirical, so the reference is our own mesh study: computed / Lindley at c = 0.2 is
    1.3147, 1.3135, 1.3130, 1.3129 for h = R/12, R/24, R/48, R/96 (the penalty form: 1.417, 1.344,
    1.323, locking). The default h = R/24 must be within 1 % of the converged 1.3128 (README)."""
    o = out("oring plates")
    s = run_summary("oring plates", "benchmarks/oring.edp", ["-case", "plates"])
    if s is None:
        return
    r = s["results"]
    check("oring plates: IPOPT converged every step", s["ipopt_status"] == "Solve_Succeeded" and s["complete"], s["ipopt_status"])
    ratio = r["force_c0.2"]["computed"] / r["force_c0.2"]["reference"]
    low, high = verdicts.check("oring_plates", "force_c0.2").low, verdicts.bound("oring_plates", "force_c0.2")
    check(f"oring plates: force / Lindley at c = 0.2 in [{low}, {high}]", low <= ratio <= high, f"{ratio:.4f}")
    fb = r["force_balance_rel_error"]["computed"]
    check("oring plates: force balance <= 1e-8", fb <= 1e-8, f"{fb:.1e}")
    sym = abs(r["symmetry_reaction_y"]["computed"] - r["force_c0.3"]["computed"] / 2) / r["force_c0.3"]["computed"]
    check("oring plates: the symmetry plane y = 0 carries the plate force (half the ring's) to 1e-8", sym <= 1e-8, f"{sym:.1e}")
    pen = r["max_penetration"]["computed"]
    check("oring plates: penetration <= 1e-10 R", pen <= 1e-10 * 0.52, f"{pen:.1e}")
    rows = open(os.path.join(o, "force_squeeze.csv")).read().splitlines() if os.path.exists(os.path.join(o, "force_squeeze.csv")) else []
    forces = [float(l.split(",")[1]) for l in rows[1:]]
    check("oring plates: force_squeeze.csv has 15 rows, force increasing with c",
          len(forces) == 15 and all(b > a for a, b in zip(forces, forces[1:])), f"{len(forces)} rows")


# ---------------------------------------------------------------- report
def png_size(path):
    """(width, height) of a PNG file, or None when it is not one."""
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


def test_report():
    """The report step on a small set of results: every figure those results allow exists and
    is a real PNG of a sensible size, the others are skipped, and the table lists every
    benchmark (the ones that did not run as missing)."""
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    from benchmark_list import BENCHMARKS
    results = out("report results")
    small = {"hertz_plane": ("benchmarks/hertz_plane.edp", []),
             "clamped_square": ("benchmarks/clamped_square.edp", ["-n", "10"]),
             "oring_plates": ("benchmarks/oring.edp", ["-case", "plates", "-steps", "3", "-h", "0.065"]),
             "cube_2d_neohookean": ("benchmarks/cube.edp", ["-material", "neohookean", "-n", "3"])}
    for name, (script, args) in small.items():
        run_driver(script, args, os.path.join(results, name))
    for level in (10, 20):
        run_driver("benchmarks/hertz_plane.edp", ["-h", repr(0.0550867877 / level)],
                   os.path.join(results, "convergence", f"plane_a{level}"))
    # the Makefile's interpreter: Debian's, where the deps script installs matplotlib
    python = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
    proc = subprocess.run([python, os.path.join(ROOT, "scripts", "report.py"), "--results", results],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    check("report: report.py exits 0", proc.returncode == 0, proc.stdout.strip().splitlines()[-1:])
    expected = ["hertz_plane_pressure.png", "hertz_plane_deformed.png", "clamped_square_pressure.png",
                "clamped_square_deformed.png", "oring_plates_force.png", "oring_plates_deformed.png", "cube_deformed.png",
                "convergence_hertz.png", "convergence_clamped.png", "iterations_vs_dofs.png"]
    for f in expected:
        path = os.path.join(results, "figures", f)
        size = png_size(path) if os.path.exists(path) else None
        check(f"report: {f} is a PNG of at least 400 x 300 pixels", size is not None and size[0] >= 400 and size[1] >= 300, str(size))
    absent = [f for f in ("hertz_circle_pressure.png", "hertz_sphere_pressure.png", "oring_groove_forces.png")
              if os.path.exists(os.path.join(results, "figures", f))]
    check("report: no figure is drawn for benchmarks that did not run", not absent, str(absent))
    md = open(os.path.join(results, "REPORT.md")).read() if os.path.exists(os.path.join(results, "REPORT.md")) else ""
    rows = [l for l in md.splitlines() if l.startswith("| ")]
    listed = {l.split("|")[1].strip() for l in rows}
    check("report: the table lists every benchmark", all(n in listed for n, _, _ in BENCHMARKS),
          str(sorted({n for n, _, _ in BENCHMARKS} - listed)))
    check("report: benchmarks that did not run are marked missing",
          any(l.startswith("| hertz_sphere |") and "missing" in l for l in rows))
    check("report: the clamped square is compared with its stored reference",
          any(l.startswith("| clamped_square | contact_force |") and l.split("|")[4].strip() != "-" for l in rows))
    # the verdicts: each checked row shows its reference kind, the tests' bound and PASS/FAIL
    cells = {(c[1], c[2]): c[3:] for c in ([x.strip() for x in l.split("|")] for l in rows) if len(c) >= 9}
    first_line = next((l for l in md.splitlines() if "PASS" in l and "FAIL" in l), "")
    check("report: it opens with the count of PASS and FAIL", md.index(first_line) < md.index("| benchmark") if first_line else False,
          first_line)
    for (bench, quantity) in (("hertz_plane", "a"), ("hertz_plane", "force_balance_rel_error"), ("cube_2d_neohookean", "w"),
                              ("oring_plates", "force_c0.2")):
        c = verdicts.check(bench, quantity)
        row = cells.get((bench, quantity))
        summary = read_summary(os.path.join(results, bench))
        expected_verdict = verdicts.verdict(bench, quantity, summary["results"][quantity])[3] if summary else None
        check(f"report: {bench} {quantity} has kind {c.kind}, the tests' bound and its verdict",
              row is not None and row[2] == c.kind and (f"{c.bound:.1e}" in row[3] or f"{c.bound:g}" in row[3])
              and row[5] == expected_verdict, str(row))
    check("report: informational quantities are listed apart, without a verdict",
          "## Informational quantities" in md and any(l.startswith("| hertz_plane | last_active_node_x |") and "PASS" not in l
                                                      for l in md.split("## Informational quantities")[1].splitlines()))
    check("report: each benchmark section says what it shows", md.count("## ") >= 8
          and "homogeneously" in md and "Lindley" in md)
    html_path = os.path.join(results, "report.html")
    check("report: report.html embeds its figures", os.path.exists(html_path)
          and open(html_path).read().count("data:image/png;base64,") == len(expected))


# ---------------------------------------------------------------- robustness
def test_hard_cases():
    """Cases where solvers fail, which must converge: large-strain Neo-Hookean Hertz (10x and
    50x the load), nearly incompressible (nu = 0.499), the disc starting 0.05 R above the
    plane, the Mooney cube on its foundation at 5x the pressure, the O-ring groove closed in
    2 steps. Each must succeed with force balance <= 1e-8 and no penetration; where an exact
    answer exists (linear Hertz with a gap: rigid motion changes nothing; the cube) it is met."""
    plane = "benchmarks/hertz_plane.edp"
    for label, args in (("Neo-Hookean Hertz at 10x the load", ["-material", "neohookean", "-pressure", "2.75e7"]),
                        ("Neo-Hookean Hertz at 50x the load", ["-material", "neohookean", "-pressure", "1.375e8"]),
                        ("Neo-Hookean Hertz with nu = 0.499", ["-material", "neohookean", "-nu", "0.499"]),
                        ("Neo-Hookean Hertz starting 0.05 R above the plane", ["-material", "neohookean", "-gap", "0.05"])):
        hertz_case(label, plane, args, bound_a=None, bound_l2=None)
    hertz_case("linear Hertz starting 0.05 R above the plane", plane, ["-gap", "0.05"])
    for dim in ("2", "3"):
        s = cube_case(f"Mooney cube {dim}D on its foundation at 5x the pressure",
                      ["-material", "mooney", "-foundation", "1", "-pressure", "4.38", "-dim", dim, "-n", "3"])
        if s:
            p = s["results"]["max_penetration"]["computed"]
            check(f"Mooney cube {dim}D at 5x: no penetration", p <= 1e-10, f"{p:.1e}")
    s = run_summary("O-ring groove closed in 2 steps", "benchmarks/oring.edp", ["-case", "groove", "-steps", "2"])
    if s:
        r = s["results"]
        check("O-ring groove in 2 steps: converged, opposite faces balance to 1e-8",
              s["complete"] and r["floor_ceiling_balance_rel_error"]["computed"] <= 1e-8
              and r["walls_balance_rel_error"]["computed"] <= 1e-8, f"{r['floor_ceiling_balance_rel_error']['computed']:.1e}")


def test_step_cutting():
    """A load step that fails is halved and retried from the last converged state: closing
    the O-ring groove in one step with the penalty form takes 11 IPOPT iterations, so with at most
    8 per step the increment must be cut (5 times, measured) and the run still completes. (The
    nodal form needs more than 8 iterations at the first contact whatever the increment.)"""
    o = out("step cutting")
    code, output, _ = run_driver("benchmarks/oring.edp", ["-case", "groove", "-steps", "1", "-maxiter", "8",
                                                          "-volumetric", "penalty"], o)
    s = read_summary(o)
    cuts = [l for l in output.splitlines() if "cutting the load increment" in l]
    check("step cutting: the run completes", code == 0 and s is not None and s["complete"], f"exit {code}")
    check("step cutting: at least one cut, printed and counted", len(cuts) >= 1 and s is not None and s["step_cuts"] == len(cuts),
          f"{len(cuts)} printed, {s and s['step_cuts']} counted")


def test_bench_smoke():
    """`make bench` at its smallest level of each study (no timing is asserted: the numbers
    are the benchmark's record): it runs, writes performance.json with every study, and the
    contact solve, Newton and the sphere give their answers."""
    proc = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "performance", "studies.py"), "--smoke", "--out", out("bench")],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    path = os.path.join(out("bench"), "performance.json")
    data = json.load(open(path)) if os.path.exists(path) else {}
    check("bench smoke: exits 0 with the seven studies in performance.json", proc.returncode == 0 and data.get("smoke")
          and data["hertz_plane"] and data["cube_ipopt_vs_newton"] and data["hertz_neohookean_ipopt_vs_newton"]
          and data["hertz_sphere"] and data.get("volumetric") and data.get("two_bodies")
          and data.get("rubber_3d_fill") and data.get("rubber_3d_indentation"), proc.stdout.strip().splitlines()[-1:])
    if data.get("rubber_3d_fill"):
        f = data["rubber_3d_fill"][0]
        check("bench smoke: the 3D block's saddle point factors and the penalty form's both give the exact w (1e-8)",
              f["penalty_w_error"] <= 1e-8 and f["nodal_w_error"] <= 1e-8, f"{f['penalty_w_error']:.1e}, {f['nodal_w_error']:.1e}")
    if data.get("cube_ipopt_vs_newton"):
        c = data["cube_ipopt_vs_newton"][0]
        check("bench smoke: IPOPT and Newton both give the exact cube (w to 1e-8)",
              c["ipopt_w_error"] <= 1e-8 and c["newton_w_error"] <= 1e-8, f"{c['ipopt_w_error']:.1e}, {c['newton_w_error']:.1e}")


def test_known_contact_newton():
    """Neo-Hookean Hertz: plain Newton given the contact set IPOPT found (u2 on the plane at
    the active nodes, u1 free) must land on IPOPT's solution. Both stop at a relative residual
    of 1e-8 (-tol); measured difference 6.4e-8 of max |U| (1.5e-10 with linear elasticity),
    bound 1e-6. A wrong active set or a wrong multiplier sign would move U by ~1e-3."""
    s = run_summary("known-contact Newton", "benchmarks/hertz_plane.edp", ["-material", "neohookean", "-newton", "1"])
    if s:
        r = s["results"]
        check("known-contact Newton: |U_Newton - U_IPOPT| / |U| <= 1e-6",
              r["newton_vs_ipopt_rel_difference"]["computed"] <= 1e-6, f"{r['newton_vs_ipopt_rel_difference']['computed']:.1e}")
        check("known-contact Newton converged in <= 10 iterations", 0 < r["newton_iterations"]["computed"] <= 10,
              r["newton_iterations"]["computed"])
    # linear elasticity: the condensed solve holds the Hessian's lower triangle, Newton needs it whole
    # (the run once stopped on FreeFEM's assertion when one matrix was made to hold both); at -tol
    # 1e-12 both land on the same U to 1e-10 (measured 4.7e-12)
    s = run_summary("known-contact Newton, linear elasticity", "benchmarks/hertz_plane.edp", ["-newton", "1"])
    if s:
        d = s["results"]["newton_vs_ipopt_rel_difference"]["computed"]
        check("known-contact Newton, linear elasticity: |U_Newton - U_IPOPT| / |U| <= 1e-10", d <= 1e-10, f"{d:.1e}")


def test_sweep_smoke():
    """`make sweep` at its smallest: 6 random cases (one per kind: Hertz, cube, O-ring, axisymmetric
    sphere, two cylinders, a hostile value), every check met."""
    proc = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "sweep.py"), "--n", "6", "--seed", "7",
                           "--out", out("sweep")], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    summary_line = [l for l in proc.stdout.splitlines() if l.startswith("sweep:")]
    check("sweep smoke: 6 cases, no failed run, no violated check",
          proc.returncode == 0 and summary_line and "0 failed runs, 0 check violations" in summary_line[0], str(summary_line))


# ---------------------------------------------------------------- bad input
def test_bad_input():
    """Every case of tests/bad_inputs.py (all drivers; the README's table): one line starting
    with `error:` that names the problem, exit code 2, and no summary.json left behind."""
    import bad_inputs
    tmp = out("bad input files")
    os.makedirs(tmp)
    bad_inputs.make_files(tmp)
    for i, (driver, args, word) in enumerate(bad_inputs.CASES):
        label = f"{os.path.basename(driver)} {' '.join(args).replace('{tmp}/', '')}"
        code, first, left = bad_inputs.run_case(driver, args, tmp, out(f"bad {i}"))
        check(f"bad input {label}: exit code 2", code == 2, f"exit {code}")
        check(f"bad input {label}: one-line error naming '{word}'", first.startswith("error:") and word in first, first)
        check(f"bad input {label}: no summary.json", not left)
    check("bad input: every driver is covered", {d for d, _, _ in bad_inputs.CASES} >=
          {os.path.join("benchmarks", f) for f in os.listdir(os.path.join(ROOT, "benchmarks")) if f.endswith(".edp")})
    blank = os.path.join(TMP, "a b")
    code, first, left = bad_inputs.run_case("benchmarks/cube.edp", [], tmp, blank)
    check("bad input: an output folder with a blank is refused", code == 2 and "-out" in first, first)


def test_ipopt_failure_is_reported():
    """An IPOPT status other than success: the load increment is halved and retried from
    the last converged state (6 times at most), then one line with the status name, a
    non-zero exit, and a summary.json marked incomplete with the status and the cuts."""
    o = out("maxiter")
    code, output, _ = run_driver("benchmarks/cube.edp", ["-maxiter", "1"], o)
    errors = [l for l in output.splitlines() if l.startswith("error:")]
    cuts = [l for l in output.splitlines() if "cutting the load increment" in l]
    check("IPOPT failure: exit code 3 (solver failure)", code == 3, f"exit {code}")
    check("IPOPT failure: one error line with the status name",
          len(errors) == 1 and "Maximum_Iterations_Exceeded" in errors[0], str(errors))
    check("IPOPT failure: 6 step cuts printed before giving up", len(cuts) == 6, f"{len(cuts)}")
    s = read_summary(o)
    check("IPOPT failure: summary.json records the status, 7 attempts of 1 iteration, load factor 0, incomplete",
          s is not None and s["ipopt_status"] == "Maximum_Iterations_Exceeded" and s["ipopt_iterations"] == 7
          and s["step_cuts"] == 6 and s["load_factor_reached"] == 0 and s["complete"] is False,
          str(s and (s["ipopt_status"], s["ipopt_iterations"], s["step_cuts"], s["complete"])))


# ---------------------------------------------------------------- usability (issue 14)
def headless_env():
    """The environment of a machine without a display."""
    return {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}


def test_headless():
    """The README's literal command, the graphical FreeFem++ without -nw, on a machine without a
    display: with its output to a file and to a pipe it must exit 0 with the whole output (it
    used to die with SIGPIPE, exit 141, when ffglut could not open a display)."""
    o = out("headless file")
    log = os.path.join(TMP, "headless.log")
    with open(log, "w") as f:
        code = subprocess.run(["FreeFem++", "benchmarks/hertz_plane.edp", "-out", o], cwd=ROOT, env=headless_env(),
                              stdout=f, stderr=subprocess.STDOUT).returncode
    text = open(log).read()
    s = read_summary(o)
    check("headless, output to a file: exit 0", code == 0, f"exit {code}")
    check("headless, output to a file: the results are in the output and summary.json is complete",
          "  a = " in text and s is not None and s["complete"], text.strip().splitlines()[-1:])
    proc = subprocess.run(["FreeFem++", "benchmarks/cube.edp", "-out", out("headless pipe")], cwd=ROOT, env=headless_env(),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    check("headless, output to a pipe: exit 0 with the results", proc.returncode == 0 and "  w = " in proc.stdout,
          f"exit {proc.returncode}")


def test_template_workspace():
    """docs/writing_your_own_problem.md: `make workspace DIR=...` (scripts/workspace.sh) copies the
    template driver into a folder outside the suite and writes the one setting (freefem++.pref);
    the template then runs there, and so does a suite driver given by its path. The template's
    own checks: force balance to 1e-8 of the indentation force (measured ~4e-13), no penetration."""
    work = os.path.join(TMP, "my_contact_work")
    proc = subprocess.run(["bash", os.path.join(ROOT, "scripts", "workspace.sh"), work], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    check("workspace: created with the template and freefem++.pref", proc.returncode == 0
          and os.path.exists(os.path.join(work, "my_problem.edp")) and os.path.exists(os.path.join(work, "freefem++.pref")),
          proc.stdout.strip().splitlines()[-1:])
    code, output, _ = run_driver("my_problem.edp", ["-depth", "0.2", "-steps", "2", "-h", "0.2"], os.path.join(work, "o"), cwd=work)
    s = read_summary(os.path.join(work, "o"))
    check("workspace: the template runs in its own folder", code == 0 and s is not None and s["complete"],
          output.strip().splitlines()[-2:])
    if s:
        r = s["results"]
        check("workspace: the template's indentation force balances to 1e-8, no penetration",
              r["force_balance_rel_error"]["computed"] <= 1e-8 and r["max_penetration"]["computed"] <= 1e-10 * 2
              and r["indentation_force"]["computed"] > 0, f"{r['force_balance_rel_error']['computed']:.1e}")
    # the template takes -nu 0.5 (exact incompressibility, its default -volumetric nodal); it used to
    # tell the user to add -volumetric nodal, then reject it as an unknown parameter
    code, output, _ = run_driver("my_problem.edp", ["-depth", "0.2", "-steps", "2", "-h", "0.2", "-nu", "0.5"],
                                 os.path.join(work, "o_incompressible"), cwd=work)
    s = read_summary(os.path.join(work, "o_incompressible"))
    check("workspace: the template runs at -nu 0.5, balanced to 1e-8", code == 0 and s is not None and s["complete"]
          and s["results"]["force_balance_rel_error"]["computed"] <= 1e-8, output.strip().splitlines()[-2:])
    code, output, _ = run_driver(os.path.join(ROOT, "benchmarks", "hertz_plane.edp"), ["-h", "0.004"], os.path.join(work, "hertz"),
                                 cwd=work)
    check("workspace: a suite driver runs from that folder by its path", code == 0, output.strip().splitlines()[-1:])


def test_fold_guard():
    """The fold guard (body/injectivity.idp): known simple and folded deformations (fold_check.edp),
    then the Neo-Hookean cube at 100x its pressure, which folds through itself with every J > 0
    (it used to end Solve_Succeeded with w = 11.8 against the exact 0.71): it must not be reported
    as a result but end with exit code 3, one error line naming the fold, and an incomplete summary."""
    check_script_cases("fold_check", 6)
    o = out("folded cube")
    code, output, _ = run_driver("benchmarks/cube.edp", ["-material", "neohookean", "-pressure", "100"], o)
    errors = [l for l in output.splitlines() if l.startswith("error:")]
    s = read_summary(o)
    check("folded cube: exit code 3", code == 3, f"exit {code}")
    check("folded cube: one error line saying the body overlaps itself", len(errors) == 1 and "overlaps itself" in errors[0],
          str(errors))
    check("folded cube: summary.json incomplete, with the failure and status Folded_Body",
          s is not None and not s["complete"] and s["ipopt_status"] == "Folded_Body" and "overlaps" in (s["failure"] or ""),
          str(s and (s["complete"], s["ipopt_status"])))
    check("folded cube: no result reported (no w line, no .vtu)", "  w = " not in output
          and not any(f.endswith(".vtu") for f in os.listdir(o)))


def test_platen_block():
    """Displacement control at refinement: the rubber block pushed 16 % of its height onto the
    wavy floor, 80 elements wide, in 4 steps, at nu = 0.45 and 0.499 (setting the prescribed
    values alone inverted the first element layer at once; it needed 16 steps). Each run: no step
    cut, force balance platen + floor to 1e-8 (measured ~1e-15), no penetration, J > 0. At
    nu = 0.45 the platen force is within 2 % of the mesh-converged 0.6462 (Richardson of
    n = 40, 80, 160; n = 80 is 1.3 % above it), and the default run (n = 40) within the report's bound."""
    for nu in ("0.45", "0.499"):
        label = f"platen block n=80 nu={nu}"
        s = run_summary(label, "benchmarks/platen_block.edp", ["-n", "80", "-steps", "4", "-nu", nu])
        if s is None:
            continue
        r = s["results"]
        check(f"{label}: 4 steps, no cut", s["complete"] and s["step_cuts"] == 0 and len(s["steps"]) == 4,
              f"{len(s['steps'])} steps, {s['step_cuts']} cuts")
        fb = r["force_balance_rel_error"]["computed"]
        check(f"{label}: platen force = floor force to 1e-8", fb <= 1e-8, f"{fb:.1e}")
        check(f"{label}: no penetration (1e-10 H), J > 0", r["max_penetration"]["computed"] <= 1e-10 * 0.5
              and r["J_min"]["computed"] > 0, f"J_min {r['J_min']['computed']:.3f}")
        if nu == "0.45":
            err = abs(r["platen_force"]["computed"] - verdicts.PLATEN_REFERENCE) / verdicts.PLATEN_REFERENCE
            check(f"{label}: platen force within 2 % of the mesh-converged 0.6462", err <= 0.02, f"{err:.2e}")
    s = run_summary("platen block default", "benchmarks/platen_block.edp", [])
    if s:
        _, err, _, verdict = verdicts.verdict("platen_block", "platen_force", s["results"]["platen_force"])
        check(f"platen block default (n = 40): platen force within {verdicts.bound('platen_block', 'platen_force'):.0%} of 0.6462",
              verdict == "PASS", f"{err:.2e}")


def test_callback_error():
    """An error met inside an IPOPT callback (a node of the bulging block leaves the floor's spline
    data, -floormargin 0): one line, exit code 3, no FreeFEM call stack, no step cuts (cutting
    cannot mend it), summary.json incomplete with the message."""
    o = out("callback error")
    code, output, _ = run_driver("benchmarks/platen_block.edp", ["-floormargin", "0"], o)
    errors = [l for l in output.splitlines() if l.startswith("error:")]
    s = read_summary(o)
    check("callback error: exit code 3", code == 3, f"exit {code}")
    check("callback error: exactly one error line, naming the spline's data", len(errors) == 1 and "spline" in errors[0], str(errors))
    check("callback error: no call stack, no step cut", not any(k in output for k in ("call ", "current line", "cutting")))
    check("callback error: summary.json incomplete with the message", s is not None and not s["complete"]
          and "spline" in (s["failure"] or ""))


def test_unreachable_tolerance():
    """A tolerance IPOPT cannot reach (-tol 1e-20) is not a reason to cut the load step: one
    attempt, one error line with the status and a hint, exit code 3."""
    code, output, _ = run_driver("benchmarks/cube.edp", ["-tol", "1e-20", "-condense", "no"], out("tol"))
    errors = [l for l in output.splitlines() if l.startswith("error:")]
    check("unreachable tolerance: exit 3, one line naming -tol, no step cut", code == 3 and len(errors) == 1
          and "-tol" in errors[0] and "cutting" not in output, str(errors))
    # the condensed SQP (Newton's method here, no contact rows) stops where its step falls to the
    # round-off of U: the answer is then exact to rounding, which is what -tol 1e-20 asks
    s = run_summary("unreachable tolerance, condensed SQP", "benchmarks/cube.edp", ["-tol", "1e-20"])
    if s:
        check("unreachable tolerance, condensed SQP: exit 0 at the round-off of U, w exact to 1e-12",
              s["results"]["w"]["rel_error"] <= 1e-12, f"{s['results']['w']['rel_error']:.2e}")


def test_no_stale_outputs():
    """An output folder starts clean of the previous run's outputs: a run that fails, or is
    interrupted, leaves no older summary.json, .vtu or pressure.csv next to its own."""
    o = out("stale")
    run_driver("benchmarks/hertz_plane.edp", [], o)
    before = sorted(os.listdir(o))
    check("stale: a first complete run writes summary, .vtu and pressure.csv",
          {"summary.json", "hertz_plane.vtu", "pressure.csv"} <= set(before), str(before))
    run_driver("benchmarks/hertz_plane.edp", ["-maxiter", "2"], o)
    s = read_summary(o)
    after = os.listdir(o)
    check("stale: a failed run leaves its own incomplete summary and neither .vtu nor pressure.csv",
          s is not None and not s["complete"] and "hertz_plane.vtu" not in after and "pressure.csv" not in after, str(after))
    run_driver("benchmarks/hertz_plane.edp", [], o)
    # interrupted once it has opened the folder (the last run's summary.json is gone) and before it
    # ends (it has not exited): whatever the machine's speed (a fixed 4 s wait failed on a fast one)
    command = ["FreeFem++", "-nw", "benchmarks/hertz_plane.edp", "-h", "0.0002", "-out", o]
    proc = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    while os.path.exists(os.path.join(o, "summary.json")) and proc.poll() is None:
        time.sleep(0.01)
    interrupted = proc.poll() is None
    proc.kill()
    proc.wait()
    left = os.listdir(o)
    check("stale: an interrupted run leaves no summary.json, .vtu or pressure.csv of the run before",
          interrupted and not ({"summary.json", "hertz_plane.vtu", "pressure.csv"} & set(left)),
          f"interrupted before its end: {interrupted}; {sorted(left)}")
    mine = out("stale user files")
    os.makedirs(mine)
    for name in ("data.csv", "notes.vtu", "summary.txt"):
        open(os.path.join(mine, name), "w").write("the user's\n")
    run_driver("benchmarks/platen_block.edp", ["-n", "10", "-steps", "1"], mine)
    code, _, _ = run_driver("benchmarks/platen_block.edp", ["-n", "10", "-steps", "1"], mine)
    check("stale: a run removes only what a run wrote (the user's .csv, .vtu and other files stay)",
          code == 0 and all(os.path.exists(os.path.join(mine, n)) for n in ("data.csv", "notes.vtu", "summary.txt")),
          str(sorted(os.listdir(mine))))


def test_output_folder_errors():
    """An output folder that cannot be created: one error line naming -out, exit code 2."""
    blocker = os.path.join(TMP, "a_file")
    open(blocker, "w").close()
    code, output, _ = run_driver("benchmarks/cube.edp", [], os.path.join(blocker, "sub"))
    first = output.strip().splitlines()[0] if output.strip() else ""
    check("output folder under a file: exit 2, one error line naming -out", code == 2 and first.startswith("error:")
          and "-out" in first and len([l for l in output.splitlines() if l.startswith("error:")]) == 1, first)


def test_external_commands():
    """Every external program the Makefile, scripts, tests and drivers call is either provided by
    scripts/install_deps.sh or part of a minimal Debian (tests/check_commands.py). On a bare Debian
    root `make test` used to fail on /usr/bin/time, which nothing installed."""
    import check_commands
    missing, found = check_commands.unprovided()
    check(f"external commands: the {len(found)} programs used are all provided", not missing, str(missing))


# ---------------------------------------------------------------- hostile input (issue 26)
def error_lines(output):
    return [l for l in output.splitlines() if l.startswith("error:")]


def test_no_shell():
    """No path reaches a shell: an -out holding $(touch pwned) is just a folder's name, through the
    run, its IPOPT options, its gmsh call (hertz_sphere meshes with gmsh) and its clean-up."""
    for driver, args in (("benchmarks/cube.edp", []), ("benchmarks/hertz_sphere.edp", ["-dim", "3"])):
        parent = out(f"no shell {os.path.basename(driver)}")
        o = os.path.join(parent, "$(touch${IFS}pwned)")
        code, output, _ = run_driver(driver, args, o)
        s = read_summary(o)
        check(f"no shell, {os.path.basename(driver)}: exit 0 into the folder named '$(touch pwned)', complete",
              code == 0 and s is not None and s["complete"], f"exit {code}; {error_lines(output)}")
        check(f"no shell, {os.path.basename(driver)}: nothing ran (no file pwned in the working or output folders)",
              not any(os.path.exists(os.path.join(d, "pwned")) for d in (ROOT, parent, o, os.path.dirname(o))))


def stale_summary(folder):
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump({"complete": True, "stale": True}, f)


def test_hostile_outputs_list():
    """The clean-up removes what .outputs names only when it is a regular file or a link of that
    name in the output folder: option-like names, '..', paths and folders are left alone, and a
    list of any length is worked through (5000 names: the old 'sh -c' silently did nothing)."""
    o = out("hostile outputs")
    os.makedirs(os.path.join(o, "userdir"))
    open(os.path.join(o, "userdir", "keep.txt"), "w").write("the user's\n")
    victim = out("hostile outputs victim.txt")
    open(victim, "w").write("outside\n")
    open(os.path.join(o, ".outputs"), "w").write("-rf\n--help\nuserdir\n..\n.\n../" + os.path.basename(victim)
                                                 + "\n" + victim + "\n/etc/hostname\n")
    stale_summary(o)
    code, output, _ = run_driver("benchmarks/cube.edp", ["-maxiter", "1"], o)
    s = read_summary(o)
    check("hostile .outputs: the run goes on (exit 3 of its own failure) and leaves its own incomplete summary",
          code == 3 and s is not None and not s["complete"] and "stale" not in s, f"exit {code}")
    check("hostile .outputs: userdir, its file, the file outside and /etc/hostname are all still there",
          os.path.isfile(os.path.join(o, "userdir", "keep.txt")) and os.path.isfile(victim)
          and os.path.exists("/etc/hostname"))
    big = out("long outputs list")
    os.makedirs(big)
    names = [f"old_step{i:05d}.log" for i in range(5000)]
    for name in names:
        open(os.path.join(big, name), "w").close()
    open(os.path.join(big, ".outputs"), "w").write("".join(n + "\n" for n in names))
    stale_summary(big)
    code, _, _ = run_driver("benchmarks/cube.edp", ["-maxiter", "1"], big)
    left = [n for n in os.listdir(big) if n.startswith("old_step")]
    s = read_summary(big)
    check("5000 listed outputs: all removed, the old complete summary replaced by this run's",
          not left and s is not None and "stale" not in s and not s["complete"], f"{len(left)} left, exit {code}")


def test_planted_files():
    """What lies at an output's name is not written through: a link pressure.csv pointing outside is
    replaced by the run's own file (its target untouched); a folder summary.json stops the run at once."""
    o = out("planted link")
    os.makedirs(o)
    target = out("planted link target.txt")
    open(target, "w").write("precious\n")
    os.symlink(target, os.path.join(o, "pressure.csv"))
    code, _, _ = run_driver("benchmarks/hertz_plane.edp", [], o)
    check("planted link: exit 0, the link's target untouched, pressure.csv now the run's own file",
          code == 0 and open(target).read() == "precious\n" and not os.path.islink(os.path.join(o, "pressure.csv"))
          and open(os.path.join(o, "pressure.csv")).readline().startswith("s,x_ref,"), f"exit {code}")
    d = out("summary folder")
    os.makedirs(os.path.join(d, "summary.json"))
    open(os.path.join(d, "summary.json", "inside.txt"), "w").write("the user's\n")
    code, output, _ = run_driver("benchmarks/cube.edp", [], d)
    errors = error_lines(output)
    check("summary.json a folder: exit 2, one error line naming it, the folder and its file kept",
          code == 2 and len(errors) == 1 and "summary.json" in errors[0]
          and os.path.isfile(os.path.join(d, "summary.json", "inside.txt")), f"exit {code}; {errors}")


def test_folder_lock():
    """A second run into a folder in use stops at once (exit 2, one line saying so) and the first
    run, undisturbed, completes with all its logs."""
    import fcntl
    o = out("locked")
    first = subprocess.Popen(["FreeFem++", "-nw", "benchmarks/sliding_disc.edp", "-out", o], cwd=ROOT,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    held = False
    while first.poll() is None and not held:   # until the first run holds the lock
        try:
            with open(os.path.join(o, ".lock")) as f:
                try:
                    fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    fcntl.flock(f, fcntl.LOCK_UN)
                except OSError:
                    held = True
        except OSError:
            pass
        time.sleep(0.01)
    code, output, _ = run_driver("benchmarks/sliding_disc.edp", [], o)
    errors = error_lines(output)
    first_output, _ = first.communicate()
    s = read_summary(o)
    check("lock: the second run into a busy folder exits 2 with one line saying it is in use",
          held and code == 2 and len(errors) == 1 and "in use" in errors[0], f"held {held}; exit {code}; {errors}")
    logs = [n for n in os.listdir(o) if n.startswith("ipopt_step")]
    check("lock: the first run completes undisturbed, one log per step and iterations counted in every step",
          first.returncode == 0 and s is not None and s["complete"] and len(logs) == len(s["steps"])
          and "iterations 0 " not in first_output, f"exit {first.returncode}, {len(logs)} logs")


def test_full_disk():
    """Every write is checked: on file systems too small for the run's outputs (tmpfs from 4 KB to
    1 MB) the run either completes with every file whole, or ends with one error line naming the file
    it could not write, exit 3, and no summary.json claiming completion. Needs root (mount)."""
    mount_point = out("full disk")
    os.makedirs(mount_point)
    results = []
    for size in ("4k", "8k", "16k", "24k", "64k", "128k", "256k", "300k", "308k", "312k", "316k", "320k", "512k", "1m"):
        if subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", mount_point],
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode != 0:
            print(f"SKIP  full disk: cannot mount a tmpfs here (needs root): {size}")
            return
        try:
            o = os.path.join(mount_point, "o")
            code, output, _ = run_driver("benchmarks/hertz_plane.edp", [], o)
            errors = error_lines(output)
            try:
                s = read_summary(o)
                valid = True
            except ValueError:
                s, valid = None, False
            if code == 0:
                ok = (valid and s is not None and s["complete"] and not errors
                      and all(os.path.getsize(os.path.join(o, n)) > 0 for n in ("hertz_plane.vtu", "pressure.csv")))
            else:
                ok = (code == 3 and len(errors) == 1 and "No space left on device" in errors[0]
                      and valid and (s is None or not s["complete"]))
            results.append((size, code, errors[0].split(":")[1].split("/")[-1] if errors else ""))
            check(f"full disk {size}: exit 0 with whole outputs, or exit 3 naming the file it could not write",
                  ok, f"exit {code}; {errors}")
        finally:
            subprocess.run(["umount", mount_point])
    # FreeFEM's savevtk (P2 fields) reports no error: its file cut short is caught by its missing closing tag
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=16k", "tmpfs", mount_point]).returncode == 0:
        try:
            code, output, _ = run_driver("benchmarks/clamped_square.edp", ["-order", "2", "-n", "8"],
                                         os.path.join(mount_point, "o"))
            errors = error_lines(output)
            check("full disk 16k, P2 .vtu (savevtk): exit 3, one line naming clamped_square.vtu",
                  code == 3 and len(errors) == 1 and "clamped_square.vtu" in errors[0], f"exit {code}; {errors}")
        finally:
            subprocess.run(["umount", mount_point])
    failed = {name for _, code, name in results if code != 0}
    check("full disk: the smallest file systems fail, the largest completes, and the failures name at least "
          "three different files (ipopt.opt, pressure.csv, the .vtu, summary.json)",
          results[0][1] != 0 and results[-1][1] == 0 and len(failed) >= 3, str(results))


def test_checks_gate_exit():
    """A run whose own checks fail does not exit 0 (tests/checks_gate.edp records a balance or a
    penetration and ends the run as the drivers do): exit 4, one error line naming the check,
    summary.json's checks_failed; within the bounds exit 0 and checks_failed empty."""
    for args, code_expected, failed in ((["-balance", "1e-12"], 0, []), (["-balance", "1e-3"], 4, ["force_balance_rel_error"]),
                                        (["-penetration", "1e-6"], 4, ["max_penetration"])):
        o = out("checks gate " + " ".join(args))
        code, output, _ = run_driver("tests/checks_gate.edp", args, o)
        s = read_summary(o)
        errors = error_lines(output)
        check(f"checks gate {' '.join(args)}: exit {code_expected}, checks_failed {failed}, "
              f"{len(failed)} error line(s) naming it", code == code_expected and s is not None
              and s["checks_failed"] == failed and len(errors) == len(failed)
              and all(f in errors[0] for f in failed), f"exit {code}; {errors}")
    from freefem import run_ok, summary_failure
    s = read_summary(out("checks gate -balance 1e-3"))
    check("checks gate: the benchmark runner and the report count that run as failed (exit 4 and its summary)",
          s is not None and not run_ok(4, s) and not run_ok(0, s) and "force_balance_rel_error" in summary_failure(s)
          and run_ok(0, read_summary(out("checks gate -balance 1e-12"))))


def test_small_strain_rubber():
    """J - 1 and the diagonal of Grad u kept without cancellation (body/kinematics.idp): the nearly
    incompressible cube at the smallest strain core/ranges.idp admits, 1e-5, converges to its exact
    homogeneous state (det F - 1 lost |J - 1| to round-off: K (J - 1), K = 500..5000 G, swamped the
    forces, and IPOPT stalled already at strains of 1e-4 with nu = 0.4999)."""
    # at the floor core/ranges.idp sets: strain 1e-5 (pressure / G = 1e-5; the platen's compression)
    for args in (["-pressure", "6.2e-5"], ["-pressure", "6.2e-5", "-nu", "0.4999", "-dim", "3", "-n", "3", "-foundation", "1"],
                 ["-material", "neohookean", "-pressure", "2.5e-5", "-dim", "axi", "-nu", "0.4999", "-foundation", "1"],
                 ["-load", "platen", "-compression", "1e-5", "-dim", "3", "-n", "3", "-nu", "0.5"]):
        s = run_summary("small strain cube " + " ".join(args), "benchmarks/cube.edp", args)
        if s:
            err = s["results"]["w"]["rel_error"]
            # reference: the exact homogeneous w; bound: the round-off floor's reach, ~1e-16 / strain over
            # the tolerance (1.0e-7 measured for the axisymmetric case, the worst)
            check(f"small strain cube {' '.join(args)}: w exact to 1e-6", err <= 1e-6, f"{err:.2e}")


# ---------------------------------------------------------------- rubber (issue 12)
def test_volumetric_derivatives():
    """The nodal volumetric treatment's gradient, Hessian, constraint Jacobian and constraint
    curvature against central differences, column by column (fd_volumetric.edp): Mooney-Rivlin
    in 2D and 3D, penalty form and exact incompressibility, linear elasticity's nodal form, and the
    axisymmetric mode's energy (hoop stretch, 2 pi r measure) in every form.
    h = 1e-5 leaves ~1e-10..2e-9 (measured); bound 1e-8, as for the laws. In plane strain the
    tangent with the penalty's coupling from plugin/fast_assembly.cpp equals the varf plus
    FreeFEM's products to 1e-12 (rounding)."""
    code, output, _ = run_driver("tests/fd_volumetric.edp", [], None)
    lines = [l for l in output.splitlines() if l.startswith("fd_volumetric case=")]
    check("fd_volumetric: 27 derivative checks ran", len(lines) == 27, f"{len(lines)} lines")
    for line in lines:
        check("fd_volumetric " + " ".join(line.split()[1:3]), line.endswith("PASS"), line)
    check("fd_volumetric exit code", code == 0, f"exit {code}")


def test_incompressible_cube():
    """nu = 0.5 (-volumetric nodal: Jbar_n = 1 at every vertex as IPOPT equalities): w equals the
    incompressible homogeneous solution 2 (C10 + C01)(l - l^-3) = -p, computed in the project,
    to 1e-8 (IPOPT's tolerance: measured <= 5.7e-10), which is Code_Aster's analytic 0.034009 and
    0.07818; the element pressures from the multipliers equal the exact -tr(sigma)/3 to 1e-8
    (measured 5.4e-10) and are uniform to 1e-8 (measured 3e-13); also on the rigid foundation."""
    code_aster = {"mooney": 0.034009, "neohookean": 0.07818}
    for material in ("mooney", "neohookean"):
        for dim, n in (("2", "6"), ("3", "3")):
            for foundation in ("0", "1"):
                label = f"cube {dim}D {material} nu=0.5" + (" on foundation" if foundation == "1" else "")
                s = cube_case(label, ["-material", material, "-dim", dim, "-n", n, "-nu", "0.5", "-foundation", foundation])
                if s is None:
                    continue
                r = s["results"]
                check(f"{label}: the exact w is Code_Aster's {code_aster[material]} (to its 5 digits)",
                      abs(r["w"]["reference"] - code_aster[material]) < 5e-6, f"{r['w']['reference']:.8f}")
                p = r["hydrostatic_pressure"]
                # on the foundation the interior point leaves gaps ~mu / lambda (~1e-10) under the
                # contact nodes, which the pressure feels near the base: measured spread 1.1e-8..1.4e-8
                spread_bound = 1e-7 if foundation == "1" else 1e-8
                check(f"{label}: pressure from the multipliers = exact -tr(sigma)/3 to 1e-8, uniform to {spread_bound:g}",
                      p["rel_error"] <= 1e-8 and r["hydrostatic_pressure_spread"]["computed"] <= spread_bound,
                      f"{p['rel_error']:.1e}, spread {r['hydrostatic_pressure_spread']['computed']:.1e}")
                if foundation == "1":
                    check(f"{label}: contact force = load to 1e-10", r["contact_force"]["rel_error"] <= 1e-10,
                          f"{r['contact_force']['rel_error']:.1e}")


def test_rivlin_tube():
    """Rivlin's incompressible thick tube (exact large strain): on the default mesh (n = 32) the
    inner radius is within 1e-3 of (a - A) of the exact value with the nodal constraints at
    nu = 0.5 (measured 4.2e-4; second order in h, README table), the load from the project's
    quadrature equals the closed form to 1e-10 (measured 4e-14), and the balance holds to 1e-8.
    The penalty form at nu = 0.4999 on the same mesh locks: its error is over 10x larger."""
    s = run_summary("rivlin tube", "benchmarks/rivlin_tube.edp", [])
    if s is None:
        return
    r = s["results"]
    err = r["inner_radius_error_rel_to_opening"]["computed"]
    check("rivlin tube: inner radius within 1e-3 of (a - A)", err <= 1e-3, f"{err:.2e}")
    check("rivlin tube: quadrature = closed form to 1e-10", r["load_quadrature_vs_closed_form"]["computed"] <= 1e-10)
    check("rivlin tube: force balance <= 1e-8", r["force_balance_rel_error"]["computed"] <= 1e-8,
          f"{r['force_balance_rel_error']['computed']:.1e}")
    p = run_summary("rivlin tube penalty", "benchmarks/rivlin_tube.edp", ["-volumetric", "penalty", "-nu", "0.4999"])
    if p:
        locked = p["results"]["inner_radius_error_rel_to_opening"]["computed"]
        check("rivlin tube: the penalty form at nu = 0.4999 locks (error > 10x the nodal form's)", locked > 10 * err,
              f"{locked:.2e} vs {err:.2e}")
    # issue 25: still locking-free at nu = 0.5: second order in h (n = 8 -> 16 divides the error by
    # 4.2, measured; 3.5 sits between first order's 2 and second order's 4)
    errors = {}
    for n in ("8", "16"):
        t = run_summary(f"rivlin tube n={n}", "benchmarks/rivlin_tube.edp", ["-n", n])
        if t:
            errors[n] = t["results"]["inner_radius_error_rel_to_opening"]["computed"]
    if len(errors) == 2:
        check("rivlin tube at nu = 0.5: second order (the error falls by >= 3.5 from n = 8 to 16)",
              errors["8"] >= 3.5 * errors["16"], f"{errors['8']:.2e} -> {errors['16']:.2e}")


def test_hertz_near_incompressible():
    """Linear Hertz on the plane near and at the incompressible limit with -volumetric nodal, at
    h = a/60: a and p_max within the same 0.3 % of Hertz as at nu = 0.3 (measured 0.02 %..0.07 %),
    the L2 error of p within the same 1 % (measured 0.15 %..0.48 %), force balance and penetration
    as always. (At the default a/30 the nodal contact pressures alternate by ~2 % node to node near
    nu = 1/2 and L2 reaches 1.2-1.7 %: README.) The penalty form at nu = 0.4999 misses a by 17 %."""
    for nu in ("0.49", "0.499", "0.4999", "0.5"):
        hertz_case(f"hertz plane nodal nu={nu} h=a/60", "benchmarks/hertz_plane.edp",
                   ["-volumetric", "nodal", "-nu", nu, "-h", "0.00083"])
    s = run_summary("hertz plane penalty nu=0.4999", "benchmarks/hertz_plane.edp", ["-volumetric", "penalty", "-nu", "0.4999"])
    if s:
        check("hertz plane penalty nu=0.4999: locks (a off by more than 5 %)", s["results"]["a"]["rel_error"] > 0.05,
              f"{s['results']['a']['rel_error']:.2e}")


# ---------------------------------------------------------------- axisymmetry (issue 16)
def test_axisymmetric_cylinder():
    """The cube's axisymmetric analogue (cube.edp -dim axi): a solid cylinder between frictionless
    plates deforms homogeneously, F = diag(a, b, a), so P1 with the hoop stretch reproduces the
    exact solution (computed in the project without finite elements) to IPOPT's tolerance: 1e-8
    (measured 1e-16..4.6e-10), supported, on the rigid foundation and exactly incompressible; on
    the foundation the contact force per full revolution equals p pi r^2 to 1e-10."""
    for material in ("mooney", "neohookean"):
        for extra in ([], ["-foundation", "1"], ["-nu", "0.5"]):
            label = f"cylinder {material} {' '.join(extra)}".strip()
            s = cube_case(label, ["-material", material, "-dim", "axi", "-n", "4"] + extra)
            if s and extra == ["-foundation", "1"]:
                f = s["results"]["contact_force"]
                check(f"{label}: contact force = p pi r^2 to 1e-10", f["rel_error"] <= 1e-10, f"{f['rel_error']:.1e}")
            if s and extra == ["-nu", "0.5"]:
                p = s["results"]["hydrostatic_pressure"]
                check(f"{label}: pressure from the multipliers = exact -tr(sigma)/3 to 1e-8", p["rel_error"] <= 1e-8,
                      f"{p['rel_error']:.1e}")


def test_axisymmetric_sphere():
    """Hertz's sphere on a plane from the 2D meridian section (hertz_sphere.edp -dim axi):
    a and p_max within 0.3 % of Hertz on the default mesh (measured 0.07 % and 0.21 %: p_max stays
    0.24 % low under refinement, the finite hemisphere), L2 of p within 1 % (0.26 %), the contact
    force from the multipliers equal to the load f pi R^2 per full revolution to 1e-8, force balance
    and penetration as for every Hertz run."""
    hertz_case("hertz sphere axisymmetric", "benchmarks/hertz_sphere.edp", ["-dim", "axi"])
    # candidates within 0.09 < a = 0.1006: the contact zone reaches their edge, which the report
    # must refuse (a fit on a truncated contact zone would be a silent wrong answer)
    out = os.path.join(TMP, "sphere_few_candidates")
    code, output, _ = run_driver("benchmarks/hertz_sphere.edp", ["-dim", "axi", "-candidates", "0.09"], out)
    last = output.strip().splitlines()[-1] if output.strip() else ""
    summary = read_summary(out)
    check("hertz sphere axisymmetric -candidates 0.09: refused after the solve, naming -candidates",
          code != 0 and last.startswith("error:") and "-candidates" in last
          and summary is not None and summary.get("failure"), f"exit {code}: {last}")


def test_oring_torus():
    """The O-ring as a torus (oring_torus.edp), a face seal between plates, against the plane-strain
    ring of oring.edp -case plates on the same section mesh (h = R/24). Held at its mean radius
    (-holdcentre 1: the section's centroid, a linear row), the force per unit circumference at c = 0.2
    tends to the plane-strain force as the ring radius grows: 2.4 % from it at r0 = 5R, 0.15 % at 20R,
    0.008 % at 100R (measured); the test asks for a decreasing difference and 1e-3 at 100R. The hold is
    spread over the section: no stress concentration (it was one node: von Mises 12.6 next to it against
    3.0 free; now 4.4, the hoop stress of a ring kept at its radius). Free, the ring expands (hoop stress ~ 0) and its
    force does not depend on r0: equal at 5R and 100R to 1e-3 (measured 2e-5), the section's radial
    shift growing in proportion to r0. The radial (rod) seal squeezed by a bore is stiffer than plane
    strain by a gap falling like R / r0: 6.7 % at 20R, 1.3 % at 100R (measured; hoop compression)."""
    plane = run_summary("oring plates for the torus", "benchmarks/oring.edp", ["-case", "plates"])
    held = {m: run_summary(f"oring torus held r0={m}", "benchmarks/oring_torus.edp", ["-holdcentre", "1", "-meanradius", m])
            for m in ("2.6", "10.4", "52")}
    if plane and all(held.values()):
        reference = plane["results"]["force_c0.2"]["computed"]
        gaps = [abs(held[m]["results"]["force_c0.2"]["computed"] - reference) / reference for m in ("2.6", "10.4", "52")]
        check("oring torus held: the gap to plane strain shrinks as r0 grows", gaps[0] > gaps[1] > gaps[2], str(gaps))
        check("oring torus held at r0 = 100 R: plane strain's force to 1e-3", gaps[2] <= 1e-3, f"{gaps[2]:.1e}")
    free = {m: run_summary(f"oring torus free r0={m}", "benchmarks/oring_torus.edp", ["-meanradius", m]) for m in ("2.6", "52")}
    if held["2.6"] and free["2.6"]:
        h, f = held["2.6"]["results"], free["2.6"]["results"]
        check("oring torus held at r0 = 5R: no concentration at the hold (von Mises within 2x the free ring's, J_min within 0.05)",
              h["von_mises_max"]["computed"] <= 2 * f["von_mises_max"]["computed"]
              and abs(h["J_min"]["computed"] - f["J_min"]["computed"]) <= 0.05,
              f"{h['von_mises_max']['computed']:.3g} vs {f['von_mises_max']['computed']:.3g}; J {h['J_min']['computed']:.3f} vs {f['J_min']['computed']:.3f}")
    if all(free.values()):
        f5, f100 = (free[m]["results"]["force_c0.2"]["computed"] for m in ("2.6", "52"))
        check("oring torus free: the force does not depend on r0 (to 1e-3)", abs(f5 - f100) / f100 <= 1e-3, f"{abs(f5 - f100) / f100:.1e}")
    radial = {m: run_summary(f"oring torus radial r0={m}", "benchmarks/oring_torus.edp", ["-case", "radial", "-meanradius", m])
              for m in ("10.4", "52")}
    if plane and all(radial.values()):
        reference = plane["results"]["force_c0.2"]["computed"]
        gaps = [(radial[m]["results"]["force_c0.2"]["computed"] - reference) / reference for m in ("10.4", "52")]
        check("oring torus radial seal: stiffer than plane strain by a gap falling like R / r0 (ratio 4-6 from 20R to 100R)",
              0 < gaps[1] < gaps[0] and 4 <= gaps[0] / gaps[1] <= 6, str(gaps))
    for label, s in list(held.items()) + list(free.items()) + [("radial " + m, r) for m, r in radial.items()]:
        if s:
            fb = s["results"]["force_balance_rel_error"]["computed"]
            check(f"oring torus r0={label}: axial force balance <= 1e-8, no penetration", fb <= 1e-8
                  and s["results"]["max_penetration"]["computed"] <= 1e-10 * 0.52, f"{fb:.1e}")


# ---------------------------------------------------------------- contact between bodies
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


def test_two_bodies():
    """Issue 13. Two elastic cylinders (default: E2 = E1 / 3, the softer lower disc the slave) and
    the swapped slave/master choice, both within the issue's 0.5 % on a and p_max (measured
    0.06 %/0.02 % and 0.19 %/0.09 %) and 1.5 % in L2; the swap moves a by 0.13 % (the bias of the
    choice, held below 0.3 %). The rigid limit (E2 = 1e4 E1, the master normal: the pair's row is then
    the obstacle's linearised gap (43)) reproduces hertz_circle -constraint linearized to 1e-3
    (measured 3.1e-5; what is left is the lower disc's compliance and its facets against the spline),
    and with updated pairing hertz_circle -constraint exact to 2e-4 (measured 5.7e-5: the
    compliance E1 / E2 = 1e-4 moves Hertz's a by 5e-5). Two spheres in 3D on a coarse mesh: within
    3 % (measured 0.96 %, 0.02 %)."""
    bound = verdicts.bound("hertz_two_cylinders", "a")
    l2 = verdicts.check("hertz_two_cylinders", "pressure_l2_rel_error").bound
    base = two_body_case("two cylinders", "benchmarks/hertz_two_cylinders.edp", [], bound, l2)
    swapped = two_body_case("two cylinders, upper slave", "benchmarks/hertz_two_cylinders.edp", ["-slave", "upper"], bound, l2)
    if base and swapped:
        check("two cylinders: the default slave is the softer (lower) disc", base["parameters"]["slave"] == "softer")
        d = abs(base["results"]["a"]["computed"] - swapped["results"]["a"]["computed"]) / base["results"]["a"]["reference"]
        check("two cylinders: slave/master bias on a below 0.3 % (measured 0.13 %)", d <= 3e-3, f"{d:.2e}")
    two_body_case("two cylinders, master normal", "benchmarks/hertz_two_cylinders.edp", ["-normal", "master", "-slave", "lower"],
                  bound, l2)
    rigid = run_summary("two cylinders, rigid limit", "benchmarks/hertz_two_cylinders.edp",
                        ["-E2", "2.1e9", "-normal", "master", "-slave", "upper"])
    circle = run_summary("circle for the rigid limit", "benchmarks/hertz_circle.edp", ["-constraint", "linearized"])
    if rigid and circle:
        for q in ("a", "p_max"):
            d = abs(rigid["results"][q]["computed"] - circle["results"][q]["computed"]) / circle["results"][q]["computed"]
            check(f"two cylinders: rigid limit E2 = 1e4 E1 reproduces hertz_circle linearized, {q} to 1e-3", d <= 1e-3, f"{d:.1e}")
    two_body_case("two cylinders E1=E2 nu 0.25/0.35", "benchmarks/hertz_two_cylinders.edp",
                  ["-E2", "2.1e5", "-nu1", "0.25", "-nu2", "0.35"], bound, l2)
    two_body_case("two spheres", "benchmarks/hertz_two_spheres.edp", [], verdicts.bound("hertz_two_spheres", "a"), None)
    check_script_cases("fd_pairs", 12)
    # updated pairing (finite sliding) in the rigid limit is the rigid circle's exact form (42):
    # the same contact condition on the deformed surface, the circle sampled by the master's chords
    updated = run_summary("two cylinders, rigid limit, updated pairing", "benchmarks/hertz_two_cylinders.edp",
                          ["-E2", "2.1e9", "-normal", "master", "-slave", "upper", "-constraint", "updated"])
    exact = run_summary("circle for the rigid limit, exact form", "benchmarks/hertz_circle.edp", ["-constraint", "exact"])
    if updated and exact:
        for q in ("a", "p_max"):
            d = abs(updated["results"][q]["computed"] - exact["results"][q]["computed"]) / exact["results"][q]["computed"]
            check(f"two cylinders, updated pairing: rigid limit reproduces hertz_circle exact, {q} to 2e-4 (measured 5.7e-5, 1.9e-5)",
                  d <= 2e-4, f"{d:.1e}")
        pc = updated["results"]["pairing_change_rel"]["computed"] if "pairing_change_rel" in updated["results"] else None
        check("two cylinders, updated pairing: settled (last gap change <= 1e-10 of the body size)",
              pc is not None and pc <= 1e-10, f"{pc}")


def check_no_tensile_pressure(label):
    """The run's pressure.csv: no tensile pressure beyond 1e-6 of its peak (IPOPT's complementarity)."""
    rows = read_pressure_csv(label) or []
    pressures = [float(row["pressure"]) for row in rows]
    check(f"{label}: no tensile pressure beyond 1e-6 of the peak", pressures and min(pressures) >= -1e-6 * max(pressures),
          f"{min(pressures) if pressures else None}")


def test_sliding_disc():
    """Issue 13, large sliding: a half disc pressed into an elastic block and slid along it by R/4
    (h = R/40, 8 slide steps of 1.25 h, so that the steps see the contact at different phases
    against the block's nodes). At every step (the run keeps the worst): balance to 1e-8, action =
    reaction to 1e-12, no penetration and the pairing settled within 1e-10 of the size (2L = 3R).
    Frictionless: the sideways force Fx / Fy below 1e-3 (measured 2.7e-4 at R/40, 7.9e-5 at R/80,
    16 steps); the ripple of Fy about its quadratic trend below 1e-2 (measured 5.1e-3 at R/40,
    9.8e-4 at R/80: the P1 master's facets)."""
    s = run_summary("sliding disc", "benchmarks/sliding_disc.edp", ["-slidesteps", "8"])
    if s is None:
        return
    r = s["results"]
    size = 3.0
    check("sliding disc: IPOPT converged every step", s["ipopt_status"] == "Solve_Succeeded" and s["complete"], s["ipopt_status"])
    for q, bound in (("force_balance_rel_error", 1e-8), ("disc_balance_rel_error", 1e-8), ("block_balance_rel_error", 1e-8),
                     ("action_reaction_rel_error", 1e-12), ("max_penetration", 1e-10 * size), ("pairing_change_rel", 1e-10),
                     ("sideways_force_ratio", 1e-3), ("force_ripple", 1e-2)):
        when = "last step" if q.startswith(("disc_", "block_")) else "worst step"
        check(f"sliding disc: {q} <= {bound:.0e} ({when})", r[q]["computed"] <= bound, f"{r[q]['computed']:.1e}")
    check_no_tensile_pressure("sliding disc")
    csv_path = os.path.join(out("sliding disc"), "force_slide.csv")
    steps = open(csv_path).read().splitlines()[1:] if os.path.exists(csv_path) else []
    check("sliding disc: force_slide.csv has the press step and 8 slide steps", len(steps) == 9, f"{len(steps)} rows")


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


def test_oring_flange():
    """Issue 13, the O-ring between elastic flanges (h = R/12 to keep the suite short). Steel: the
    rigid plates' force less the deficit the flange's compression costs. The measured deficit
    (rigid - steel) / rigid, 7.7e-5, agrees with the run's own first-order estimate to 10 % (measured
    4.5-4.7 % below it at h = R/12 and R/24, with 15 or 30 steps: the estimate differences nodal forces
    across a contact edge that moves half an element per step). Soft flange (E = 40 MPa, nu =
    0.45): the housing's deformation matters, the force falls by more than 10 % (measured 25 %)."""
    h = str(0.52 / 12)
    rigid = run_summary("oring plates, h = R/12", "benchmarks/oring.edp", ["-case", "plates", "-h", h])
    steel = run_summary("oring flange steel", "benchmarks/oring_flange.edp", ["-h", h])
    soft = run_summary("oring flange soft", "benchmarks/oring_flange.edp", ["-h", h, "-Ef", "40", "-nuf", "0.45", "-steps", "5"])
    size = 2 * 0.52
    if steel:
        flange_checks("oring flange steel", steel, size)
    if soft:
        flange_checks("oring flange soft", soft, size)
    if rigid and steel:
        f_rigid = rigid["results"]["force_c0.3"]["computed"]
        f_steel = steel["results"]["force"]["computed"]
        measured = (f_rigid - f_steel) / f_rigid
        estimate = steel["results"]["compliance_force_deficit_estimate"]["computed"]
        check("oring flange steel: force deficit against the rigid plates = the flange's compliance estimate to 10 %",
              estimate > 0 and abs(measured / estimate - 1) <= 0.1, f"measured {measured:.3e}, estimate {estimate:.3e}")
    if rigid and soft:
        f_rigid = rigid["results"]["force_c0.3"]["computed"]
        f_soft = soft["results"]["force"]["computed"]
        check("oring flange soft: the housing's deformation lowers the force by more than 10 %", f_soft < 0.9 * f_rigid,
              f"{f_soft / f_rigid:.3f} of the rigid plates' force")


def main():
    tests = [test_law_derivatives, test_linear_stiffness, test_obstacle_derivatives, test_cube, test_cube_second_parameter_set, test_cube_on_foundation,
             test_hertz_plane, test_condensed_path, test_hertz_circle, test_hertz_hyperelastic, test_known_contact_newton,
             test_clamped_square, test_hertz_sphere, test_oring_groove, test_oring_plates, test_report, test_output_contract,
             test_working_folder_untouched, test_bad_input, test_ipopt_failure_is_reported,
             test_hard_cases, test_step_cutting, test_sweep_smoke, test_bench_smoke,
             test_new_law_recipe, test_law_recipe_from_docs, test_headless, test_template_workspace, test_fold_guard, test_platen_block,
             test_callback_error, test_unreachable_tolerance, test_no_stale_outputs, test_output_folder_errors,
             test_external_commands, test_volumetric_derivatives, test_incompressible_cube, test_rivlin_tube,
             test_hertz_near_incompressible, test_axisymmetric_cylinder, test_axisymmetric_sphere,
             test_oring_torus, test_two_bodies, test_oring_flange, test_sliding_disc,
             test_cube_homogeneous_default_form, test_stability_check, test_indentation, test_oring_plates_deep,
             test_no_shell, test_hostile_outputs_list, test_planted_files, test_folder_lock, test_full_disk,
             test_checks_gate_exit, test_small_strain_rubber]
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
