"""Hand-written derivatives against finite differences: the .edp check scripts (each line a case), the laws and the obstacles from their registries."""

import pytest

from helpers import *  # noqa: F401,F403 (check, out, run_driver, read_summary, ROOT, TMP and the shared helpers)

# The check scripts: tests/<script>.edp prints one line per case ending in PASS or FAIL and exits 1 on
# a failure. (expected number of cases, the prefix of a case's line); the laws' and the obstacles'
# counts come from their registries, so a new law or obstacle kind is checked without touching this.
#   fd_laws: every registered law's P and A against central differences of psi and P, in 2D and 3D
#     (truncation ~h^2 = 1e-10: bound 1e-8), and two materials on two regions
#   fd_obstacles: every registered obstacle kind's gradient and Hessian, a disc and a shifted disc
#     (h = 1e-5: truncation ~1e-10, bound 1e-8)
#   fd_volumetric: the nodal volumetric treatment's gradient, Hessian, constraint Jacobian and
#     curvature, column by column (Mooney-Rivlin 2D and 3D, penalty and exact incompressibility,
#     linear elasticity's nodal form, the axisymmetric energy in every form; measured 1e-10..2e-9,
#     bound 1e-8); in plane strain the plugin's coupled tangent against the varf and FreeFEM's
#     products to 1e-12; the stabilised form's gradient and its saddle point matrix's Schur
#     complement against differences of the gradient (2D, 3D, axisymmetric, linear; 4e-10..6e-9),
#     and the 3D plugin's saddle with the stabilisation against the script's to 1e-12
#   fd_pairs: the contact pairs' rows against finite differences of the gap
#   fd_friction: the friction tangents orthogonal to the rows' gradients (1e-14), the friction force
#     against central differences of the dissipation (h = 1e-6: measured 5e-12 in 2D, 2e-11 in 3D;
#     bound 1e-8), the dissipation positively homogeneous, on a curved obstacle's rows and a pair's
#   fd_inertia: a time step's inertia term (body/inertia.idp) in the energy, gradient, Hessian and its
#     lower triangle, linear and Neo-Hookean (h = 1e-6: measured 1e-11..3e-11; bound 1e-8)
#   fd_fluid_pressure: the fluid pressure's term p V(U) (body/fluid_pressure.idp), plane strain and
#     axisymmetric, an arc closed along two walls and a closed outline: V's gradient and Hessian
#     (h = 1e-5, V quadratic or cubic: measured 1.8e-11..4.1e-11, bound 2e-10), the wired energy's
#     gradient and tangent (h = 1e-6: 5.8e-12..7.5e-11, bound 5e-10), and with the wall nodes on their
#     walls the nodal forces against -p n (2 pi r) ds on the deformed mesh and V against the deformed
#     volume (round-off: 0..6e-16, bound 1e-12)
#   stiffness_check: linear elasticity's Lame-form Hessian against the generic tangent (P1 and P2
#     in 2D, P1 in 3D and axisymmetric, whole and as the lower triangle, moduli varying per element),
#     and a hyperelastic tangent and forces from the plugin against their varfs (the 3D saddle point
#     matrix also when rewritten in place at a second state): equal to 1e-12
SCRIPTS = {
    "fd_laws": (lambda: 2 * len(registered_laws()) + 2, None),
    "fd_obstacles": (lambda: len(registered_obstacles()) + 2, "fd_obstacles obstacle="),
    "fd_volumetric": (lambda: 41, "fd_volumetric case="),
    "fd_pairs": (lambda: 12, None),
    "fd_friction": (lambda: 6, None),
    "fd_inertia": (lambda: 6, "fd_inertia law="),
    "fd_fluid_pressure": (lambda: 24, None),
    "stiffness_check": (lambda: 10, None),
}


@pytest.mark.parametrize("script", sorted(SCRIPTS))
def test_check_script(script):
    expected, prefix = SCRIPTS[script]
    check_script_cases(script, expected(), prefix=prefix)


def test_law_derivatives():
    """Every registered law is among fd_laws.edp's cases, in 2D and in 3D (test_check_script runs them)."""
    laws = registered_laws()
    code, output, _ = run_driver("tests/fd_laws.edp", [], None)
    for law in laws:
        check(f"fd_laws: law {law} checked in 2D and 3D",
              all(f"fd_laws dim={d} law={law} " in output for d in (2, 3)))


def test_new_law_recipe():
    """The recipe for a new law (docs/adding_a_law.md), followed in a copy of include/: one new file (here the
    Mooney-Rivlin law renamed plantedLaw, with one planted error in d2W/dJ2) and one registration
    entry. The finite-difference test must pick the new law up with its own parameters and catch
    the planted error in its Hessian only, while the registered laws still pass."""
    work = out("new law")
    include = os.path.join(work, "include")
    shutil.copytree(os.path.join(ROOT, "include"), include)
    law = open(os.path.join(include, "laws", "mooneyRivlin.idp")).read()
    for old, new in (("mooneyRivlin", "plantedLaw"), ("MooneyRivlin", "PlantedLaw")):
        law = law.replace(old, new)   # a law of its own: its own names and parameters (plantedLawC10)
    planted = law.replace("28./9*plantedLawC01", "28./8*plantedLawC01")
    check("new law: the planted error is in the file", planted != law)
    with open(os.path.join(include, "laws", "plantedLaw.idp"), "w") as f:
        f.write(planted)
    register_law(include, "plantedLaw", first=False)
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


def register_law(include, name, first=True):
    """Step 2 of docs/adding_a_law.md, literally: the page's registry line, with the law's name, added
    to the list registeredLaws, first or last (the page allows any place)."""
    doc = open(os.path.join(ROOT, "docs", "adding_a_law.md")).read()
    m = re.search(r"<!-- registry line -->\n\s*```freefem\n(.*?)\n\s*```", doc, re.S)
    check("law recipe: docs/adding_a_law.md gives the registry line", m is not None)
    if m is None:
        return
    line = m.group(1).strip().replace("<name>", name)
    registry = os.path.join(include, "laws", "registry.idp")
    text = open(registry).read()
    start = text.index("macro registeredLaws(apply)\n")
    at = text.index("\n", start) + 1 if first else text.index("// EOM", start)
    with open(registry, "w") as f:
        f.write(text[:at] + "  " + line + "\n" + text[at:])


def test_law_recipe_from_docs():
    """Issues 25 and 41: docs/adding_a_law.md followed literally. Its example law files (Yeoh, Gent) are
    written to include/laws/ in a copy of the suite and registered as the page says (the page's
    registry line, one law first in the list and one last); the finite-difference test checks them in
    2D and 3D (1e-8, as every law). With C20 = C30 = 0 Yeoh is the Neo-Hookean law, so the O-ring
    plates (a non-homogeneous, nearly incompressible problem where a law that kept its own volumetric
    term would lock) give Neo-Hookean's plate force under the default volumetric form at nu = 0.4999
    and 0.5: both runs solve the same problem to -tol 1e-10, bound 1e-9 (measured: equal to all 16
    digits). Gent's domain (I1b - 3 < Jm): the plates squeezed 20 % with Jm = 1 make the solver try
    points past it (measured: 2), which are rejected, and the run completes (exit 0): before the
    domain hook a law could only fail() there (exit 3). A copy of the Yeoh file without its
    setVolumetricModulus call is refused: exit 2, one error line naming setVolumetricModulus."""
    doc = open(os.path.join(ROOT, "docs", "adding_a_law.md")).read()
    files = re.findall(r"<!-- law file: (\S+) -->\n```freefem\n(.*?)```", doc, re.S)
    check("law recipe: docs/adding_a_law.md holds the Yeoh and Gent law files",
          [os.path.basename(path) for path, _ in files] == ["yeoh.idp", "gent.idp"], str([p for p, _ in files]))
    if len(files) != 2:
        return
    work, include = suite_copy("law recipe")
    for (path, text), first in zip(files, (True, False)):
        with open(os.path.join(work, path), "w") as f:
            f.write(text)
        register_law(include, os.path.basename(path)[:-4], first)
    laws = registered_laws(include)
    check("law recipe: yeoh registered first and gent last", laws[0] == "yeoh" and laws[-1] == "gent", str(laws))
    code, output, _ = run_driver(os.path.join(ROOT, "tests", "fd_laws.edp"), [], None, cwd=work)
    for law in ("yeoh", "gent"):
        lines = [l for l in output.splitlines() if l.startswith("fd_laws dim=") and f"law={law} " in l]
        check(f"law recipe: the {law} law's P and A against finite differences in 2D and 3D (1e-8)",
              len(lines) == 2 and all(l.endswith("PASS") for l in lines) and code == 0, str(lines))
    driver = open(os.path.join(ROOT, "benchmarks", "oring.edp")).read()
    law_line = 'setMooneyRivlin("neohookean", C10, 0, nu);'
    check("law recipe: the O-ring driver's law line found", law_line in driver)
    for name, call in (("yeoh", "setYeoh(C10, 0, 0, nu);"), ("gent", "setGent(2*C10, 1, nu);")):
        with open(os.path.join(work, f"oring_{name}.edp"), "w") as f:
            f.write(driver.replace(law_line, call))
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
    o_gent = out("law recipe gent")
    code_g, output_g, _ = run_driver(os.path.join(work, "oring_gent.edp"), common, o_gent, cwd=work)
    g = read_summary(o_gent)
    rejected = (g or {}).get("solver", {}).get("outside_domain_trial_points", 0)
    check("law recipe: Gent, Jm = 1: trial points past the locking stretch rejected, the run completes (exit 0)",
          code_g == 0 and g is not None and g["complete"] and rejected > 0,
          f"exit {code_g}, {rejected} rejected: {output_g.strip().splitlines()[-1:]}")
    path, law_text = files[0]
    forgetful = law_text.replace("  setVolumetricModulus((nu == 0.5 ? 0. : 2*C10/(1 - 2*nu)), nu);\n", "")
    check("law recipe: the copy without setVolumetricModulus differs", forgetful != law_text)
    with open(os.path.join(work, path), "w") as f:
        f.write(forgetful)
    o = out("law recipe forgetful")
    code, output, _ = run_driver(os.path.join(work, "oring_yeoh.edp"), common, o, cwd=work)
    errors = [l for l in output.splitlines() if l.startswith("error:")]
    check("law recipe: a law without setVolumetricModulus is refused (exit 2, one line naming it, no summary)",
          code == 2 and len(errors) == 1 and "setVolumetricModulus" in errors[0] and not os.path.exists(os.path.join(o, "summary.json")),
          f"exit {code}: {errors}")