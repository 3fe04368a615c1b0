"""The solve paths and their failures: the condensed path against IPOPT on the whole problem, step cuts, IPOPT failures, unreachable tolerances, errors inside callbacks, the fold guard, the hard cases."""

import pytest

from helpers import *  # noqa: F401,F403 (check, out, run_driver, read_summary, ROOT, TMP and the shared helpers)


@pytest.mark.heavy(seconds=44)
def test_condensed_path():
    """The condensed solve (include/solve/condensation.idp and the files after it) against the full KKT path on the same
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
              0 < condensed["solver"].get("condensed_dofs", 0) < condensed["ndof"] / 5
              and "condensed_dofs" not in full["solver"],
              f"{condensed['solver'].get('condensed_dofs')} of {condensed['ndof']}")
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
              "condensed_dofs" in oring["auto"]["solver"] and "condensed_dofs" not in oring["no"]["solver"])
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
                  cube["yes"]["solver"].get("condensed_dofs") == 0
                  and "factor_entries_per_unknown" in cube["yes"]["solver"] and "condensed_dofs" not in cube["no"]["solver"])
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
