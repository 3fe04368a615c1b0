"""Dynamics (issue 29): implicit time steps as constrained minimisations, against wave theory (the bar
against a wall) and the conservation laws of a free flight."""

import pytest

from helpers import *  # noqa: F401,F403 (check, out, run_driver, read_summary, ROOT, TMP and the shared helpers)

import benchmark_list  # noqa: E402
from freefem import run_ok  # noqa: E402

BAR = "benchmarks/bar_impact.edp"


def test_bar_impact():
    """The default bar (Code_Aster SDNV100, n = 400, Newmark, mass redistributed off the contact
    nodes): contact duration, mean contact stress, rebound velocity, the energy after separation
    within the verdicts' bounds of wave theory; the equilibrium with inertia at every step (1e-8),
    no penetration; history.csv, the .pvd series and its frames; a progress line per printed step."""
    label = "bar impact"
    code, output, _ = run_driver(BAR, [], out(label))
    s = read_summary(out(label))
    check(f"{label}: exit 0", code == 0 and s is not None, f"exit {code}: {output.strip().splitlines()[-2:]}")
    if s is None:
        return
    check(f"{label}: summary.json says complete (what make's runner reads)", s["complete"] is True and run_ok(code, s))
    r = s["results"]
    for q in ("contact_duration", "mean_contact_stress", "rebound_velocity", "energy_ratio", "impact_time"):
        bound = verdicts.bound("bar_impact", q)
        check(f"{label}: {q} within {bound:.0e} of wave theory", r[q]["rel_error"] <= bound, f"{r[q]['rel_error']:.2e}")
    check(f"{label}: equilibrium with inertia at every step (1e-8 of the largest term)",
          r["dynamics_balance_rel_error"]["computed"] <= 1e-8, f"{r['dynamics_balance_rel_error']['computed']:.1e}")
    check(f"{label}: no penetration (1e-10 of the bar)", r["max_penetration"]["computed"] <= 1e-10 * 0.2)
    rows = list(csv.DictReader(open(os.path.join(out(label), "history.csv"))))
    check(f"{label}: history.csv has a row per step and the documented columns",
          len(rows) == r["time_steps"]["computed"] and list(rows[0]) == ["time", "contact_force", "kinetic", "elastic", "external_work",
                                                                         "total", "probe_displacement", "probe_velocity", "balance"])
    pvd = os.path.join(out(label), "bar_impact.pvd")
    frames = re.findall(r'file="([^"]+)"', open(pvd).read()) if os.path.exists(pvd) else []
    check(f"{label}: bar_impact.pvd lists every 10th step's frame, and each exists",
          len(frames) == -(-int(r["time_steps"]["computed"]) // 10) and all(os.path.exists(os.path.join(out(label), f)) for f in frames),
          f"{len(frames)} frames")
    check(f"{label}: a progress line per printed step (time, contact force, energies)",
          len(re.findall(r"^t = [\d.e+-]+ us: contact force", output, re.M)) == len(frames))


@pytest.mark.parametrize("name", ["sphere_impact", "sphere_impact_rubber", "sphere_impact_incompressible",
                                  "sphere_impact_neohookean"])
def test_sphere_impact(name):
    """A steel sphere (linear, and Neo-Hookean: the condensed SQP in every step) and a rubber-like one
    (nu = 0.499, the nodal form; and nu = 0.5, the nodal form's rows) against a rigid wall
    (axisymmetric, Newmark, redistributed mass): Hertz's contact time and peak force within the
    verdicts' 3 % (measured 1.5 % and 1.1 %; Neo-Hookean 1.0 % and 0.96 %; rubber 1.5 % and 1.6 %; at
    nu = 0.5 1.5 % and 1.8 %), the sphere back at v0 and its energy kept (1e-3; measured 2e-6 to 3e-5),
    the equilibrium with inertia at every step (with the pressure's nodal forces at nu = 0.5)."""
    args = next(a for n, _, a in benchmark_list.BENCHMARKS if n == name)
    s = run_summary(name, "benchmarks/sphere_impact.edp", args + ["-every", "0"])
    if s is None:
        return
    r = s["results"]
    check(f"{name}: summary.json says complete", s["complete"] is True)
    for q in ("contact_time", "peak_force", "rebound_velocity", "energy_ratio"):
        bound = verdicts.bound(name if name != "sphere_impact_neohookean" else "sphere_impact", q)
        check(f"{name}: {q} within {bound:.0e} of Hertz's impact", r[q]["rel_error"] <= bound, f"{r[q]['rel_error']:.2e}")
    check(f"{name}: equilibrium with inertia at every step (1e-8)", r["dynamics_balance_rel_error"]["computed"] <= 1e-8,
          f"{r['dynamics_balance_rel_error']['computed']:.1e}")
    check(f"{name}: no penetration", r["max_penetration"]["computed"] <= 1e-10 * 0.02)


@pytest.mark.heavy(seconds=100)
def test_sphere_impact_rubber_neohookean():
    """The rubber-like sphere with a Neo-Hookean law in the nodal form (the condensed SQP on the coupled
    tangent, inertia added; axisymmetric) at dt = t_c / 100: Hertz within the verdicts' bounds (measured
    2.0 % and 1.5 %; at the default t_c / 200 1.5 % and 1.5 %), the equilibrium with inertia at every step."""
    rubber = next(a for n, _, a in benchmark_list.BENCHMARKS if n == "sphere_impact_rubber")
    s = run_summary("sphere impact rubber neohookean", "benchmarks/sphere_impact.edp",
                    rubber + ["-material", "neohookean", "-dt", "5.3266e-5", "-every", "0"])
    if s is not None:
        r = s["results"]
        for q in ("contact_time", "peak_force", "rebound_velocity", "energy_ratio"):
            bound = verdicts.bound("sphere_impact_rubber", q)
            check(f"sphere impact rubber neohookean: {q} within {bound:.0e} of Hertz's impact", r[q]["rel_error"] <= bound,
                  f"{r[q]['rel_error']:.2e}")
        check("sphere impact rubber neohookean: equilibrium with inertia at every step (1e-8)",
              r["dynamics_balance_rel_error"]["computed"] <= 1e-8, f"{r['dynamics_balance_rel_error']['computed']:.1e}")


@pytest.mark.heavy(seconds=43)
def test_sphere_impact_3d_rubber_neohookean():
    """The rubber-like sphere in 3D with a Neo-Hookean law in the nodal form (the condensed SQP on the
    saddle point matrix, inertia added, pressures scaled: body/volumetric.idp, saddlePressureScales),
    on a coarse mesh (h = 1.2e-4 = a_max / 2.5) at dt = t_c / 100. Unscaled, this run's first step's
    SQP stalled (25 iterations, exit 3). Against Hertz: the peak force within the verdicts' 3 %
    (measured 0.57 %), the sphere back at v0 and its energy kept; the equilibrium with inertia at every
    step (1e-8). An independent path: the linear law's nodal form (no SQP: one reduced problem a step)
    on the same mesh and steps. The two laws differ by a fraction of the contact's strain (a_max / R
    = 0.03); measured: peak forces 0.09 % apart (the axisymmetric runs: 0.1 %), the same contact time;
    bounds 0.3 % (a tenth of the strain) and one step. (The contact time against Hertz, 4.0 %
    here, is the coarse mesh's: the linear law's is the same.)"""
    rubber = next(a for n, _, a in benchmark_list.BENCHMARKS if n == "sphere_impact_rubber")
    coarse = ["-dim", "3", "-h", "1.2e-4", "-hmax", "0.003", "-zone", "9e-4", "-dt", "5.3266e-5", "-every", "0"]
    label = "sphere impact 3D rubber neohookean"
    s = run_summary(label, "benchmarks/sphere_impact.edp", rubber + coarse + ["-material", "neohookean"])
    linear = run_summary("sphere impact 3D rubber linear", "benchmarks/sphere_impact.edp", rubber + coarse)
    if s is None:
        return
    r = s["results"]
    for q in ("peak_force", "rebound_velocity", "energy_ratio"):
        bound = verdicts.bound("sphere_impact_rubber", q)
        check(f"{label}: {q} within {bound:.0e} of Hertz's impact", r[q]["rel_error"] <= bound, f"{r[q]['rel_error']:.2e}")
    check(f"{label}: equilibrium with inertia at every step (1e-8)", r["dynamics_balance_rel_error"]["computed"] <= 1e-8,
          f"{r['dynamics_balance_rel_error']['computed']:.1e}")
    check(f"{label}: no penetration", r["max_penetration"]["computed"] <= 1e-10 * 0.02)
    if linear:
        f, fl = r["peak_force"]["computed"], linear["results"]["peak_force"]["computed"]
        check(f"{label}: the linear law's peak force within 0.3 %", abs(f - fl) <= 3e-3 * fl, f"{f:.6g} vs {fl:.6g}")
        t, tl = r["contact_time"]["computed"], linear["results"]["contact_time"]["computed"]
        check(f"{label}: the linear law's contact time within one step", abs(t - tl) <= 5.3266e-5 * (1 + 1e-9), f"{t:.6g} vs {tl:.6g}")


@pytest.mark.heavy(seconds=41)
def test_sphere_impact_3d():
    """The 3D quarter sphere (-dim 3) on a coarser mesh and step (h = a_max / 6, dt = t_c / 100): Hertz
    within the verdicts' bounds (measured 2.0 % and 1.3 %), and the default axisymmetric run's peak
    force within 1 % (an independent path: measured 0.2 %) and its contact time within two of the 3D
    run's steps."""
    args = next(a for n, _, a in benchmark_list.BENCHMARKS if n == "sphere_impact")
    axi = run_summary("sphere impact axisymmetric, for 3D", "benchmarks/sphere_impact.edp", args + ["-every", "0"])
    s = run_summary("sphere impact 3D", "benchmarks/sphere_impact.edp", ["-dim", "3", "-h", "2.8e-5", "-dt", "8.306e-7", "-every", "0"])
    if s is not None:
        r = s["results"]
        for q in ("contact_time", "peak_force", "rebound_velocity", "energy_ratio"):
            bound = verdicts.bound("sphere_impact_3d", q)
            check(f"sphere impact 3D: {q} within {bound:.0e} of Hertz's impact", r[q]["rel_error"] <= bound, f"{r[q]['rel_error']:.2e}")
        check("sphere impact 3D: equilibrium with inertia at every step (1e-8)", r["dynamics_balance_rel_error"]["computed"] <= 1e-8)
        check("sphere impact 3D: no penetration", r["max_penetration"]["computed"] <= 1e-10 * 0.02)
        if axi:
            f3, fa = r["peak_force"]["computed"], axi["results"]["peak_force"]["computed"]
            check("sphere impact 3D: the axisymmetric run's peak force within 1 %", abs(f3 - fa) <= 1e-2 * fa, f"{f3:.6g} vs {fa:.6g}")
            t3, ta = r["contact_time"]["computed"], axi["results"]["contact_time"]["computed"]
            check("sphere impact 3D: the axisymmetric run's contact time within two 3D steps", abs(t3 - ta) <= 2 * 8.306e-7, f"{t3:.6g} vs {ta:.6g}")


def test_bars_head_on():
    """Two equal bars meeting head on (a contact pair between two bodies, the mass redistributed off
    both sides' contact nodes): the velocities exchanged within the verdicts' 2 % (measured 1.1 %),
    the contact for 2 L / c, the total momentum kept to 1e-10 of a bar's (measured 3.8e-13), the
    energy after separation to 1e-3 (measured 6.5e-5)."""
    s = run_summary("bars head on", "benchmarks/bars_head_on.edp", ["-every", "0"])
    if s is None:
        return
    r = s["results"]
    check("bars head on: summary.json says complete", s["complete"] is True)
    for q in ("velocity_A_after", "velocity_B_after", "contact_duration", "energy_ratio"):
        bound = verdicts.bound("bars_head_on", q)
        check(f"bars head on: {q} within {bound:.0e}", r[q]["rel_error"] <= bound, f"{r[q]['rel_error']:.2e}")
    check("bars head on: momentum kept (1e-10 of a bar's)", r["momentum_drift_rel"]["computed"] <= 1e-10,
          f"{r['momentum_drift_rel']['computed']:.1e}")
    check("bars head on: equilibrium with inertia at every step (1e-8)", r["dynamics_balance_rel_error"]["computed"] <= 1e-8)


def test_discs_head_on():
    """Two equal discs meeting head on (plane strain halves, a contact pair between curved surfaces,
    Newmark with the mass off both sides' contact nodes): the velocities exchanged within the
    verdicts' 1 % (measured 0.67 %: 1.3 % of the energy stays in the discs' vibrations, the contact
    lasting about a period of the discs' lowest mode), the energy after separation to 1e-3 (measured
    7.5e-5), the total momentum kept to 1e-10 of a disc's (measured 1.0e-13, the issue's 1e-10)."""
    s = run_summary("discs head on", "benchmarks/discs_head_on.edp", ["-every", "0"])
    if s is None:
        return
    r = s["results"]
    check("discs head on: summary.json says complete", s["complete"] is True)
    for q in ("velocity_A_after", "velocity_B_after", "energy_ratio"):
        bound = verdicts.bound("discs_head_on", q)
        check(f"discs head on: {q} within {bound:.0e}", r[q]["rel_error"] <= bound, f"{r[q]['rel_error']:.2e}")
    check("discs head on: A moves up after, B down", r["velocity_A_after"]["computed"] > 0 > r["velocity_B_after"]["computed"])
    check("discs head on: momentum kept (1e-10 of a disc's)", r["momentum_drift_rel"]["computed"] <= 1e-10,
          f"{r['momentum_drift_rel']['computed']:.1e}")
    check("discs head on: equilibrium with inertia at every step (1e-8)", r["dynamics_balance_rel_error"]["computed"] <= 1e-8)
    check("discs head on: no penetration", r["max_penetration"]["computed"] <= 1e-10 * 0.01)


def check_spheres_head_on(label, name, s):
    """The checks of two spheres head on (benchmark `name`'s verdicts): Hertz's impact, the velocities
    exchanged, the energy and the momentum kept, the balance with inertia, no penetration."""
    r = s["results"]
    check(f"{label}: summary.json says complete", s["complete"] is True)
    for q in ("contact_time", "peak_force", "velocity_A_after", "velocity_B_after", "energy_ratio"):
        bound = verdicts.bound(name, q)
        check(f"{label}: {q} within {bound:.0e}", r[q]["rel_error"] <= bound, f"{r[q]['rel_error']:.2e}")
    check(f"{label}: momentum kept (1e-10 of a sphere's)", r["momentum_drift_rel"]["computed"] <= 1e-10,
          f"{r['momentum_drift_rel']['computed']:.1e}")
    check(f"{label}: equilibrium with inertia at every step (1e-8)", r["dynamics_balance_rel_error"]["computed"] <= 1e-8)
    check(f"{label}: no penetration", r["max_penetration"]["computed"] <= 1e-10 * 0.01)


def test_spheres_head_on():
    """Two equal steel spheres meeting head on at 0.1 m/s each (discs_head_on.edp -dim axi: the
    meridian halves, a contact pair, Newmark with the mass off both sides' contact nodes): Hertz's
    impact of the pair (relative velocity 2 v0, reduced mass m / 2, radius R / 2, modulus
    E / (2 (1 - nu^2)): the same contact time as one sphere against a rigid wall) within the verdicts'
    3 % (measured 1.5 % and 0.99 %), the velocities exchanged and the energy kept to 1e-3 (measured
    5.2e-6 and 6e-7), the total momentum to 1e-10 of a sphere's (measured 5.0e-13)."""
    args = next(a for n, _, a in benchmark_list.BENCHMARKS if n == "spheres_head_on")
    s = run_summary("spheres head on", "benchmarks/discs_head_on.edp", args + ["-every", "0"])
    if s is not None:
        check_spheres_head_on("spheres head on", "spheres_head_on", s)


@pytest.mark.heavy(seconds=70)
def test_spheres_head_on_3d():
    """The two spheres in 3D (discs_head_on.edp -dim 3: each sphere's quarter on its symmetry planes, a
    3D contact pair between their surfaces; h = a_max / 4.2): Hertz within the verdicts' 3 % (measured
    2.0 % and 1.5 %), the velocities exchanged and the energy kept to 1e-3 (measured 5.8e-6 and 3.7e-7),
    the momentum to 1e-10 (measured 9.7e-14); the mesh two bodies (summed apart: summed 1 um apart,
    FreeFEM welded the poles and the spheres came apart at 0.065 m/s, 57 % of the energy vibrating).
    An independent path, the axisymmetric run: the peak force within 1 % (measured 0.53 %), the
    contact time within two steps."""
    args = next(a for n, _, a in benchmark_list.BENCHMARKS if n == "spheres_head_on_3d")
    axi_args = next(a for n, _, a in benchmark_list.BENCHMARKS if n == "spheres_head_on")
    label = "spheres head on 3D"
    s = run_summary(label, "benchmarks/discs_head_on.edp", args + ["-every", "0"])
    axi = run_summary("spheres head on axisymmetric, for 3D", "benchmarks/discs_head_on.edp", axi_args + ["-every", "0"])
    if s is None:
        return
    check_spheres_head_on(label, "spheres_head_on_3d", s)
    if axi:
        r = s["results"]
        f3, fa = r["peak_force"]["computed"], axi["results"]["peak_force"]["computed"]
        check(f"{label}: the axisymmetric run's peak force within 1 %", abs(f3 - fa) <= 1e-2 * fa, f"{f3:.6g} vs {fa:.6g}")
        t3, ta = r["contact_time"]["computed"], axi["results"]["contact_time"]["computed"]
        dt = s["parameters"]["dt"]
        check(f"{label}: the axisymmetric run's contact time within two steps", abs(t3 - ta) <= 2 * dt * (1 + 1e-9),
              f"{t3:.6g} vs {ta:.6g}")


def test_free_flight():
    """No contact (the wall 1 m away), the bar flying and vibrating (-profile ramp): Newmark keeps the
    momentum to the issue's 1e-12 (measured 6.5e-13 over 581 steps) and, for linear elasticity, the
    energy to 1e-11 (the issue's 1e-10; measured 9.7e-13). Both are round-off floors that grow with
    the steps, not the solver's tolerance: each step solves for its increment from the predictor, the
    inertia force is w M (U - Upred) and the stored energy is evaluated without the translation (1e5
    times the deformation here); what is left is the rounding of U, stored whole (n = 400, 2,321
    steps: 1.0e-12 and 1.5e-12). Before, w M U - w M Upred cancelled to 1e-16 of w M Upred: 3.6e-11
    and 5.4e-11. Backward Euler dissipates: its energy falls. No impact: the run says so (exit 4,
    impact_over its one failed check, issue 42) and reports its quantities without references."""
    for label, extra in (("free flight", []), ("free flight euler", ["-scheme", "euler"])):
        o = out(label)
        args = ["-profile", "ramp", "-gap", "1", "-tend", "2e-4", "-every", "0", "-n", "100"]
        args += extra
        code, output, _ = run_driver(BAR, args, o)
        s = read_summary(o)
        check(f"{label}: exit 4, impact_over the only failed check, no result against a reference",
              code == 4 and s is not None and s["checks_failed"] == ["impact_over"]
              and all(q["reference"] is None for q in s["results"].values()),
              f"exit {code}; {error_lines(output)}")
        if s is None:
            continue
        r = s["results"]
        momentum = r["momentum_change_rel"]["computed"]
        check(f"{label}: momentum kept (1e-12)", momentum <= 1e-12, f"{momentum:.1e}")
        if extra:
            ratio = r["energy_ratio"]["computed"]
            check("free flight, Euler: the energy falls (numerical dissipation)", ratio < 1 - 1e-3,
                  f"{ratio:.4f}")
        else:
            change = r["energy_change_rel"]["computed"]
            check("free flight: energy kept (1e-11)", change <= 1e-11, f"{change:.1e}")
            check("free flight: no contact", r["contact_duration"]["computed"] == 0)


def test_bar_impact_3d_against_2d():
    """The same bar as a 3D mesh of tetrahedra (-dim 3, a W x W section) and as the plane-strain
    triangles (both uniaxial: the lateral displacements blocked), n = 100: an independent path through
    the 3D mass, energy and contact. The rebound velocities agree to 1e-4 (measured 6e-5), the mean
    contact stresses to 1e-4 (3e-5)."""
    two = run_summary("bar 2d n100", BAR, ["-n", "100", "-every", "0"])
    three = run_summary("bar 3d n100", BAR, ["-n", "100", "-every", "0", "-dim", "3"])
    if two is None or three is None:
        return
    for q in ("rebound_velocity", "mean_contact_stress"):
        a, b = two["results"][q]["computed"], three["results"][q]["computed"]
        check(f"bar 3D against 2D: {q} agree to 1e-4", abs(a - b) <= 1e-4 * abs(a), f"{a} {b}")
    check("bar 3D: equilibrium with inertia at every step (1e-8)", three["results"]["dynamics_balance_rel_error"]["computed"] <= 1e-8)
    check("bar 3D: summary.json says complete", three["complete"] is True)
