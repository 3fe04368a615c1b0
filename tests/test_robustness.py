"""Hostile and bad input, the output folder, checked writes, the checks gate, the randomized sweep."""

from helpers import *  # noqa: F401,F403 (check, out, run_driver, read_summary, ROOT, TMP and the shared helpers)


def test_bad_input():
    """Every case of tests/bad_inputs.py (all drivers; the table in docs/robustness.md): one line starting
    with `error:` that names the problem, exit code 2, and no summary.json left behind."""
    import bad_inputs
    tmp = out("bad input files")
    os.makedirs(tmp)
    bad_inputs.make_files(tmp)
    for i, (driver, args, word) in enumerate(bad_inputs.CASES):
        label = f"{os.path.basename(driver)} {' '.join(args).replace('{tmp}/', '')}"
        code, first, left = bad_inputs.run_case(driver, args, tmp, out(f"bad {i}"))
        check(f"bad input {label}: exit code 2", code == 2, f"exit {code}")
        check(f"bad input {label}: one-line error naming '{word}'", first.startswith("error:") and word in first, first)
        check(f"bad input {label}: no summary.json", not left)
    check("bad input: every driver is covered", {d for d, _, _ in bad_inputs.CASES} >=
          {os.path.join("benchmarks", f) for f in os.listdir(os.path.join(ROOT, "benchmarks")) if f.endswith(".edp")})
    blank = os.path.join(TMP, "a b")
    code, first, left = bad_inputs.run_case("benchmarks/cube.edp", [], tmp, blank)
    check("bad input: an output folder with a blank is refused", code == 2 and "-out" in first, first)


def test_no_shell():
    """No path reaches a shell: an -out holding $(touch pwned) is just a folder's name, through the
    run, its IPOPT options, its gmsh call (hertz_sphere meshes with gmsh) and its clean-up."""
    for driver, args in (("benchmarks/cube.edp", []), ("benchmarks/hertz_sphere.edp", ["-dim", "3"])):
        parent = out(f"no shell {os.path.basename(driver)}")
        o = os.path.join(parent, "$(touch${IFS}pwned)")
        code, output, _ = run_driver(driver, args, o)
        s = read_summary(o)
        check(f"no shell, {os.path.basename(driver)}: exit 0 into the folder named '$(touch pwned)', complete",
              code == 0 and s is not None and s["complete"], f"exit {code}; {error_lines(output)}")
        check(f"no shell, {os.path.basename(driver)}: nothing ran (no file pwned in the working or output folders)",
              not any(os.path.exists(os.path.join(d, "pwned")) for d in (ROOT, parent, o, os.path.dirname(o))))


def test_hostile_outputs_list():
    """The clean-up removes what .outputs names only when it is a regular file or a link of that
    name in the output folder: option-like names, '..', paths and folders are left alone, and a
    list of any length is worked through (5000 names: the old 'sh -c' silently did nothing)."""
    o = out("hostile outputs")
    os.makedirs(os.path.join(o, "userdir"))
    open(os.path.join(o, "userdir", "keep.txt"), "w").write("the user's\n")
    victim = out("hostile outputs victim.txt")
    open(victim, "w").write("outside\n")
    open(os.path.join(o, ".outputs"), "w").write("-rf\n--help\nuserdir\n..\n.\n../" + os.path.basename(victim)
                                                 + "\n" + victim + "\n/etc/hostname\n")
    stale_summary(o)
    code, output, _ = run_driver("benchmarks/cube.edp", ["-maxiter", "1"], o)
    s = read_summary(o)
    check("hostile .outputs: the run goes on (exit 3 of its own failure) and leaves its own incomplete summary",
          code == 3 and s is not None and not s["complete"] and "stale" not in s, f"exit {code}")
    check("hostile .outputs: userdir, its file, the file outside and /etc/hostname are all still there",
          os.path.isfile(os.path.join(o, "userdir", "keep.txt")) and os.path.isfile(victim)
          and os.path.exists("/etc/hostname"))
    big = out("long outputs list")
    os.makedirs(big)
    names = [f"old_step{i:05d}.log" for i in range(5000)]
    for name in names:
        open(os.path.join(big, name), "w").close()
    open(os.path.join(big, ".outputs"), "w").write("".join(n + "\n" for n in names))
    stale_summary(big)
    code, _, _ = run_driver("benchmarks/cube.edp", ["-maxiter", "1"], big)
    left = [n for n in os.listdir(big) if n.startswith("old_step")]
    s = read_summary(big)
    check("5000 listed outputs: all removed, the old complete summary replaced by this run's",
          not left and s is not None and "stale" not in s and not s["complete"], f"{len(left)} left, exit {code}")


def test_planted_files():
    """What lies at an output's name is not written through: a link pressure.csv pointing outside is
    replaced by the run's own file (its target untouched); a folder summary.json stops the run at once."""
    o = out("planted link")
    os.makedirs(o)
    target = out("planted link target.txt")
    open(target, "w").write("precious\n")
    os.symlink(target, os.path.join(o, "pressure.csv"))
    code, _, _ = run_driver("benchmarks/hertz_plane.edp", [], o)
    check("planted link: exit 0, the link's target untouched, pressure.csv now the run's own file",
          code == 0 and open(target).read() == "precious\n" and not os.path.islink(os.path.join(o, "pressure.csv"))
          and open(os.path.join(o, "pressure.csv")).readline().startswith("s,x_ref,"), f"exit {code}")
    d = out("summary folder")
    os.makedirs(os.path.join(d, "summary.json"))
    open(os.path.join(d, "summary.json", "inside.txt"), "w").write("the user's\n")
    code, output, _ = run_driver("benchmarks/cube.edp", [], d)
    errors = error_lines(output)
    check("summary.json a folder: exit 2, one error line naming it, the folder and its file kept",
          code == 2 and len(errors) == 1 and "summary.json" in errors[0]
          and os.path.isfile(os.path.join(d, "summary.json", "inside.txt")), f"exit {code}; {errors}")


def test_folder_lock():
    """A second run into a folder in use stops at once (exit 2, one line saying so) and the first
    run, undisturbed, completes with all its logs."""
    import fcntl
    o = out("locked")
    first = subprocess.Popen(["FreeFem++", "-nw", "benchmarks/sliding_disc.edp", "-out", o], cwd=ROOT,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    held = False
    while first.poll() is None and not held:   # until the first run holds the lock
        try:
            with open(os.path.join(o, ".lock")) as f:
                try:
                    fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    fcntl.flock(f, fcntl.LOCK_UN)
                except OSError:
                    held = True
        except OSError:
            pass
        time.sleep(0.01)
    code, output, _ = run_driver("benchmarks/sliding_disc.edp", [], o)
    errors = error_lines(output)
    first_output, _ = first.communicate()
    s = read_summary(o)
    check("lock: the second run into a busy folder exits 2 with one line saying it is in use",
          held and code == 2 and len(errors) == 1 and "in use" in errors[0], f"held {held}; exit {code}; {errors}")
    logs = [n for n in os.listdir(o) if n.startswith("ipopt_step")]
    check("lock: the step logs sort in step order (ipopt_step00001.log ...: ipopt_step100.log sorted before "
          "ipopt_step11.log)", sorted(logs) == sorted(logs, key=lambda n: int(re.sub(r"\D", "", n))), str(sorted(logs)[:3]))
    check("lock: the first run completes undisturbed, one log per step and iterations counted in every step",
          first.returncode == 0 and s is not None and s["complete"] and len(logs) == len(s["steps"])
          and "iterations 0 " not in first_output, f"exit {first.returncode}, {len(logs)} logs")


def test_full_disk():
    """Every write is checked: on file systems too small for the run's outputs (tmpfs from 4 KB to
    1 MB) the run either completes with every file whole, or ends with one error line naming the file
    it could not write, exit 3, and no summary.json claiming completion. Needs root (mount)."""
    mount_point = out("full disk")
    os.makedirs(mount_point)
    results = []
    for size in ("4k", "8k", "16k", "24k", "64k", "128k", "256k", "300k", "308k", "312k", "316k", "320k", "512k", "1m"):
        if subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", mount_point],
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode != 0:
            print(f"SKIP  full disk: cannot mount a tmpfs here (needs root): {size}")
            return
        try:
            o = os.path.join(mount_point, "o")
            code, output, _ = run_driver("benchmarks/hertz_plane.edp", [], o)
            errors = error_lines(output)
            try:
                s = read_summary(o)
                valid = True
            except ValueError:
                s, valid = None, False
            if code == 0:
                ok = (valid and s is not None and s["complete"] and not errors
                      and all(os.path.getsize(os.path.join(o, n)) > 0 for n in ("hertz_plane.vtu", "pressure.csv")))
            else:
                ok = (code == 3 and len(errors) == 1 and "No space left on device" in errors[0]
                      and valid and (s is None or not s["complete"]))
            results.append((size, code, errors[0].split(":")[1].split("/")[-1] if errors else ""))
            check(f"full disk {size}: exit 0 with whole outputs, or exit 3 naming the file it could not write",
                  ok, f"exit {code}; {errors}")
        finally:
            subprocess.run(["umount", mount_point])
    # FreeFEM's savevtk (P2 fields) reports no error: its file cut short is caught by its missing closing tag
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=16k", "tmpfs", mount_point]).returncode == 0:
        try:
            code, output, _ = run_driver("benchmarks/clamped_square.edp", ["-order", "2", "-n", "8"],
                                         os.path.join(mount_point, "o"))
            errors = error_lines(output)
            check("full disk 16k, P2 .vtu (savevtk): exit 3, one line naming clamped_square.vtu",
                  code == 3 and len(errors) == 1 and "clamped_square.vtu" in errors[0], f"exit {code}; {errors}")
        finally:
            subprocess.run(["umount", mount_point])
    failed = {name for _, code, name in results if code != 0}
    check("full disk: the smallest file systems fail, the largest completes, and the failures name at least "
          "three different files (ipopt.opt, pressure.csv, the .vtu, summary.json)",
          results[0][1] != 0 and results[-1][1] == 0 and len(failed) >= 3, str(results))


def test_checks_gate_exit():
    """A run whose own checks fail does not exit 0 (tests/checks_gate.edp records a balance or a
    penetration and ends the run as the drivers do): exit 4, one error line naming the check,
    summary.json's checks_failed; within the bounds exit 0 and checks_failed empty."""
    for args, code_expected, failed in ((["-balance", "1e-12"], 0, []), (["-balance", "1e-3"], 4, ["force_balance_rel_error"]),
                                        (["-penetration", "1e-6"], 4, ["max_penetration"])):
        o = out("checks gate " + " ".join(args))
        code, output, _ = run_driver("tests/checks_gate.edp", args, o)
        s = read_summary(o)
        errors = error_lines(output)
        check(f"checks gate {' '.join(args)}: exit {code_expected}, checks_failed {failed}, "
              f"{len(failed)} error line(s) naming it", code == code_expected and s is not None
              and s["checks_failed"] == failed and len(errors) == len(failed)
              and all(f in errors[0] for f in failed), f"exit {code}; {errors}")
    from freefem import run_ok, summary_failure
    s = read_summary(out("checks gate -balance 1e-3"))
    check("checks gate: the benchmark runner and the report count that run as failed (exit 4 and its summary)",
          s is not None and not run_ok(4, s) and not run_ok(0, s) and "force_balance_rel_error" in summary_failure(s)
          and run_ok(0, read_summary(out("checks gate -balance 1e-12"))))


def test_no_stale_outputs():
    """An output folder starts clean of the previous run's outputs: a run that fails, or is
    interrupted, leaves no older summary.json, .vtu or pressure.csv next to its own."""
    o = out("stale")
    run_driver("benchmarks/hertz_plane.edp", [], o)
    before = sorted(os.listdir(o))
    check("stale: a first complete run writes summary, .vtu and pressure.csv",
          {"summary.json", "hertz_plane.vtu", "pressure.csv"} <= set(before), str(before))
    run_driver("benchmarks/hertz_plane.edp", ["-maxiter", "2"], o)
    s = read_summary(o)
    after = os.listdir(o)
    check("stale: a failed run leaves its own incomplete summary and neither .vtu nor pressure.csv",
          s is not None and not s["complete"] and "hertz_plane.vtu" not in after and "pressure.csv" not in after, str(after))
    run_driver("benchmarks/hertz_plane.edp", [], o)
    # interrupted once it has opened the folder (the last run's summary.json is gone) and before it
    # ends (it has not exited): whatever the machine's speed (a fixed 4 s wait failed on a fast one)
    command = ["FreeFem++", "-nw", "benchmarks/hertz_plane.edp", "-h", "0.0002", "-out", o]
    proc = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    while os.path.exists(os.path.join(o, "summary.json")) and proc.poll() is None:
        time.sleep(0.01)
    interrupted = proc.poll() is None
    proc.kill()
    proc.wait()
    left = os.listdir(o)
    check("stale: an interrupted run leaves no summary.json, .vtu or pressure.csv of the run before",
          interrupted and not ({"summary.json", "hertz_plane.vtu", "pressure.csv"} & set(left)),
          f"interrupted before its end: {interrupted}; {sorted(left)}")
    mine = out("stale user files")
    os.makedirs(mine)
    for name in ("data.csv", "notes.vtu", "summary.txt"):
        open(os.path.join(mine, name), "w").write("the user's\n")
    run_driver("benchmarks/platen_block.edp", ["-n", "10", "-steps", "1"], mine)
    code, _, _ = run_driver("benchmarks/platen_block.edp", ["-n", "10", "-steps", "1"], mine)
    check("stale: a run removes only what a run wrote (the user's .csv, .vtu and other files stay)",
          code == 0 and all(os.path.exists(os.path.join(mine, n)) for n in ("data.csv", "notes.vtu", "summary.txt")),
          str(sorted(os.listdir(mine))))


def test_output_folder_errors():
    """An output folder that cannot be created: one error line naming -out, exit code 2."""
    blocker = os.path.join(TMP, "a_file")
    open(blocker, "w").close()
    code, output, _ = run_driver("benchmarks/cube.edp", [], os.path.join(blocker, "sub"))
    first = output.strip().splitlines()[0] if output.strip() else ""
    check("output folder under a file: exit 2, one error line naming -out", code == 2 and first.startswith("error:")
          and "-out" in first and len([l for l in output.splitlines() if l.startswith("error:")]) == 1, first)


def test_sweep_smoke():
    """`make sweep` at its smallest: 6 random cases (one per kind: Hertz, cube, O-ring, axisymmetric
    sphere, two cylinders, a hostile value), every check met."""
    proc = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "sweep.py"), "--n", "6", "--seed", "7",
                           "--out", out("sweep")], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    summary_line = [l for l in proc.stdout.splitlines() if l.startswith("sweep:")]
    check("sweep smoke: 6 cases, no failed run, no violated check",
          proc.returncode == 0 and summary_line and "0 failed runs, 0 check violations" in summary_line[0], str(summary_line))
