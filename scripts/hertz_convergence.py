#!/usr/bin/env python3
"""`make convergence`: the Hertz benchmarks refined from h = a/10 to a/160 (element size in
the contact zone, a = Hertz's half-width). Prints one line per run and a table of DOFs,
IPOPT iterations, errors of a, p_max and the L2 error of p against Hertz, and wall time;
writes it to results/hertz_convergence.md.
Usage: scripts/hertz_convergence.py [--levels 10,20,40,80,160] [--cases plane,circle_vertical,circle_exact]"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from freefem import ROOT, read_summary, run_driver  # noqa: E402
import md_tables  # noqa: E402

CASES = {
    "plane": ("benchmarks/hertz_plane.edp", [], 2.75e6, 2.1e9, 1.0),
    "circle_vertical": ("benchmarks/hertz_circle.edp", ["-constraint", "vertical"], 250.0, 2.1e5, 1.2 / 2.2),
    "circle_linearized": ("benchmarks/hertz_circle.edp", ["-constraint", "linearized"], 250.0, 2.1e5, 1.2 / 2.2),
    "circle_exact": ("benchmarks/hertz_circle.edp", ["-constraint", "exact"], 250.0, 2.1e5, 1.2 / 2.2),
}


def hertz_a(f, E, R, nu=0.3, R1=1.0):
    return math.sqrt(8 * f * R1 * R * (1 - nu ** 2) / (math.pi * E))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--levels", default="10,20,40,80,160", help="a/h values")
    parser.add_argument("--cases", default="plane,circle_vertical,circle_exact")
    args = parser.parse_args()
    levels = [int(v) for v in args.levels.split(",")]
    rows, failed = [], 0
    for case in args.cases.split(","):
        script, extra, f, E, R = CASES[case]
        a = hertz_a(f, E, R)
        for level in levels:
            out_dir = os.path.join("results", "convergence", f"{case}_a{level}")
            print(f"{case} h = a/{level}: running", flush=True)
            code, output, seconds = run_driver(script, extra + ["-h", repr(a / level)], out_dir)
            s = read_summary(out_dir)
            if code != 0 or s is None:
                failed += 1
                print("    " + "\n    ".join(output.strip().splitlines()[-3:]), flush=True)
                continue
            r = s["results"]
            row = (case, f"a/{level}", s["ndof"], s["ipopt_iterations"], r["a"]["rel_error"],
                   r["p_max"]["rel_error"], r["pressure_l2_rel_error"]["computed"],
                   r["force_balance_rel_error"]["computed"], s["wall_time_s"])
            rows.append(row)
            print(f"{case} h = a/{level}: {row[2]} dofs, {row[3]} iterations, a {row[4]:.2e}, p_max {row[5]:.2e}, "
                  f"L2 {row[6]:.2e}, {seconds:.1f} s", flush=True)
    header = ("case", "h", "DOFs", "IPOPT it.", "a rel. error", "p_max rel. error", "L2(p) rel. error",
              "force balance", "time (s)")
    table = md_tables.table(header, [(c, h, n, it, f"{ea:.2e}", f"{ep:.2e}", f"{el:.2e}", f"{fb:.0e}", f"{t:.1f}")
                                    for c, h, n, it, ea, ep, el, fb, t in rows])
    print("\n" + table)
    md_tables.write(os.path.join(ROOT, "results", "hertz_convergence.md"), "Hertz convergence", table)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
