#!/usr/bin/env python3
"""`make bench`'s runs on several processes (docs/scaling.md): the 3D Hertz sphere, condensed, and
the 3D rubber indentation (the nodal form's condensed SQP), each as
1 process x 1 thread (FreeFem++), 2 processes x 1 thread (mpirun -np 2 FreeFem++-mpi: MUMPS's
factorization shared by MPI) and 1 process x 2 threads (FreeFem++, two OpenBLAS threads), with
each run's factorization phases, wall time, peak memory of every process (GNU time around each) and
MUMPS's own entries in the factors and flops per process: the sphere at 67k, 201k and 508k DOFs,
the indentation at 85k.
Results in scaling.json, SCALING.md and scaling.png in results/performance (--out).
    scripts/performance/scaling.py [--levels 24,36,50] [--rubber-levels 32] [--layouts 1x1,2x1,1x2]
                                   [--out results/performance]"""

import argparse
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))   # scripts/
from freefem import MPIRUN, ROOT, read_summary  # noqa: E402
import md_tables  # noqa: E402

A_SPHERE = 0.1005577   # Hertz radius of the default hertz_sphere (m): h = a / level
LAYOUTS = {"1x1": (1, 1), "2x1": (2, 1), "1x2": (1, 2)}   # processes x threads
# the cases: driver, its arguments at a level, the answer compared across layouts
CASES = {"sphere": ("benchmarks/hertz_sphere.edp", lambda level: ["-h", repr(A_SPHERE / level)], "a"),
         # 3D rubber: the nodal form's saddle point matrix factorized at every SQP iteration (h = R/level)
         "indentation": ("benchmarks/indentation.edp", lambda level: ["-dim", "3", "-h", repr(1.0 / level)], "force")}


def layout_run(case, level, layout, out_dir):
    """The case at h = size/level as `layout`; a row of measurements, or None when it failed."""
    script, arguments, answer = CASES[case]
    processes, threads = LAYOUTS[layout]
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OPENBLAS_NUM_THREADS=str(threads))
    # each process's GNU time appends its one line to a file beside the output folder, not to the
    # output mpirun forwards from the ranks: a fresh machine's run under load once came back with no
    # whole "RANK_PEAK" line in it (the line a rank writes as it exits: lost or interleaved), and the
    # study stopped at "max() arg is an empty sequence"
    peak_file = os.path.join(ROOT, out_dir) + "_rank_peaks.txt"
    os.makedirs(os.path.dirname(peak_file), exist_ok=True)
    if os.path.exists(peak_file):
        os.remove(peak_file)
    timed = ["/usr/bin/time", "-a", "-o", peak_file, "-f", "RANK_PEAK %e %M"]
    driver = ["-nw", script] + arguments(level) + ["-out", out_dir]
    if processes == 1:
        command = timed + ["FreeFem++"] + driver
    else:   # GNU time around each process; OpenMPI passes the thread counts on with -x
        command = MPIRUN + [str(processes), "-x", "OMP_NUM_THREADS", "-x", "OPENBLAS_NUM_THREADS"] + timed + ["FreeFem++-mpi"] + driver
    proc = subprocess.run(command, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    s = read_summary(out_dir)
    peaks = re.findall(r"RANK_PEAK ([\d.]+) (\d+)", open(peak_file).read()) if os.path.exists(peak_file) else []
    if proc.returncode != 0 or s is None or not s.get("complete") or len(peaks) != processes:
        print(f"{case} 1/{level} {layout}: FAILED (exit {proc.returncode})\n" + proc.stdout[-800:], flush=True)
        return None
    r, solver = s["results"], s["solver"]
    row = {"case": case, "level": level, "layout": layout, "processes": s["mpi_processes"], "ndof": s["ndof"],
           "wall_s": max(float(p[0]) for p in peaks), "rss_mb_per_process": [int(p[1]) / 1024 for p in peaks],
           "ordering_s": solver["condensation_ordering_s"], "analysis_s": solver["condensation_analysis_s"],
           "factorization_s": solver["condensation_factorization_s"],
           "factorizations": s["timings"]["factorizations"], "all_factorizations_s": solver["factorization_time_s"],
           "entries_per_process": s["factor_entries_per_process"], "flops_per_process": s["factor_flops_per_process"],
           "answer_name": answer, "answer": r[answer]["computed"], "iterations": s["ipopt_iterations"]}
    print(f"{case} 1/{level} {layout}: {row['ndof']} dofs, {row['factorizations']} factorizations in {row['all_factorizations_s']:.2f} s, "
          f"wall {row['wall_s']:.1f} s, RSS {'/'.join(f'{m:.0f}' for m in row['rss_mb_per_process'])} MB", flush=True)
    return row


def table(rows):
    return md_tables.table(
        ("case", "h", "DOFs", "processes x threads", "first: ordering (s)", "analysis (s)", "factorization (s)", "factorizations",
         "all factorizations (s)", "wall (s)", "peak RSS per process (MB)", "factor entries per process", "flops per process",
         "answer", "speed-up, all factorizations"),
        [(r["case"], f"1/{r['level']}", r["ndof"], r["layout"].replace("x", " x "), f"{r['ordering_s']:.2f}", f"{r['analysis_s']:.2f}",
          f"{r['factorization_s']:.2f}", r["factorizations"], f"{r['all_factorizations_s']:.2f}", f"{r['wall_s']:.1f}",
          " / ".join(f"{m:.0f}" for m in r["rss_mb_per_process"]),
          " / ".join(f"{e:.3g}" for e in r["entries_per_process"]), " / ".join(f"{f:.3g}" for f in r["flops_per_process"]),
          f"{r['answer_name']} {r['answer']:.9g}", f"{r['speedup']:.2f}" if "speedup" in r else "-") for r in rows])


def figure(rows, path):
    """Two panels: each case's speed-up over 1 x 1 in all its factorizations (ordering, analysis and
    numerical phase: 2 processes, 2 threads), and the
    peak memory, one process against the largest of two and their sum."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cases = []
    for r in rows:
        key = (r["case"], r["level"])
        if key not in cases:
            cases.append(key)
    by = {(r["case"], r["level"], r["layout"]): r for r in rows}
    labels = [f"{'sphere a' if c == 'sphere' else 'rubber R'}/{l}\n{by.get((c, l, '1x1'), {}).get('ndof', 0):,} DOFs" for c, l in cases]
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    x = range(len(cases))
    for offset, layout, colour in ((-0.2, "2x1", "tab:blue"), (0.2, "1x2", "tab:orange")):
        values = [by[(c, l, layout)]["speedup"] if (c, l, layout) in by and "speedup" in by[(c, l, layout)] else 0 for c, l in cases]
        left.bar([i + offset for i in x], values, 0.4, color=colour,
                 label="2 processes x 1 thread (MPI)" if layout == "2x1" else "1 process x 2 threads")
    left.axhline(1, color="black", linewidth=0.8)
    left.axhline(2, color="grey", linewidth=0.8, linestyle="--")
    left.set_xticks(list(x)); left.set_xticklabels(labels, fontsize=8)
    left.set_ylabel("speed-up over 1 x 1, all factorizations"); left.set_ylim(0, 2.2); left.legend(fontsize=8, loc="lower right")
    left.set_title("The condensed factorizations (ordering, analysis, numerical) on 2 cores", fontsize=10)
    one = [by[(c, l, "1x1")]["rss_mb_per_process"][0] / 1024 if (c, l, "1x1") in by else 0 for c, l in cases]
    largest = [max(by[(c, l, "2x1")]["rss_mb_per_process"]) / 1024 if (c, l, "2x1") in by else 0 for c, l in cases]
    total = [sum(by[(c, l, "2x1")]["rss_mb_per_process"]) / 1024 if (c, l, "2x1") in by else 0 for c, l in cases]
    right.bar([i - 0.27 for i in x], one, 0.27, color="tab:grey", label="1 process")
    right.bar(list(x), largest, 0.27, color="tab:blue", label="2 processes: the larger")
    right.bar([i + 0.27 for i in x], total, 0.27, color="tab:cyan", label="2 processes: both")
    right.set_xticks(list(x)); right.set_xticklabels(labels, fontsize=8)
    right.set_ylabel("peak memory (GB)"); right.legend(fontsize=8)
    right.set_title("Peak memory: the factors split, the mesh and assembly copied", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--levels", default="24,36,50", help="the sphere at h = a/level: 67k, 201k and 508k DOFs")
    parser.add_argument("--rubber-levels", default="32", help="the 3D indentation at h = R/level (85k DOFs)")
    parser.add_argument("--layouts", default=",".join(LAYOUTS), help="processes x threads, among " + ", ".join(LAYOUTS))
    parser.add_argument("--out", default="results/performance")
    args = parser.parse_args()
    layouts = [x for x in args.layouts.split(",") if x]
    if not all(x in LAYOUTS for x in layouts):
        print(f"error: --layouts must be among {', '.join(LAYOUTS)}, got {args.layouts}")
        return 2
    rows = []
    for case, levels in (("sphere", args.levels), ("indentation", args.rubber_levels)):
        for level in [int(x) for x in levels.split(",") if x]:
            runs = {layout: layout_run(case, level, layout, f"{args.out}/scaling_{case}_{level}_{layout}") for layout in layouts}
            base = runs.get("1x1")
            for layout, row in runs.items():
                if row is None:
                    continue
                if base:
                    row["speedup"] = base["all_factorizations_s"] / row["all_factorizations_s"]
                    row["answer_difference"] = abs(row["answer"] - base["answer"]) / abs(base["answer"])
                rows.append(row)
    out = os.path.join(ROOT, args.out)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "scaling.json"), "w") as f:
        json.dump(rows, f, indent=1)
    text = "# Runs on several processes (scripts/performance/scaling.py)\n\n" + table(rows) + "\n"
    for r in rows:
        if r["processes"] > 1:
            text += (f"\n{r['case']} 1/{r['level']} on {r['layout']}: {r['ndof']} DOFs, factor entries {sum(r['entries_per_process']):.4g}, "
                     f"flops {sum(r['flops_per_process']):.4g}, peak RSS in all {sum(r['rss_mb_per_process']) / 1024:.2f} GB, "
                     f"wall {r['wall_s']:.0f} s\n")
    if rows:
        figure(rows, os.path.join(out, "scaling.png"))
        text += "\n![factorization speed-up and memory](scaling.png)\n"
    with open(os.path.join(out, "SCALING.md"), "w") as f:
        f.write(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
