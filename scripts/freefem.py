"""Running a FreeFem++ driver from the repository root and reading its summary."""

import json
import os
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_driver(script, args, out_dir, timeout=1800, cwd=ROOT):
    """Run `FreeFem++ script args [-out out_dir]`; return (exit code, output, seconds)."""
    command = ["FreeFem++", "-nw", script] + list(args) + (["-out", out_dir] if out_dir else [])
    start = time.time()
    proc = subprocess.run(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=timeout)
    return proc.returncode, proc.stdout, time.time() - start


def read_summary(out_dir):
    path = os.path.join(out_dir if os.path.isabs(out_dir) else os.path.join(ROOT, out_dir), "summary.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)
