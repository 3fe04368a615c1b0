"""Contact against analytic answers: Hertz (plane, circle, sphere, axisymmetric, nearly incompressible, hyperelastic), the clamped square, two bodies, the sliding disc, the O-ring flange."""

import pytest

from helpers import *  # noqa: F401,F403 (check, out, run_driver, read_summary, ROOT, TMP and the shared helpers)


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


def test_hertz_sphere():
    """3D: a hemisphere on the plane, coarse mesh (h = a/8, ~5k dofs): a and p_max within 3 %
    of Hertz (measured 1.3 % and 0.9 %; 0.45 % / 0.08 % at h = a/16)."""
    hertz_case("hertz sphere", "benchmarks/hertz_sphere.edp", [], bound_a=verdicts.bound("hertz_sphere", "a"), bound_l2=None)


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


@pytest.mark.parametrize("nu", ["0.49", "0.499", "0.4999", "0.5"])
def test_hertz_near_incompressible(nu):
    """Linear Hertz on the plane near and at the incompressible limit with -volumetric nodal, at
    h = a/60: a and p_max within the same 0.3 % of Hertz as at nu = 0.3 (measured 0.02 %..0.07 %),
    the L2 error of p within the same 1 % (measured 0.15 %..0.48 %), force balance and penetration
    as always. (At the default a/30 the nodal contact pressures alternate by ~2 % node to node near
    nu = 1/2 and L2 reaches 1.2-1.7 %: docs/rubber.md.) One test per nu; test_hertz_penalty_locks
    runs the penalty form, which misses a by 17 % at nu = 0.4999."""
    hertz_case(f"hertz plane nodal nu={nu} h=a/60", "benchmarks/hertz_plane.edp",
               ["-volumetric", "nodal", "-nu", nu, "-h", "0.00083"])


def test_hertz_penalty_locks():
    """test_hertz_near_incompressible's contrast: the penalty form at nu = 0.4999 misses a by more
    than 5 %."""
    s = run_summary("hertz plane penalty nu=0.4999", "benchmarks/hertz_plane.edp", ["-volumetric", "penalty", "-nu", "0.4999"])
    if s:
        check("hertz plane penalty nu=0.4999: locks (a off by more than 5 %)", s["results"]["a"]["rel_error"] > 0.05,
              f"{s['results']['a']['rel_error']:.2e}")


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


def test_contact_candidates_accumulate():
    """setContactCandidates adds a label's nodes to those of earlier calls (tests/candidates_check.edp:
    bottom and top of an 8 x 8 square, 9 + 9 nodes), and a label given twice is bad input (exit 2, one
    line naming it)."""
    check_script_cases("candidates_check", 1, prefix="candidates_check ")
    code, output, _ = run_driver("tests/candidates_check.edp", ["-twice", "1"], None)
    errors = [l for l in output.splitlines() if l.startswith("error:")]
    check("candidates: a label given twice is bad input (exit 2, one line)", code == 2 and len(errors) == 1
          and "already a contact candidate label" in errors[0], f"exit {code}; {errors}")
