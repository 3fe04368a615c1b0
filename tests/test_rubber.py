"""Rubber: the cube's exact homogeneous states, incompressibility, Rivlin's tube, the axisymmetric cylinder, the O-ring benchmarks, the platen block, the stability study and the 3D indentation."""

import pytest

from helpers import *  # noqa: F401,F403 (check, out, run_driver, read_summary, ROOT, TMP and the shared helpers)


# The block's cases, one test each (pytest -k "3d and mooney" selects): material x (dimension, n).
CUBE_GRID = [(material, dim, n) for material in ("mooney", "neohookean") for dim, n in (("2", "6"), ("3", "3"))]
CUBE_IDS = [f"{dim}d-{material}" for material, dim, _ in CUBE_GRID]


@pytest.mark.parametrize("material, dim, n", CUBE_GRID, ids=CUBE_IDS)
def test_cube(material, dim, n):
    expected = {"mooney": 0.0340725, "neohookean": 0.0783308}   # preprint / issue, 6 digits
    s = cube_case(f"cube {dim}D {material}", ["-material", material, "-dim", dim, "-n", n])
    if s is None:
        return
    w_exact = s["results"]["w"]["reference"]
    check(f"cube {dim}D {material}: exact solution is the preprint's {expected[material]}",
          abs(w_exact - expected[material]) < 5e-8, f"{w_exact:.8f}")
    if dim == "2":
        ca = s["results"]["w_vs_code_aster_incompressible"]["rel_error"]
        check(f"cube {dim}D {material}: 0.19 % from Code_Aster's incompressible value",
              abs(ca - 0.0019) < 0.0001, f"{ca:.5f}")


@pytest.mark.parametrize("material, dim, n", [(m, d, {"2": "5", "3": "2"}[d]) for m, d, _ in CUBE_GRID], ids=CUBE_IDS)
def test_cube_second_parameter_set(material, dim, n):
    """Non-default data and 3 load steps: same exactness, one record per step."""
    extra = {"mooney": ["-C10", "0.5", "-C01", "0.8"], "neohookean": ["-C10", "2.0"]}[material]
    args = ["-material", material, "-dim", dim, "-n", n, "-nu", "0.45", "-pressure", "0.3", "-steps", "3"] + extra
    s = cube_case(f"cube {dim}D {material} nu=0.45 p=0.3 3 steps", args)
    if s is not None:
        check(f"cube {dim}D {material} 3 steps: three step records, load 1/3, 2/3, 1",
              [round(st["load_factor"], 12) for st in s["steps"]] == [round(1 / 3, 12), round(2 / 3, 12), 1.0])


@pytest.mark.parametrize("material, dim, n", CUBE_GRID, ids=CUBE_IDS)
def test_cube_on_foundation(material, dim, n):
    """The block resting on the rigid plane y = 0 (contact instead of u_y = 0) has the same
    exact solution; the contact force from IPOPT's multipliers must carry the whole load
    (pressure x top area), the forces must balance and nothing may sink into the plane."""
    label = f"cube {dim}D {material} on foundation"
    s = cube_case(label, ["-material", material, "-dim", dim, "-n", n, "-foundation", "1"])
    if s is None:
        return
    f = s["results"]["contact_force"]
    check(f"{label}: contact force = applied load to 1e-10", f["rel_error"] <= 1e-10,
          f"{f['computed']:.12g} vs {f['reference']:.12g}, rel={f['rel_error']:.1e}")
    p = s["results"]["max_penetration"]["computed"]
    check(f"{label}: penetration <= 1e-10 x block height", p <= 1e-10, f"{p:.1e}")
    # every component of applied + contact + reactions sums to zero (a sum over a stepped
    # slice that dropped the last node's z made this 5e-3 in 3D while the contact force held)
    b = s["results"]["force_balance_rel_error"]["computed"]
    check(f"{label}: force balance <= 1e-8", b <= 1e-8, f"{b:.1e}")


# The default volumetric form's grid: (dimension, law, nu), one test each.
DEFAULT_FORM_GRID = ([(dim, material, nu) for dim in ("2", "axi") for material in ("mooney", "neohookean")
                      for nu in ("0.45", "0.4999", "0.5")]
                     + [("3", material, nu) for material in ("mooney", "neohookean") for nu in ("0.4999", "0.5")])


@pytest.mark.parametrize("dim, material, nu", DEFAULT_FORM_GRID,
                         ids=[f"{d if d == 'axi' else d + 'd'}-{m}-nu{nu}" for d, m, nu in DEFAULT_FORM_GRID])
def test_cube_homogeneous_default_form(dim, material, nu):
    """Issue 25: the default volumetric form on the compressed block, 1 % to 35 % compression, 2D, axisymmetric
    and 3D, Mooney-Rivlin and Neo-Hookean, nu 0.45 to 0.5, supported or on the rigid foundation, on the
    structured mesh and with its interior vertices moved at random by up to 0.3 of the spacing. Under
    the rigid platen (displacement control) the exact state is stable to Biot's limit and every run must
    land on it (35 % in 4 load steps: in one, IPOPT on the whole axisymmetric block on the foundation
    ended in another state, which the run reported with exit 4). Under the dead load (the preprint's loading) it is stable only to 20-26 % on these
    meshes (tests/stability_check.edp): up to 20 % every run must land on it; at 28 % the block
    buckles at its free top corner, and the run must say so (exit 4, the tangent's negative eigenvalue
    at the exact state) instead of reporting the buckled state against the exact one. Poisson's ratio
    compressible (0.45), nearly (0.4999: the penalty's K / G = 5000) and exactly incompressible (0.5);
    0.499 went, which took 40 of the 180 runs and met every check as 0.4999 did (make test's 15 minutes).

    One test per (dimension, law, nu): pytest -k "axi and mooney" selects; in 3D n = 3 and nu 0.4999
    and 0.5, without the foundation. test_cube_dead_load_past_stability runs the buckled block."""
    name = "3D" if dim == "3" else dim
    mesh = ["-n", "3"] if dim == "3" else []
    for foundation in (("0",) if dim == "3" else ("0", "1")):
        on = "" if dim == "3" else f" foundation={foundation}"
        support = [] if dim == "3" else ["-foundation", foundation]
        for perturb in ("0", "0.3"):
            for c, steps in (("0.01", "1"), ("0.35", "4")):
                homogeneous_case(f"cube {name} {material} nu={nu}{on} perturb={perturb} platen {c}",
                                 ["-dim", dim] + mesh + ["-material", material, "-nu", nu] + support
                                 + ["-perturb", perturb, "-load", "platen", "-compression", c, "-steps", steps])
        homogeneous_case(f"cube {name} {material} nu={nu}{on} perturb=0.3 dead load 0.2",
                         ["-dim", dim] + mesh + ["-material", material, "-nu", nu] + support
                         + ["-perturb", "0.3", "-compression", "0.2"])


def test_cube_dead_load_past_stability():
    """The dead-loaded block past its instability (test_cube_homogeneous_default_form): the run says
    so."""
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


def test_stability_check():
    """Issue 25, the stability check (tests/stability_check.edp): the default form's tangent at the exact
    homogeneous state has no negative eigenvalue under the platen at 0, 10, 28 and 35 % compression
    (2D, axisymmetric, 3D; both laws; nu 0.499, 0.4999, 0.5) nor under the dead load at 10 %; and the
    dead load's critical compression is the compressible block's (nu = 0.3, plain P1) to 1 % on
    n = 6, 12, 24, and falls with n: the block's own instability, not a mode of the form."""
    check_script_cases("stability_check", 95, prefix="stability_check ")


@pytest.mark.parametrize("material, dim, n", CUBE_GRID, ids=CUBE_IDS)
def test_incompressible_cube(material, dim, n):
    """nu = 0.5 (-volumetric nodal: Jbar_n = 1 at every vertex as IPOPT equalities): w equals the
    incompressible homogeneous solution 2 (C10 + C01)(l - l^-3) = -p, computed in the project,
    to 1e-8 (IPOPT's tolerance: measured <= 5.7e-10), which is Code_Aster's analytic 0.034009 and
    0.07818; the element pressures from the multipliers equal the exact -tr(sigma)/3 to 1e-8
    (measured 5.4e-10) and are uniform to 1e-8 (measured 3e-13); also on the rigid foundation."""
    code_aster = {"mooney": 0.034009, "neohookean": 0.07818}
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


CYLINDER_GRID = [(material, extra) for material in ("mooney", "neohookean")
                 for extra in ([], ["-foundation", "1"], ["-nu", "0.5"])]


@pytest.mark.parametrize("material, extra", CYLINDER_GRID,
                         ids=[f"{m}-{'-'.join(e).lstrip('-') or 'supported'}" for m, e in CYLINDER_GRID])
def test_axisymmetric_cylinder(material, extra):
    """The cube's axisymmetric analogue (cube.edp -dim axi): a solid cylinder between frictionless
    plates deforms homogeneously, F = diag(a, b, a), so P1 with the hoop stretch reproduces the
    exact solution (computed in the project without finite elements) to IPOPT's tolerance: 1e-8
    (measured 1e-16..4.6e-10), supported, on the rigid foundation and exactly incompressible; on
    the foundation the contact force per full revolution equals p pi r^2 to 1e-10."""
    label = f"cylinder {material} {' '.join(extra)}".strip()
    s = cube_case(label, ["-material", material, "-dim", "axi", "-n", "4"] + extra)
    if s and extra == ["-foundation", "1"]:
        f = s["results"]["contact_force"]
        check(f"{label}: contact force = p pi r^2 to 1e-10", f["rel_error"] <= 1e-10, f"{f['rel_error']:.1e}")
    if s and extra == ["-nu", "0.5"]:
        p = s["results"]["hydrostatic_pressure"]
        check(f"{label}: pressure from the multipliers = exact -tr(sigma)/3 to 1e-8", p["rel_error"] <= 1e-8,
              f"{p['rel_error']:.1e}")


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


@pytest.mark.heavy(seconds=34)
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


def depth_forces(folder):
    """The indentation's force at each depth (its force_depth.csv)."""
    with open(os.path.join(folder, "force_depth.csv")) as f:
        return [float(row["force"]) for row in csv.DictReader(f)]


def depth_force_gap(folder, reference):
    """The largest relative difference of the indentation's forces in `folder` from `reference` (a
    list of ten), 1 when either is not ten depths long."""
    other = depth_forces(folder)
    if not len(other) == len(reference) == 10:
        return 1
    return max(abs(a - b) / abs(b) for a, b in zip(other, reference))


def check_depth_forces(prefix, reference, runs, what):
    """Each (label, folder) of `runs` gives the force of the indentation in `reference` at every depth
    to the issue 43's 1e-6 (relative)."""
    plain = depth_forces(reference)
    for label, folder in runs:
        worst = depth_force_gap(folder, plain)
        check(f"{prefix}: {label}: {what}'s force at every depth to 1e-6", worst <= 1e-6, f"{worst:.1e}")


def planted_indentation(label, rel, old, new, args):
    """The indentation run with `args` in a copy of the suite whose include/<rel> has `old` replaced
    by `new` (planted_suite): checks that the plant is there and that the run exits 0 with its
    summary; returns (summary or None, its output folder)."""
    work, in_copy = planted_suite(label, rel, old, new)
    check(f"{label}: the plant is in the copy", in_copy)
    o = out(label + " run")
    code, output, _ = run_driver(os.path.join(ROOT, "benchmarks", "indentation.edp"), args, o, cwd=work)
    summary = read_summary(o)
    check(f"{label}: the run exits 0 with its summary", code == 0 and summary is not None,
          f"exit {code}: {output.strip().splitlines()[-3:]}")
    return summary, o


@pytest.mark.heavy(seconds=49)
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
    # issue 43: the SQP's reuse of its factors (the default -reuse 0.2 of the 3D saddle point path)
    # against a factorization at every iteration (-reuse 0): the same force at every depth to the
    # issue's 1e-6, in fewer factorizations. The reference runs at -tol 1e-10: its models are all
    # IPOPT's, whose barrier gap on the contact nodes moves the force at 0.04 R by 1.0e-6 at the
    # default 1e-8, where the default's models on reused factors are exact (test_reduced_by_last_set;
    # measured 4.9e-9 against IPOPT at 1e-10)
    fresh = run_summary("indentation 3D h=0.125 reuse 0", "benchmarks/indentation.edp",
                        ["-dim", "3", "-h", "0.125", "-reuse", "0", "-tol", "1e-10"])
    if fresh is None:
        return
    reused, plain = depth_forces(out("indentation 3D h=0.125")), depth_forces(out("indentation 3D h=0.125 reuse 0"))
    worst = max((abs(a - b) / abs(b) for a, b in zip(reused, plain)), default=1)
    check("indentation 3D h=0.125: the default (reuse 0.2) gives -reuse 0's force at every depth to 1e-6",
          len(reused) == len(plain) == 10 and worst <= 1e-6, f"{worst:.1e}")
    reusing = read_summary(out("indentation 3D h=0.125"))
    if reusing:
        counts = (reusing["timings"]["factorizations"], fresh["timings"]["factorizations"])
        check("indentation 3D h=0.125: fewer factorizations with the default reuse than with -reuse 0",
              counts[0] < counts[1] and reusing["solver"].get("reused_factorizations", 0) > 0, f"{counts}")
        # the default reuses on the 3D saddle point path only: 0.2 there, 0 in the axisymmetric model
        ratios = (reusing["solver"].get("reuse_ratio"), axi["solver"].get("reuse_ratio"), fresh["solver"].get("reuse_ratio"))
        check("indentation: the reuse ratio in effect is 0.2 in 3D by default, 0 axisymmetric, 0 with -reuse 0",
              ratios == (0.2, 0, 0), str(ratios))


def test_indentation_krylov():
    """Issue 43: Newton's steps on reused factors by GMRES (solve/krylov_step.idp) on the 3D
    indentation at R/8, by the default -krylov step (one factorization a load step, after its first
    Newton step by GMRES on the last step's factors) and by -krylov yes (GMRES at every iteration
    after a factorization). Against a factorization at every iteration (-krylov no -reuse 0, at -tol
    1e-10: IPOPT's models at 1e-8 keep a barrier gap on the contact nodes worth 1.0e-6 of the force,
    test_reduced_by_last_set): the same force at every depth to the issue's 1e-6 (the force sums
    the multipliers of all the contact rows). The default factorizes less than the chord steps alone
    (-krylov no: each step twice) and at most once a load step after the first's two (measured: 11
    in 10 steps), -krylov yes less than -reuse 0; the summaries' per-step factorizations and Krylov
    iterations add up to their totals. A planted error (a copy of the suite whose preconditioner's
    Schur block is scaled by 0.01, as if its factors were far staler than they are) makes -krylov
    yes's GMRES miss its tolerance in some steps: those factorize afresh (more factorizations than
    without it). The default's GMRES, on factors of the same load step or the last, meets the
    tolerance even so at R/8 and R/16 (measured), so its plant is GMRES's cap cut to one iteration:
    no step by GMRES is taken, each falls back to a fresh factorization. In both the forces are the
    same to 1e-6: never a wrong step. The 3D Neo-Hookean block on its foundation with -krylov yes
    lands on its exact homogeneous state (cube_case's bounds), on one factorization."""
    args = ["-dim", "3", "-h", "0.125"]
    direct = run_summary("indentation krylov: direct", "benchmarks/indentation.edp",
                         args + ["-krylov", "no", "-reuse", "0", "-tol", "1e-10"])
    chord = run_summary("indentation krylov: chord", "benchmarks/indentation.edp", args + ["-krylov", "no"])
    default = run_summary("indentation krylov: step", "benchmarks/indentation.edp", args)
    krylov = run_summary("indentation krylov: krylov", "benchmarks/indentation.edp", args + ["-krylov", "yes"])
    planted, o = planted_indentation("indentation krylov planted", "solve/krylov_step.idp",
                                     "real krylovPlantedError = 1;", "real krylovPlantedError = 0.01;",
                                     args + ["-krylov", "yes"])
    planted_step, o_step = planted_indentation("indentation krylov planted step", "solve/krylov_step.idp",
                                               "int krylovMaxIterations = 15;", "int krylovMaxIterations = 1;", args)
    if None in (direct, chord, default, krylov, planted, planted_step):
        return

    check_depth_forces("indentation krylov", out("indentation krylov: direct"),
                       (("step", out("indentation krylov: step")), ("krylov", out("indentation krylov: krylov")),
                        ("planted", o), ("planted step", o_step)), "-reuse 0")
    counts = [s["timings"]["factorizations"] for s in (direct, krylov, planted)]
    check("indentation krylov: factorizations: krylov < direct -reuse 0, and the planted run factorizes more than krylov",
          counts[1] < counts[0] and counts[2] > counts[1], str(counts))
    steps = len(default["steps"])
    counts = [s["timings"]["factorizations"] for s in (default, chord)]
    check("indentation krylov: factorizations: step < chord, at most one a load step after the first's two",
          counts[0] < counts[1] and counts[0] <= steps + 1, f"{counts} in {steps} steps")
    check("indentation krylov: planted step: GMRES ran, and no Newton step by GMRES was taken",
          planted_step["timings"]["krylov_iterations"] > 0 and planted_step["solver"].get("krylov_steps", 0) == 0,
          f"{planted_step['timings']}")
    for label, s in (("step", default), ("krylov", krylov), ("planted", planted)):
        steps = s["steps"]
        check(f"indentation krylov: {label}: GMRES ran; the steps' factorizations and Krylov iterations add up to the totals",
              s["timings"]["krylov_iterations"] > 0 and s["solver"].get("krylov_steps", 0) > 0
              and sum(x["factorizations"] for x in steps) == s["timings"]["factorizations"]
              and sum(x["krylov_iterations"] for x in steps) == s["timings"]["krylov_iterations"],
              f"{s['timings']}")
    check("indentation krylov: direct and chord ran no GMRES",
          direct["timings"]["krylov_iterations"] == 0 and chord["timings"]["krylov_iterations"] == 0)
    # the block on its foundation by the same path: its exact homogeneous state (cube_case's bounds)
    label = "cube 3D neohookean on foundation -krylov yes"
    cube = cube_case(label, ["-material", "neohookean", "-dim", "3", "-n", "3", "-foundation", "1", "-krylov", "yes"])
    if cube:
        check(f"{label}: GMRES ran, on one factorization (measured: 25 iterations)",
              cube["timings"]["krylov_iterations"] > 0 and cube["timings"]["factorizations"] == 1, str(cube["timings"]))



def test_single_precision_factors():
    """Issue 43: the SQP's factorizations in single precision (-factors auto, the default on the 3D
    saddle point path: solve/sqp.idp). The plugin against double on a known problem
    (single_factors_check.edp: its bounds there). The 3D indentation at R/8 with the default
    against -factors double: the same force at every depth to the issue's 1e-6 (both stop where
    each free dof's residual is below -tol, 1e-8, of the force scale; measured 3.8e-11 at R/16),
    every factorization of the default single and none of double's. A planted rejection (a copy
    whose every model on fresh single precision factors fails) is made again on double factors:
    one single factorization, the rejection reported, exit 0 and the same forces: never a wrong
    step."""
    check_script_cases("single_factors_check", 7, prefix="single_factors_check case=")
    args = ["-dim", "3", "-h", "0.125"]
    auto = run_summary("indentation factors: auto", "benchmarks/indentation.edp", args)
    double = run_summary("indentation factors: double", "benchmarks/indentation.edp", args + ["-factors", "double"])
    planted, o = planted_indentation("indentation factors planted", "solve/sqp.idp",
                                     "      if (status != 0 && freshSingle) { sqpRejectSingle }",
                                     "      if (freshSingle) status = 1;\n      if (status != 0 && freshSingle) { sqpRejectSingle }",
                                     args)
    if auto is None or double is None or planted is None:
        return
    check_depth_forces("indentation factors", out("indentation factors: double"),
                       (("auto", out("indentation factors: auto")), ("planted", o)), "-factors double")
    single = [s["solver"].get("single_precision_factorizations", -1) for s in (auto, double, planted)]
    total = [s["timings"]["factorizations"] for s in (auto, double, planted)]
    check("indentation factors: every factorization single by default, none with -factors double, one planted",
          single[0] == total[0] > 0 and single[1] == 0 and single[2] == 1, f"single {single} of {total}")
    check("indentation factors: the planted run reports the rejection, the others none",
          planted["solver"].get("single_precision_rejected") == 1
          and "single_precision_rejected" not in auto["solver"], str(planted["solver"]))



def test_reduced_by_last_set():
    """Issue 43: the SQP's models on reused factors solved by the last model's contact set, without
    IPOPT (reduced_problem.idp's solveReducedByLastSet: the KKT conditions checked exactly). The 3D
    indentation at R/8 against a copy of the suite that never tries the set (lastSetPasses = 0:
    IPOPT on every model, as before), run at the default -tol 1e-8 and at -tol 1e-10. IPOPT's answer
    at 1e-8 keeps a barrier gap on the contact nodes (measured: the force at 0.04 R 1.0e-6 from its
    answer at 1e-10), which the exact set does not (5.0e-9): the default is within the issue's 1e-6 of
    the tight reference at every depth and no farther from it than IPOPT at 1e-8. The set serves
    models by default and none in the copy, at no more factorizations; the runs' own checks
    (balance, penetration) pass (exit 0). Models on fresh factors whose S is positive definite take
    the set too (more solves by the set than reused models), on S's Cholesky factor
    (dense_kkt_check.edp: its bounds there)."""
    check_script_cases("dense_kkt_check", 8, prefix="dense_kkt_check case=")
    args = ["-dim", "3", "-h", "0.125"]
    by_set = run_summary("indentation last set", "benchmarks/indentation.edp", args)
    runs, folders = {}, {}
    for label, extra in (("off", []), ("off tight", ["-tol", "1e-10"])):
        runs[label], folders[label] = planted_indentation(f"indentation last set {label}", "solve/reduced_problem.idp",
                                                          "int lastSetPasses = 10;", "int lastSetPasses = 0;", args + extra)
    if by_set is None or None in runs.values():
        return
    tight = depth_forces(folders["off tight"])
    mine, ipopt = depth_force_gap(out("indentation last set"), tight), depth_force_gap(folders["off"], tight)
    check("indentation last set: the default within 1e-6 of IPOPT at -tol 1e-10 at every depth, no farther than IPOPT at 1e-8",
          mine <= 1e-6 and mine <= ipopt, f"{mine:.1e} against IPOPT's {ipopt:.1e}")
    served = (by_set["solver"].get("last_set_solves", 0), runs["off"]["solver"].get("last_set_solves", 0))
    check("indentation last set: the set served models by default, none in the copy", served[0] > 0 and served[1] == 0,
          str(served))
    reused = by_set["solver"].get("reused_factorizations", 0)
    check("indentation last set: models on fresh factors served too (more set solves than reused models)",
          served[0] > reused, f"{served[0]} set solves, {reused} reused models")
    counts = (by_set["timings"]["factorizations"], runs["off"]["timings"]["factorizations"])
    check("indentation last set: no more factorizations than without it", counts[0] <= counts[1], str(counts))


@pytest.mark.heavy(seconds=25)
def test_anderson_acceleration():
    """Issue 43: the SQP's steps on reused factors mixed from its last ones (solve/anderson.idp,
    -anderson 3 by default on the 3D saddle point path). The 3D indentation at R/16 with -reuse 0.5
    and -krylov no (the chord steps alone, where the factors are kept longest, so the steps mixed
    most) against -anderson 0: the force at
    every depth to the issue's 1e-6 (both stop where each free dof's residual is below -tol, 1e-8, of
    the force scale), fewer SQP iterations in all (measured 84 against 111, the same 14
    factorizations), mixed steps in one run and none in the other. A planted wrong mix (the mixing
    coefficients 50 times theirs) at R/8: the SQP's checks on the energy and the residual catch its
    steps, and the forces are -anderson 0's to 1e-6, exit 0: never a wrong step."""
    args = ["-dim", "3", "-h", "0.0625", "-reuse", "0.5", "-krylov", "no"]
    mixed = run_summary("indentation anderson", "benchmarks/indentation.edp", args)
    plain = run_summary("indentation anderson off", "benchmarks/indentation.edp", args + ["-anderson", "0"])
    coarse = ["-dim", "3", "-h", "0.125", "-krylov", "no"]
    coarse_plain = run_summary("indentation anderson off R/8", "benchmarks/indentation.edp", coarse + ["-anderson", "0"])
    planted, o = planted_indentation("indentation anderson planted", "solve/anderson.idp",
                                     "    mixed -= gamma[i]*step;", "    mixed -= 50*gamma[i]*step;", coarse)
    if None in (mixed, plain, coarse_plain, planted):
        return
    check_depth_forces("indentation anderson", out("indentation anderson off"),
                       (("mixed", out("indentation anderson")),), "-anderson 0")
    check_depth_forces("indentation anderson R/8", out("indentation anderson off R/8"), (("planted", o),), "-anderson 0")
    iterations = [sum(step["iterations"] for step in run["steps"]) for run in (mixed, plain)]
    check("indentation anderson: fewer SQP iterations mixed than not", iterations[0] < iterations[1], str(iterations))
    steps = (mixed["solver"].get("anderson_steps", 0), plain["solver"].get("anderson_steps", 0),
             planted["solver"].get("anderson_steps", 0))
    check("indentation anderson: mixed steps by default and planted, none with -anderson 0",
          steps[0] > 0 and steps[1] == 0 and steps[2] > 0, str(steps))


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
