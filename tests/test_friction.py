"""Friction (issue 28): Cattaneo's partial slip, exact stick under a held load, gross sliding, the contact patch test,
Coulomb's law in every friction run, the sliding disc with friction, and -mu 0 leaving a run as it was."""

import pytest

from helpers import *  # noqa: F401,F403 (check, out, run_driver, read_summary, ROOT, TMP and the shared helpers)
import benchmark_list  # noqa: E402

CATTANEO = "benchmarks/cattaneo.edp"


def bench_args(name):
    """The arguments of a benchmark of scripts/benchmark_list.py (the test runs what the report runs)."""
    return next(args for n, _, args in benchmark_list.BENCHMARKS if n == name)


def friction_rows(label):
    path = os.path.join(out(label), "pressure.csv")
    return list(csv.DictReader(open(path))) if os.path.exists(path) else []


def check_coulomb(label, s, bench):
    """The run's Coulomb check within the verdict's bound for the benchmark `bench` (the run's own gate
    is 1e-8 or 100 x -tol), and the dissipation is not negative."""
    r = s["results"]
    bound = verdicts.bound(bench, "coulomb_violation")
    check(f"{label}: Coulomb's law at every node (coulomb_violation <= {bound:.0e})",
          "coulomb_violation" in r and r["coulomb_violation"]["computed"] <= bound,
          f"{r.get('coulomb_violation', {}).get('computed')}")
    check(f"{label}: dissipated energy >= 0", "dissipated_energy" in r and r["dissipated_energy"]["computed"] >= 0)
    check(f"{label}: no failed check", s["checks_failed"] == [], str(s["checks_failed"]))


def check_cattaneo_theory(label, s, bench):
    """Cattaneo's stick half-width, Hertz's a and the loads within the verdicts' bounds for `bench`, and
    the shear traction's L2 error against Cattaneo's."""
    r = s["results"]
    for q in ("stick_half_width", "a", "tangential_force", "normal_force"):
        bound = verdicts.bound(bench, q)
        check(f"{label}: {q} within {bound:.0e} of its reference", r[q]["rel_error"] <= bound, f"{r[q]['rel_error']:.2e}")
    bound = verdicts.bound(bench, "shear_l2_rel_error")
    check(f"{label}: shear traction L2 error <= {bound:.0%}", r["shear_l2_rel_error"]["computed"] <= bound,
          f"{r['shear_l2_rel_error']['computed']:.4f}")


def test_cattaneo_pair():
    """Two identical cylinders (dolfinx_contact's set-up: R 8, E 200, nu 0.3, p 0.625, mu 0.2,
    q 0.05851), the default mesh a/60: Cattaneo's stick half-width within 2 % (measured 0.29 %) and
    the shear traction's L2 error within 3 % (measured 2.4 %; 3.5 % at a/30, 0.75 % at a/120);
    Hertz's a within 1 % (measured 0.35 %); the tangential load reached to 1e-10 (load control)."""
    label = "cattaneo pair"
    s = run_summary(label, CATTANEO, [])
    if s is None:
        return
    check_cattaneo_theory(label, s, "cattaneo")
    check_coulomb(label, s, "cattaneo")
    rows = friction_rows(label)
    check(f"{label}: pressure.csv has shear, slip and status columns",
          rows and {"shear", "slip", "status"} <= set(rows[0].keys()))
    states = {row["status"] for row in rows}
    check(f"{label}: both stick and slip nodes (partial slip)", {"stick", "slip"} <= states, str(states))
    # where a node slips its shear is mu p; where it sticks it is below
    mu = s["parameters"]["mu"]
    worst = max((abs(abs(float(row["shear"])) - mu * float(row["pressure"])) / (mu * max(float(x["pressure"]) for x in rows))
                 for row in rows if row["status"] == "slip"), default=1)
    check(f"{label}: slipping nodes carry |q| = mu p (1e-8 of mu p_max)", worst <= 1e-8, f"{worst:.1e}")
    zone = os.path.join(out(label), "stick_zone.csv")
    lines = open(zone).read().splitlines() if os.path.exists(zone) else []
    check(f"{label}: stick_zone.csv has one row per tangential step", len(lines) == 1 + s["parameters"]["steps"], f"{len(lines)} lines")


def stick_zone_rows(label):
    path = os.path.join(out(label), "stick_zone.csv")
    return list(csv.DictReader(open(path))) if os.path.exists(path) else []


@pytest.mark.heavy(seconds=78)
def test_cattaneo_rigid():
    """A rigid cylinder on a nearly or exactly incompressible block (issue 40), the default mesh a/60
    and block 10^4 a: Cattaneo's stick half-width within 3 % (measured 0.019 % at nu = 0.4999, 0.021 %
    at 0.5; 35 % for the issue's set-up, nodal form and linearised rows), the shear traction's L2 error
    within the issue's 5 % (1.1 % and 1.2 %; 70 % before), the stick zone shrinking at every step as Q
    grows (it grew) and one interval, Coulomb's law to round-off; at nu = 0.5 the block's volume kept
    (the run's own check, 1e-8) and the shear the normal load leaves below the issue's 1e-2 p0 (none in
    Cattaneo's theory at beta = 0; measured 8.2e-3). The Neo-Hookean law at a tenth of the load
    (strains of 5 %, block 100 a) meets Cattaneo too (c 0.22 %, L2 4.8 %). The issue's set-up (nodal
    form, linearised rows, block 20 a; a/30 here) fails the run's own checks: exit code 4."""
    for nu in ("0.4999", "0.5"):
        label = f"cattaneo rigid nu {nu}"
        s = run_summary(label, CATTANEO, ["-setup", "rigid", "-nu", nu])
        if s is None:
            continue
        r = s["results"]
        check_cattaneo_theory(label, s, "cattaneo_rigid")
        check(f"{label}: the stabilised nodal form by default with friction", s["parameters"]["volumetric"] == "stabilised",
              s["parameters"]["volumetric"])
        check_coulomb(label, s, "cattaneo_rigid")
        c = [float(row["stick_half_width"]) for row in stick_zone_rows(label)]
        check(f"{label}: the stick zone shrinks at every step as Q grows", len(c) == 5 and all(b < a for a, b in zip(c, c[1:])),
              str(c))
        if nu == "0.5":
            check(f"{label}: the block's volume kept (volume_balance_rel_error <= 1e-8)",
                  r.get("volume_balance_rel_error", {}).get("computed", 1) <= 1e-8, str(r.get("volume_balance_rel_error")))
            check(f"{label}: the normal load's shear below 1e-2 p0 (beta = 0: none in theory)",
                  r.get("normal_phase_shear", {}).get("computed", 1) <= 1e-2, str(r.get("normal_phase_shear")))
    label = "cattaneo rigid neohookean"
    s = run_summary(label, CATTANEO, ["-setup", "rigid", "-material", "neohookean", "-pressure", "0.0625", "-block", "100"])
    if s is not None:
        r = s["results"]
        check(f"{label}: stick half-width within 1 % of Cattaneo's", r["stick_half_width"]["rel_error"] <= 1e-2,
              f"{r['stick_half_width']['rel_error']:.2e}")
        check(f"{label}: shear traction L2 error <= 5 %", r["shear_l2_rel_error"]["computed"] <= 5e-2,
              f"{r['shear_l2_rel_error']['computed']:.4f}")
        check_coulomb(label, s, "cattaneo_rigid")
    label = "cattaneo rigid, the issue's set-up"
    code, output, _ = run_driver(CATTANEO, ["-setup", "rigid", "-volumetric", "nodal", "-constraint", "linearized",
                                            "-block", "20", "-h", "0.0206"], out(label))
    s = read_summary(out(label))
    failed = s["checks_failed"] if s else []
    check(f"{label}: exit code 4, the stick zone neither shrinking nor one interval",
          code == 4 and {"stick_zone_shrinks", "stick_zone_interval"} <= set(failed), f"exit {code}, {failed}")


def test_cattaneo_rigid_normal_phase():
    """At nu = 0.5 (Dundurs' beta = 0) the normal load leaves no shear in Cattaneo's theory; on the block
    the frictionless surface under the contact is stretched (the finite block's stretch, falling as 1 /
    its size, and its mesh's) and the stick zone's edge answers it with a shear, which falls as the
    block grows (a/30: 8.7e-2 p0 at 20 a, 4.4e-2 at 100 a, 1.2e-2 at 1000 a; below 1e-2 at 10^4 a,
    test_cattaneo_rigid: docs/benchmarks/friction.md). The one tangential step of 1e-6 mu P is there to
    end the run; its stick checks are not this test's."""
    shears = []
    for block in ("20", "100", "1000"):
        o = out(f"cattaneo rigid normal phase, block {block}")
        run_driver(CATTANEO, ["-setup", "rigid", "-nu", "0.5", "-h", "0.0206", "-block", block, "-ratio", "1e-6", "-steps", "1"], o)
        s = read_summary(o)
        shears.append(s["results"]["normal_phase_shear"]["computed"] if s and "normal_phase_shear" in s["results"] else None)
    check("cattaneo rigid normal phase: the shear falls as the block grows (20, 100, 1000 a)",
          None not in shears and shears[0] > shears[1] > shears[2], str(shears))


@pytest.mark.heavy(seconds=56)
def test_mindlin_sphere():
    """Two identical spheres (3D, the halves y >= 0), pressed and then sheared to Q = 0.8 mu P, the
    default mesh a/10: Mindlin's stick radius within the issue's 3 % (measured 2.6 % low; 3.3 % at a/8)
    and tangential displacement within 2 % (measured 1.8 %, once the bodies' own compliance beyond the
    half-space, measured by the bonded step, is taken off: 11 % high before), Hertz's a within 1 %
    (0.17 %); Coulomb's law to the verdict's 1e-10 (Coulomb's polish: 3.1e-15; the Tresca polish left
    4.9e-8 at -tol 1e-9, IPOPT alone 4e-6 at -tol 1e-8)."""
    label = "mindlin sphere"
    s = run_summary(label, "benchmarks/mindlin_sphere.edp", bench_args("mindlin_sphere"))
    if s is None:
        return
    r = s["results"]
    for q in ("stick_radius", "tangential_displacement", "a", "tangential_force", "normal_force"):
        bound = verdicts.bound("mindlin_sphere", q)
        check(f"{label}: {q} within {bound:.0e} of its reference", r[q]["rel_error"] <= bound, f"{r[q]['rel_error']:.2e}")
    check_coulomb(label, s, "mindlin_sphere")
    # the correction is the bodies' own: positive, and of the size a shear through the hemispheres' narrowing
    # sections gives (2 ln(R / a) / (2 pi G R) = 2.5e-3 here, against the bonded 2.4e-2)
    far, bonded = r["far_compliance"]["computed"], r["bonded_compliance"]["computed"]
    check(f"{label}: the bodies' compliance beyond Mindlin's is positive and below a fifth of the bonded one",
          0 < far < 0.2 * bonded, f"{far:.3g} of {bonded:.3g}")
    rows = friction_rows(label)
    states = {row["status"] for row in rows}
    check(f"{label}: both stick and slip nodes (partial slip)", {"stick", "slip"} <= states, str(states))
    zone = os.path.join(out(label), "stick_zone.csv")
    lines = open(zone).read().splitlines() if os.path.exists(zone) else []
    check(f"{label}: stick_zone.csv has one row per tangential step", len(lines) == 1 + s["parameters"]["steps"], f"{len(lines)} lines")
    # each tangential step starts with every site sticking (frictionWarmCarry(1)); the polish's trial force
    # settles three of the four without IPOPT (measured: steps 3-5 0 iterations, the last 23)
    tangential = [st["iterations"] for st in s["steps"][-s["parameters"]["steps"]:]]
    check(f"{label}: at least 3 of the 4 tangential steps by the polish alone (0 IPOPT iterations)",
          sum(1 for it in tangential if it == 0) >= 3, str(tangential))


def test_mindlin_rigid_hold():
    """A rigid sphere pressed into an exactly incompressible block (nu = 0.5, Dundurs' beta = 0: Mindlin's
    solution holds; issue 40), sheared to 0.99 mu P on the coarse mesh a/5, then the same load 10 more
    steps, each step's slips from the last: the platen does not move (bound 1e-10 of its displacement,
    measured 6.3e-14 on one thread, 6.1e-14 and 7.0e-14 on two), Coulomb's law to round-off (1.4e-13),
    the block's volume kept (1e-8; 1e-20), P and Q reached (1e-10), Mindlin's stick radius within the
    issue's 5 % (1.5 %). The two spheres' held load (mindlin_sphere_hold: 3.2e-14) and the default
    meshes' verdicts are the report's."""
    label = "mindlin rigid hold"
    s = run_summary(label, "benchmarks/mindlin_sphere.edp", bench_args("mindlin_rigid_hold"))
    if s is None:
        return
    r = s["results"]
    bound = verdicts.bound("mindlin_rigid_hold", "hold_tangential_drift")
    check(f"{label}: the platen does not creep over 10 held steps (<= {bound:.0e})",
          r["hold_tangential_drift"]["computed"] <= bound, f"{r['hold_tangential_drift']['computed']:.1e}")
    check(f"{label}: the block's volume kept (volume_balance_rel_error <= 1e-8)",
          r.get("volume_balance_rel_error", {}).get("computed", 1) <= 1e-8, str(r.get("volume_balance_rel_error")))
    for q in ("normal_force", "tangential_force"):
        check(f"{label}: {q} reached to 1e-10", r[q]["rel_error"] <= 1e-10, f"{r[q]['rel_error']:.1e}")
    bound = verdicts.bound("mindlin_rigid", "stick_radius")
    check(f"{label}: Mindlin's stick radius within {bound:.0%}", r["stick_radius"]["rel_error"] <= bound,
          f"{r['stick_radius']['rel_error']:.2e}")
    check_coulomb(label, s, "mindlin_rigid_hold")


def test_cattaneo_hold():
    """Exact stick: Q held at 0.99 mu P for 50 load steps, each step's slips measured from the last:
    the platen does not move after the first held step (relative change <= 1e-10; measured 1e-14,
    the active-set polish of solve/friction_polish.idp; without it IPOPT alone crept by 2.5e-5)."""
    label = "cattaneo hold"
    s = run_summary(label, CATTANEO, bench_args("cattaneo_hold"))
    if s is None:
        return
    r = s["results"]
    check(f"{label}: tangential displacement held (drift <= 1e-10)", r["hold_tangential_drift"]["computed"] <= 1e-10,
          f"{r['hold_tangential_drift']['computed']:.1e}")
    check_coulomb(label, s, "cattaneo_hold")


def test_cattaneo_gross_sliding():
    """Displacement control past mu P (-travel): the body slides and every contact node slips with
    |q| = mu p (the run's Coulomb check, 1e-8); the total Q = mu P in global axes to 1e-6: each node's
    law holds in its own row frame, and the pair's normals tilt as the surfaces deform (measured 3e-7)."""
    label = "cattaneo gross sliding"
    s = run_summary(label, CATTANEO, bench_args("cattaneo_sliding"))
    if s is None:
        return
    r = s["results"]
    bound = verdicts.bound("cattaneo_sliding", "tangential_force")
    check(f"{label}: Q = mu P to {bound:.0e}", r["tangential_force"]["rel_error"] <= bound, f"{r['tangential_force']['rel_error']:.1e}")
    check_coulomb(label, s, "cattaneo_sliding")
    states = {row["status"] for row in friction_rows(label) if row["status"] != "open"}
    check(f"{label}: every contact node slips", states == {"slip"}, str(states))


def test_sliding_disc_friction():
    """The disc slid along the block with mu = 0.3: Fx / Fy = mu over the sliding steps within 1 %
    (measured 0.97 %: the deformed block's surface tilts under the disc, so the contact normal is
    not vertical; the per-node law is the run's Coulomb check)."""
    label = "sliding disc mu 0.3"
    s = run_summary(label, "benchmarks/sliding_disc.edp", bench_args("sliding_disc_friction"))
    if s is None:
        return
    r = s["results"]
    check(f"{label}: friction_ratio_error <= 1 %", r["friction_ratio_error"]["computed"] <= 0.01,
          f"{r['friction_ratio_error']['computed']:.4f}")
    check_coulomb(label, s, "sliding_disc_friction")


@pytest.mark.parametrize("label, script, args", [
    ("hertz plane mu", "benchmarks/hertz_plane.edp", ["-mu", "0.3"]),
    ("two cylinders mu", "benchmarks/hertz_two_cylinders.edp", ["-mu", "0.3"]),
    ("axisymmetric sphere mu", "benchmarks/hertz_sphere.edp", ["-dim", "axi", "-mu", "0.3"])],
    ids=["hertz-plane", "two-cylinders", "axisymmetric-sphere"])
def test_friction_on_other_drivers(label, script, args):
    """Friction on a rigid obstacle (hertz_plane), on a pair (two cylinders) and axisymmetric (the
    sphere): each completes with Coulomb's law at every node to round-off (bound 1e-12, measured 4e-17
    to 4e-16: the polish solves Coulomb's problem on its active set; IPOPT's multipliers alone left 7e-11
    to 9e-8) in two solves of its one load step (the first without bounds, as nothing touched before
    it; the second's polish ends with the bounds its own forces give: 6 to 10 solves before)."""
    s = run_summary(label, script, args)
    if s is None:
        return
    r = s["results"]
    check(f"{label}: Coulomb's law at every node to round-off (coulomb_violation <= 1e-12)",
          r["coulomb_violation"]["computed"] <= 1e-12, f"{r['coulomb_violation']['computed']:.1e}")
    check(f"{label}: Coulomb's fixed point settles in 2 solves (Coulomb's polish)",
          r["friction_solves"]["computed"] == 2, str(r["friction_solves"]["computed"]))
    check(f"{label}: dissipated energy >= 0", r["dissipated_energy"]["computed"] >= 0)
    check(f"{label}: the force balance closes with the friction forces (1e-8)",
          r["force_balance_rel_error"]["computed"] <= 1e-8, f"{r['force_balance_rel_error']['computed']:.1e}")


def test_friction_mu_zero():
    """With -mu 0 hertz_plane's frictionless numbers are unchanged (to 1e-12) and pressure.csv has no
    friction columns."""
    plain = run_summary("hertz plane plain", "benchmarks/hertz_plane.edp", [])
    zero = run_summary("hertz plane mu 0", "benchmarks/hertz_plane.edp", ["-mu", "0"])
    if plain and zero:
        for q in ("a", "p_max", "contact_force", "pressure_l2_rel_error"):
            a, b = plain["results"][q]["computed"], zero["results"][q]["computed"]
            check(f"-mu 0 leaves hertz_plane's {q} unchanged (1e-12)", abs(a - b) <= 1e-12 * abs(a), f"{a} {b}")
        check("-mu 0: no friction columns in pressure.csv", "shear" not in (friction_rows("hertz plane mu 0") or [{}])[0])


def test_rigid_frictionless_reference():
    """-mu 0 on Cattaneo's and Mindlin's rigid set-ups, the frictionless reference make bench times their
    friction against: the normal load alone on the same mesh, exit 0, Hertz's a within the rigid set-ups'
    verdict bound (1 %; Cattaneo's a/30: measured 0.057 %; Mindlin's default a/10: 0.84 %, in the plain
    nodal form that -mu 0 defaults to: 0.26 % in the stabilised one that make bench gives both runs), the
    load P applied to the run's -tol (1e-9: without friction's polish the contact forces are IPOPT's
    multipliers; measured 1.3e-10 and 5.5e-12), friction recorded as none, and no tangential result."""
    for label, script, args, bench in (
            ("cattaneo rigid mu 0", CATTANEO, ["-setup", "rigid", "-h", "0.0206", "-mu", "0"], "cattaneo_rigid"),
            ("mindlin rigid mu 0", "benchmarks/mindlin_sphere.edp", ["-setup", "rigid", "-mu", "0"], "mindlin_rigid")):
        s = run_summary(label, script, args)
        if s is None:
            continue
        r = s["results"]
        bound = verdicts.bound(bench, "a")
        check(f"{label}: Hertz's a within {bound:.0%}", r["a"]["rel_error"] <= bound, f"{r['a']['rel_error']:.2e}")
        check(f"{label}: P applied (-tol 1e-9)", r["normal_force"]["rel_error"] <= 1e-9, f"{r['normal_force']['rel_error']:.1e}")
        check(f"{label}: friction none, no tangential result",
              s["parameters"].get("friction") == "none" and "tangential_force" not in r and "stick_half_width" not in r,
              f"{s['parameters'].get('friction')}, {sorted(r)}")


def same_results_as_copy(tag, work, cases, statistic):
    """Each case (label, script, args) run by the suite and by its planted copy in `work`: the copy's run
    exits 0, the path the solver statistic `statistic` counts ran in the suite's run and not in the
    copy's, every result the same to the runs' -tol, 1e-9 relative, and Coulomb's law to the verdicts'
    1e-10 in both."""
    for label, script, args in cases:
        default = run_summary(f"{tag} {label}", script, args)
        o = out(f"{tag} {label} copy")
        code, output, _ = run_driver(os.path.join(ROOT, script), args, o, cwd=work)
        other = read_summary(o)
        check(f"{tag}: {label}: the copy's run exits 0", code == 0 and other is not None,
              f"exit {code}: {output.strip().splitlines()[-3:]}")
        if default is None or other is None:
            continue
        check(f"{tag}: {label}: {statistic} in the suite's run, not in the copy's",
              default["solver"].get(statistic, 0) > 0 and statistic not in other["solver"],
              f"{default['solver'].get(statistic)} {other['solver'].get(statistic)}")
        worst, name = 0, ""
        for q, r in default["results"].items():
            a, b = r["computed"], other["results"].get(q, {}).get("computed")
            if q in ("coulomb_violation", "force_balance_rel_error", "max_penetration", "volume_balance_rel_error"):
                continue   # round-off measures, each within its bound below or in the run's own checks
            if b is None or not isinstance(a, (int, float)):
                continue
            d = abs(a - b) / max(abs(a), abs(b), 1e-300)
            if d > worst:
                worst, name = d, q
        check(f"{tag}: {label}: every result the same to 1e-9", worst <= 1e-9, f"{worst:.1e} ({name})")
        for s in (default, other):
            c = s["results"]["coulomb_violation"]["computed"]
            check(f"{tag}: {label}: Coulomb's law to 1e-10", c <= 1e-10, f"{c:.1e}")


# the rubber punch (2D, the condensed SQP, Coulomb's unsymmetric systems) and the rigid sphere (3D, a/5,
# nu 0.5)
PUNCH_AND_RIGID_SPHERE = (
    ("punch", "tests/punch_squeeze.edp", ["-volumetric", "stabilised", "-mu", "0.3"]),
    ("rigid sphere", "benchmarks/mindlin_sphere.edp", ["-setup", "rigid", "-nu", "0.5", "-h", "0.0483", "-steps", "2"]))


def test_polish_dense_kkt():
    """The polish's KKT systems by LAPACK's dense LU (plugin/dense_kkt.cpp, the default) against
    UMFPACK's sparse solve (a copy of the suite with polishDenseEnabled = false), on the punch and the
    rigid sphere: every result the same to the runs' -tol (the same systems to round-off, both refined
    twice, which feeds the next steps' IPOPT solves; measured 9.2e-16 on the punch, 2.3e-13 on the
    sphere), Coulomb's law to round-off in both (same_results_as_copy)."""
    work, planted = planted_suite("polish dense kkt umfpack", "solve/friction_polish.idp",
                                  "bool polishDenseEnabled = true;", "bool polishDenseEnabled = false;")
    check("polish dense kkt: the switch is in the copy", planted)
    same_results_as_copy("polish dense kkt", work, PUNCH_AND_RIGID_SPHERE, "dense_kkt_solves")


def test_site_narrowing():
    """Friction's solve on the rows' and the sites' dofs (solve/site_narrowing.idp, the default) against
    the whole condensed problem (a copy of the suite with siteNarrowingEnabled = false), on the punch and
    the rigid sphere: the dropped dofs are eliminated exactly (a dense Schur complement), so every result
    is the same to the runs' -tol, 1e-9 relative (measured 7.4e-16 on the punch, 2.0e-13 on the sphere), and
    Coulomb's law holds to round-off in both (same_results_as_copy)."""
    work, planted = planted_suite("site narrowing off", "solve/site_narrowing.idp",
                                  "bool siteNarrowingEnabled = true;", "bool siteNarrowingEnabled = false;")
    check("site narrowing: the switch is in the copy", planted)
    same_results_as_copy("site narrowing", work, PUNCH_AND_RIGID_SPHERE, "site_narrowings")


def test_oring_friction():
    """The O-ring between plates with mu = 0.3 (the benchmark, R/24; Neo-Hookean, the condensed SQP):
    Coulomb's law to round-off at every node (bound 1e-12, measured 2.4e-17; 6.6e-6 before Coulomb's
    polish, the SQP's multipliers), one solve a load step but the first contact's two (measured 16 for
    15 steps, 66 before), and friction raises the force at c = 0.2 above the frictionless ring's (the
    flanks held back: +1.7 %)."""
    label = "oring plates mu 0.3"
    s = run_summary(label, "benchmarks/oring.edp", bench_args("oring_plates_friction"))
    plain = run_summary("oring plates mu 0", "benchmarks/oring.edp", ["-case", "plates"])
    if s is None or plain is None:
        return
    r = s["results"]
    check(f"{label}: Coulomb's law at every node to round-off (coulomb_violation <= 1e-12)",
          r["coulomb_violation"]["computed"] <= 1e-12, f"{r['coulomb_violation']['computed']:.1e}")
    steps = len(s["steps"])
    check(f"{label}: one friction solve a load step, two at first contact ({steps + 1} at most)",
          r["friction_solves"]["computed"] <= steps + 1, f"{r['friction_solves']['computed']} for {steps} steps")
    f, f0 = r["force_c0.2"]["computed"], plain["results"]["force_c0.2"]["computed"]
    check(f"{label}: friction raises the force at c = 0.2", f > f0, f"{f:.5f} against {f0:.5f}")
    check(f"{label}: dissipated energy >= 0", r["dissipated_energy"]["computed"] >= 0)


def test_oring_groove_friction_relative():
    """Friction sees only the relative motion of body and obstacle (contact/friction.idp,
    frictionObstacleTravel): the O-ring's groove closes by moving its upper part along the diagonal,
    partly along its own faces, and with mu = 0.3 the four faces must carry the same force, as they
    do without friction (coarse ring: equal to 4.5e-16). Before the obstacles' travel entered the
    slip, the moving faces dragged nothing and the floor and ceiling carried 0.186 and 0.317."""
    label = "oring groove mu 0.3"
    s = run_summary(label, "benchmarks/oring.edp", ["-case", "groove", "-mu", "0.3", "-h", "0.052"])
    if s is None:
        return
    forces = [s["results"][f"{face}_force"]["computed"] for face in ("floor", "wall", "ceiling", "opposite_wall")]
    check(f"{label}: the four faces carry the same force to 1e-10 (measured 4.5e-16; the bound leaves the "
          "solver's path, which need not be symmetric, room)", max(forces) - min(forces) <= 1e-10 * max(forces),
          str(forces))
    c = s["results"]["coulomb_violation"]["computed"]
    check(f"{label}: Coulomb's law to round-off (1e-12; measured 1.8e-16)", c <= 1e-12, f"{c:.1e}")


def test_friction_needs_condensation():
    """Friction is carried by the condensed solve's reduced problem: where it cannot apply (the nodal
    form's exact incompressibility rows, asked for by -volumetric nodal at nu = 0.5, involve every dof;
    the default there is the stabilised form, which condenses) the run refuses with one error line
    naming -mu, exit 2."""
    code, output, _ = run_driver("benchmarks/hertz_plane.edp",
                                 ["-material", "neohookean", "-nu", "0.5", "-volumetric", "nodal", "-mu", "0.3"],
                                 out("friction refused"))
    errors = [l for l in output.splitlines() if l.startswith("error:")]
    check("friction with nu = 0.5, -volumetric nodal: exit 2", code == 2, f"exit {code}")
    check("friction with nu = 0.5, -volumetric nodal: one error line naming -mu", len(errors) == 1 and "-mu" in errors[0], str(errors))


def test_punch_squeeze():
    """Issue 40's punch case (tests/punch_squeeze.edp: a Neo-Hookean section, nu 0.499, squeezed 20 %
    between a rigid punch and floor with mu 0.4, the half model at h = 0.05) failed near full load
    with square()'s default diagonals and ran with flags=1. Both complete now with their own checks
    (balance, penetration, Coulomb's law), and their punch forces differ by less than the mesh's own
    error, measured as the change of the flags=1 force from h = 0.1 to h = 0.05."""
    forces = {}
    for flags, h in (("0", "0.05"), ("1", "0.05"), ("1", "0.1")):
        label = f"punch squeeze flags {flags} h {h}"
        s = run_summary(label, "tests/punch_squeeze.edp", ["-flags", flags, "-h", h])
        if s is None:
            continue
        check(f"{label}: no failed check", s["checks_failed"] == [], str(s["checks_failed"]))
        check(f"{label}: Coulomb's law at every node (1e-8, the run's own gate)",
              s["results"].get("coulomb_violation", {}).get("computed", 1) <= 1e-8,
              str(s["results"].get("coulomb_violation")))
        forces[(flags, h)] = s["results"]["punch_force"]["computed"]
        # the warm polish: reduced problems solved on the last solve's active set, without IPOPT
        # (measured 17 of 25 at mu 0.3; the friction tests' answers are its check)
        check(f"{label}: some reduced problems solved by the warm polish", s["solver"].get("warm_polishes", 0) > 0,
              str(s["solver"].get("warm_polishes")))
    if len(forces) == 3:
        diagonals = abs(forces[("0", "0.05")] - forces[("1", "0.05")])
        mesh = abs(forces[("1", "0.05")] - forces[("1", "0.1")])
        check("punch squeeze: the two meshes' forces within the mesh's own error", diagonals <= mesh,
              f"|F(flags 0) - F(flags 1)| = {diagonals:.3e}, |F(h) - F(2h)| = {mesh:.3e}")


@pytest.mark.parametrize("label, args", [("patch test", []), ("patch test mu 0.3", ["-mu", "0.3"])],
                         ids=["frictionless", "mu0.3"])
def test_patch_test(label, args):
    """The contact patch test (issue 28): two blocks with non-matching meshes pressed by a uniform
    pressure. Two-pass pairs transmit it exactly, with and without friction: the traction uniform and
    the stress exact within the verdicts' 1e-6 (measured 5e-10); one pass fails it (a spread of 36 %
    measured: the check holds it above 10 %, so the docs' statement stays true)."""
    s = run_summary(label, "benchmarks/patch_test.edp", args)
    if s is None:
        return
    r = s["results"]
    for q in ("pressure_spread", "stress_error_rel"):
        bound = verdicts.bound("patch_test", q)
        check(f"{label}: {q} <= {bound:.0e}", r[q]["computed"] <= bound, f"{r[q]['computed']:.1e}")
    check(f"{label}: the mean traction is p (1e-8)", r["pressure_mean"]["rel_error"] <= 1e-8, f"{r['pressure_mean']['rel_error']:.1e}")


def test_patch_test_single_pass():
    """test_patch_test's one-pass pairs: they fail the patch test (a spread above 10 %)."""
    s = run_summary("patch test single pass", "benchmarks/patch_test.edp", ["-pass", "single"])
    if s is not None:
        check("patch test: one pass fails it (spread above 10 %)", s["results"]["pressure_spread"]["computed"] > 0.1,
              f"{s['results']['pressure_spread']['computed']:.3f}")


def test_tresca():
    """Tresca's friction (-friction tresca -g TAU): the bound is given, so one solve per step; where a
    node slips its shear traction is TAU, nowhere is it above (1e-8 of TAU; measured 2e-16)."""
    label = "tresca"
    s = run_summary(label, "benchmarks/hertz_plane.edp", ["-friction", "tresca", "-g", "1e6"])
    if s is None:
        return
    r = s["results"]
    check(f"{label}: one friction solve (the bounds are known)", r["friction_solves"]["computed"] == 1, str(r["friction_solves"]["computed"]))
    check(f"{label}: Coulomb's check (1e-8)", r["coulomb_violation"]["computed"] <= 1e-8, f"{r['coulomb_violation']['computed']:.1e}")
    rows = friction_rows(label)
    slipping = [abs(float(row["shear"])) for row in rows if row["status"] == "slip"]
    check(f"{label}: slipping nodes carry |q| = TAU (1e-8)", slipping and max(abs(q - 1e6) for q in slipping) <= 1e-8 * 1e6,
          f"{len(slipping)} nodes")
    check(f"{label}: no node above TAU", all(abs(float(row["shear"])) <= 1e6 * (1 + 1e-8) for row in rows))
