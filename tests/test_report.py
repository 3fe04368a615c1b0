"""The report, the verdict table and make bench at its smallest."""

from helpers import *  # noqa: F401,F403 (check, out, run_driver, read_summary, ROOT, TMP and the shared helpers)


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
