#!/usr/bin/env python3
"""Reference values for benchmarks/clamped_square.edp, which has no analytic solution: a
mesh-convergence study with P2 on n = 25, 50, 100, 200 elements per side, Richardson
extrapolation from the three finest levels where the quantity converges monotonically, and a
P1 run on the finest mesh as a cross-check. Writes benchmarks/reference/clamped_square.json (values,
error estimates, every run) and prints the table. Takes a few minutes on 2 cores:
    python3 scripts/clamped_square_reference.py"""

import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from freefem import ROOT, read_summary, run_driver  # noqa: E402

QUANTITIES = ["contact_force", "centre_of_pressure_y", "separation_y", "pressure_at_y0.7",
              "pressure_at_y0.8", "pressure_at_y0.9", "pressure_at_y0.95", "clamp_reaction_x"]
LEVELS = [25, 50, 100, 200]
CROSS_CHECK = (1, 200)


def run(order, n):
    out_dir = os.path.join("results", "clamped_square_study", f"P{order}_n{n}")
    print(f"P{order} n = {n}: running", flush=True)
    code, output, seconds = run_driver("benchmarks/clamped_square.edp", ["-order", str(order), "-n", str(n)], out_dir)
    s = read_summary(out_dir)
    if code != 0 or s is None:
        sys.exit(f"P{order} n = {n} failed:\n" + "\n".join(output.strip().splitlines()[-3:]))
    values = {q: s["results"][q]["computed"] for q in QUANTITIES}
    print(f"P{order} n = {n}: {s['ndof']} dofs, {s['ipopt_iterations']} iterations, {seconds:.1f} s", flush=True)
    return {"order": order, "n": n, "ndof": s["ndof"], "iterations": s["ipopt_iterations"],
            "time_s": round(seconds, 2), "values": values}


def extrapolate(q1, q2, q3):
    """Richardson from three levels halving h: (value, observed order or None, error estimate)."""
    d1, d2 = q2 - q1, q3 - q2
    if d1 != 0 and d2 != 0 and d1 * d2 > 0 and abs(d2) < abs(d1):
        p = math.log2(d1 / d2)
        value = q3 + d2 / (2 ** p - 1)
        return value, p, abs(value - q3)
    return q3, None, abs(d2)       # not in the asymptotic range: finest value, last change as error


def main():
    runs = [run(2, n) for n in LEVELS] + [run(*CROSS_CHECK)]
    p2 = runs[:len(LEVELS)]
    reference = {}
    for q in QUANTITIES:
        value, order, error = extrapolate(*(r["values"][q] for r in p2[-3:]))
        reference[q] = {"value": value, "observed_order": order, "error_estimate": error,
                        "p1_fine": runs[-1]["values"][q]}
    data = {"command": "python3 scripts/clamped_square_reference.py",
            "note": "P2 on n = 25..200 elements per side; Richardson from the three finest levels where "
                    "monotone, else the finest value with its last change as error estimate; "
                    "p1_fine: P1 on n = 200",
            "reference": reference, "runs": runs}
    os.makedirs(os.path.join(ROOT, "benchmarks", "reference"), exist_ok=True)
    with open(os.path.join(ROOT, "benchmarks", "reference", "clamped_square.json"), "w") as f:
        json.dump(data, f, indent=1)
    head = "| quantity | " + " | ".join(f"P2 n={n}" for n in LEVELS) + " | P1 n=200 | reference | order | error est. |"
    print(head + "\n|" + "---|" * (len(LEVELS) + 5))
    for q in QUANTITIES:
        r = reference[q]
        cells = " | ".join(f"{x['values'][q]:.6g}" for x in p2)
        order = "-" if r["observed_order"] is None else f"{r['observed_order']:.2f}"
        print(f"| {q} | {cells} | {r['p1_fine']:.6g} | {r['value']:.7g} | {order} | {r['error_estimate']:.1e} |")


if __name__ == "__main__":
    main()
