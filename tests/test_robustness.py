"""Hostile and bad input, the output folder, checked writes, the checks gate, the randomized sweep."""

import pytest

from helpers import *  # noqa: F401,F403 (check, out, run_driver, read_summary, ROOT, TMP and the shared helpers)


@pytest.mark.heavy(seconds=60)
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
    """The clean-up removes what .outputs records only when it is a regular file of that name in the
    output folder whose identity is the one recorded: option-like names, '..', paths, folders, names
    without an identity (as lists held before issue 42) and records of files outside are left alone,
    and a list of any length is worked through (5000 records: the old 'sh -c' did nothing)."""
    o = out("hostile outputs")
    run_driver("benchmarks/cube.edp", ["-n", "2"], o)
    os.makedirs(os.path.join(o, "userdir"))
    open(os.path.join(o, "userdir", "keep.txt"), "w").write("the user's\n")
    open(os.path.join(o, "notes.txt"), "w").write("the user's\n")
    victim = out("hostile outputs victim.txt")
    open(victim, "w").write("outside\n")
    up = "../" + os.path.basename(victim)
    names = ["-rf", "--help", "userdir", "notes.txt", "..", ".", up, victim, "/etc/hostname"]
    with open(os.path.join(o, ".outputs"), "a") as f:
        f.write("".join(n + "\n" for n in names) + output_record(os.path.join(o, "userdir"))
                + output_record(victim, up) + output_record(victim, victim)
                + output_record(os.path.join(o, ".outputs")))
    code, output, _ = run_driver("benchmarks/cube.edp", ["-maxiter", "1"], o)
    s = read_summary(o)
    check("hostile .outputs: the run goes on (exit 3, its own failure), its own incomplete summary",
          code == 3 and s is not None and not s["complete"], f"exit {code}; {error_lines(output)}")
    check("hostile .outputs: userdir, its file, notes.txt, the file outside, /etc/hostname stay",
          os.path.isfile(os.path.join(o, "userdir", "keep.txt")) and os.path.isfile(victim)
          and os.path.isfile(os.path.join(o, "notes.txt")) and os.path.exists("/etc/hostname"))
    big = out("long outputs list")
    run_driver("benchmarks/cube.edp", ["-n", "2"], big)
    names = [f"old_step{i:05d}.log" for i in range(5000)]
    for name in names:
        open(os.path.join(big, name), "w").close()
    records = subprocess.run(["stat", "-c", "%d %i %.9W %n"] + names, cwd=big,
                             stdout=subprocess.PIPE, text=True).stdout
    with open(os.path.join(big, ".outputs"), "a") as f:
        f.write(records)
    code, _, _ = run_driver("benchmarks/cube.edp", ["-maxiter", "1"], big)
    left = [n for n in os.listdir(big) if n.startswith("old_step")]
    s = read_summary(big)
    check("5000 recorded outputs: all removed, the earlier complete summary replaced by this run's",
          len(records.splitlines()) == 5000 and not left and s is not None and not s["complete"],
          f"{len(left)} left, exit {code}")


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
    """`make sweep` at its smallest: 7 random cases (one per kind: Hertz, cube, O-ring, axisymmetric
    sphere, two cylinders, a hostile value, a hostile folder or state), every check met."""
    sweep = os.path.join(ROOT, "scripts", "sweep.py")
    proc = subprocess.run([sys.executable, sweep, "--n", "7", "--seed", "7",
                           "--out", out("sweep")], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    summary_line = [l for l in proc.stdout.splitlines() if l.startswith("sweep:")]
    check("sweep smoke: 7 cases, no failed run, no violated check",
          proc.returncode == 0 and summary_line and "0 failed runs, 0 check violations" in summary_line[0], str(summary_line))


# Issue 42, files lost or overwritten: a file counts as the suite's only by the identity recorded in
# .outputs when the run created it (plugin/files.cpp); every output is created fresh and renamed in.

COARSE_SPHERE = ["-h", "0.02", "-zone", "0.2", "-hmax", "0.3"]   # hertz_sphere meshed by gmsh, 1 s


def output_record(path, name=None):
    """A line of .outputs for the file at path, as plugin/files.cpp writes it: device, inode, birth
    time, name (GNU stat's %d %i %.9W)."""
    ident = subprocess.run(["stat", "-c", "%d %i %.9W", path], stdout=subprocess.PIPE,
                           text=True).stdout.strip()
    return f"{ident} {name or os.path.basename(path)}\n"


def test_input_in_output_folder():
    """Issue 42, probe 1: the mesh a run wrote, given back to a run into the same folder as -mesh,
    is read, not removed by the clean-up first (it exited 2, 'file not found'); a later run without
    -mesh still removes it as the suite's own."""
    o = out("input in output folder")
    run_driver("benchmarks/hertz_sphere.edp", COARSE_SPHERE, o)
    mesh = os.path.join(o, "quarter_hemisphere.msh")
    before = open(mesh).read() if os.path.exists(mesh) else None
    code, output, _ = run_driver("benchmarks/hertz_sphere.edp", ["-mesh", mesh], o)
    check("input in the output folder: the run with -mesh <out>/quarter_hemisphere.msh exits 0",
          before and code == 0 and read_summary(o)["complete"],
          f"exit {code}; {error_lines(output)}")
    check("input in the output folder: the mesh is still there, unchanged",
          os.path.exists(mesh) and open(mesh).read() == before)
    identity = output_record(mesh)
    code, _, _ = run_driver("benchmarks/hertz_sphere.edp", COARSE_SPHERE, o)
    check("input in the output folder: still the suite's, removed and made anew by a run meshing",
          code == 0 and os.path.exists(mesh) and output_record(mesh) != identity, f"exit {code}")


def test_links_not_written_through():
    """Issue 42, probe 2: a hard link planted at an output's name (pressure.csv, ipopt.opt, the
    IPOPT log, the .vtu, summary.json; gmsh.log and the mesh of a gmsh run) is replaced, not written
    through: the file outside keeps its content (it received the output before)."""
    plane = ["pressure.csv", "ipopt.opt", "ipopt_step00001.log", "hertz_plane.vtu", "summary.json"]
    for driver, args, names in (("benchmarks/hertz_plane.edp", ["-condense", "no"], plane),
                                ("benchmarks/hertz_sphere.edp", COARSE_SPHERE,
                                 ["gmsh.log", "quarter_hemisphere.msh"])):
        label = f"hard links, {os.path.basename(driver)}"
        o = out(label)
        os.makedirs(o)
        victims = []
        for name in names:
            victim = out(f"outside {os.path.basename(driver)} {name}")
            open(victim, "w").write("precious\n")
            os.link(victim, os.path.join(o, name))
            victims.append(victim)
        code, output, _ = run_driver(driver, args, o)
        check(f"{label}: exit 0, and every file outside still holds its own text",
              code == 0 and all(open(v).read() == "precious\n" for v in victims),
              f"exit {code}; {error_lines(output)}")
        check(f"{label}: each output is now a file of its own",
              all(os.stat(os.path.join(o, n)).st_nlink == 1 for n in names))


def test_user_file_at_output_name():
    """Issue 42, probe 3: a file of the user's under an output's name is left alone: the run refuses
    the folder (exit 2, one error line naming the file and -out, nothing written); it was
    overwritten."""
    o = out("user file at output name")
    os.makedirs(o)
    notes = os.path.join(o, "pressure.csv")
    open(notes, "w").write("notes\n")
    code, output, _ = run_driver("benchmarks/hertz_plane.edp", [], o)
    errors = error_lines(output)
    check("user file pressure.csv: exit 2, one error line naming it and -out, the file unchanged, "
          "no summary.json", code == 2 and len(errors) == 1 and "pressure.csv" in errors[0]
          and "-out" in errors[0] and open(notes).read() == "notes\n" and read_summary(o) is None,
          f"exit {code}; {errors}")
    # the same name written after the suite's file of that name was deleted: a new file (ext4 gives
    # it the old inode number at once), not the suite's
    again = o + "2"
    run_driver("benchmarks/cube.edp", ["-n", "2"], again)
    os.remove(os.path.join(again, "cube.vtu"))
    open(os.path.join(again, "cube.vtu"), "w").write("notes\n")
    code, output, _ = run_driver("benchmarks/cube.edp", ["-n", "2"], again)
    check("user file made after the suite's of that name was deleted: left alone (exit 2)",
          code == 2 and open(os.path.join(again, "cube.vtu")).read() == "notes\n",
          f"exit {code}; {error_lines(output)}")


def test_mpi_writes_nothing_elsewhere():
    """Issue 42, probe 4: under MPI the other processes' IPOPT wrote ipopt.out in the working folder
    (truncating a link of that name): now nothing is created there and the link's target is
    intact."""
    work = out("mpi workdir")
    os.makedirs(work)
    with open(os.path.join(work, "freefem++.pref"), "w") as f:
        f.write(f'loadpath += "/usr/lib/freefem++"\nloadpath += "{ROOT}/plugin"\n'
                f'includepath += "{ROOT}/include"\nload += "headless"\nverbosity = 0\n')
    victim = out("mpi victim.txt")
    open(victim, "w").write("precious\n")
    os.symlink(victim, os.path.join(work, "ipopt.out"))
    plane = os.path.join(ROOT, "benchmarks/hertz_plane.edp")
    code, output, _ = run_driver(plane, [], os.path.join(work, "o"), cwd=work, processes=2)
    check("mpi: exit 0, the link ipopt.out's target untouched",
          code == 0 and open(victim).read() == "precious\n", f"exit {code}; {error_lines(output)}")
    os.remove(os.path.join(work, "ipopt.out"))
    code, _, _ = run_driver(plane, [], os.path.join(work, "o"), cwd=work, processes=2)
    left = sorted(os.listdir(work))
    check("mpi: no ipopt.out (or any other file) created in the working folder",
          code == 0 and left == ["freefem++.pref", "o"], str(left))


def test_lock_and_list_safe():
    """Issue 42, probe 5: a crafted .outputs listing .lock (with its identity) leaves the lock
    alone, so a second run during the first is still refused; a killed run's empty .write_probe is
    removed by the next run (it blocked the folder for good); .outputs as a FIFO or a link to
    /dev/zero is refused at once (both hung)."""
    o = out("lock listed")
    os.makedirs(o)
    lock = os.path.join(o, ".lock")
    open(lock, "w").close()
    open(os.path.join(o, ".outputs"), "w").write(output_record(lock) + ".lock\n")
    lock_inode = os.stat(lock).st_ino
    first = subprocess.Popen(["FreeFem++", "-nw", "benchmarks/sliding_disc.edp", "-out", o],
                             cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    # until the first run holds the lock and has cleaned the folder (its curve file exists)
    while first.poll() is None and not os.path.exists(os.path.join(o, "force_slide.csv")):
        time.sleep(0.01)
    code, output, _ = run_driver("benchmarks/sliding_disc.edp", [], o)
    running = first.poll() is None   # (the first run is not needed further: ended here)
    first.kill()
    first.wait()
    check("lock listed in .outputs: the lock kept, a second run during the first refused (in use)",
          running and os.stat(lock).st_ino == lock_inode and code == 2 and "in use" in output,
          f"first running {running}, exit {code}; {error_lines(output)}")
    probe = out("stale probe")
    os.makedirs(probe)
    open(os.path.join(probe, ".write_probe"), "w").close()
    code, _, _ = run_driver("benchmarks/cube.edp", ["-n", "2"], probe)
    check("a killed run's empty .write_probe: removed, the run completes",
          code == 0 and not os.path.exists(os.path.join(probe, ".write_probe")), f"exit {code}")
    for label, make in (("a FIFO", os.mkfifo),
                        ("a link to /dev/zero", lambda p: os.symlink("/dev/zero", p))):
        d = out(f"outputs {label}")
        os.makedirs(d)
        make(os.path.join(d, ".outputs"))
        try:
            code, output, _ = run_driver("benchmarks/cube.edp", ["-n", "2"], d, timeout=120)
        except subprocess.TimeoutExpired:
            code, output = "timeout", ""
        errors = error_lines(output)
        check(f".outputs {label}: refused at once (exit 2, one line naming it), left in place",
              code == 2 and len(errors) == 1 and ".outputs" in errors[0]
              and os.path.lexists(os.path.join(d, ".outputs")), f"exit {code}; {errors}")


def test_gmsh_dies_with_its_run():
    """Issue 42, probe 11: gmsh runs in a process group of its own without the lock's descriptor and
    dies with the run: a run killed while meshing leaves no gmsh writing, and the next run into the
    folder is not refused as 'in use'."""
    o = out("killed while meshing")
    command = ["FreeFem++", "-nw", "benchmarks/hertz_sphere.edp", "-h", "0.004", "-out", o]
    proc = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    def read(path, how=None):   # "" once the process or the descriptor is gone
        try:
            if how:
                return how(path)
            with open(path) as f:
                return f.read()
        except OSError:
            return ""

    def target(fd):   # (gmsh opens and closes its own files meanwhile)
        try:
            return os.readlink(f"/proc/{gmsh}/fd/{fd}")
        except OSError:
            return ""
    gmsh = None
    while proc.poll() is None and gmsh is None:   # until the run has started gmsh
        children = read(f"/proc/{proc.pid}/task/{proc.pid}/children").split()
        gmsh = next((int(c) for c in children if read(f"/proc/{c}/comm").strip() == "gmsh"), None)
        time.sleep(0.01)
    group = os.getpgid(gmsh) if gmsh else None
    inherited = [target(fd) for fd in (read(f"/proc/{gmsh}/fd", os.listdir) if gmsh else [])]
    proc.kill()
    proc.wait()
    # until gmsh is gone (a zombie of init's until reaped)
    def alive(pid):
        state = read(f"/proc/{pid}/stat").split()
        return len(state) > 2 and state[2] != "Z"
    while gmsh and alive(gmsh):
        time.sleep(0.01)
    check("killed while meshing: gmsh ran in a group of its own, without the folder's .lock open",
          gmsh and group == gmsh and not any(f.endswith("/.lock") for f in inherited),
          f"gmsh {gmsh}, group {group}, {inherited}")
    mesh = os.path.join(o, "quarter_hemisphere.msh")
    size = os.path.getsize(mesh) if os.path.exists(mesh) else 0
    code, output, _ = run_driver("benchmarks/cube.edp", ["-n", "2"], o)
    check("killed while meshing: gmsh ended with the run (no mesh written after), the next run "
          "into the folder exits 0", size == 0 and code == 0,
          f"mesh {size} bytes, exit {code}; {error_lines(output)}")


def test_make_variables_not_commands():
    """Issue 42, probe 10: make's user variables reach the recipes as environment variables, never
    as command text: `make workspace DIR='x`touch M`'`, `DIR='x"; touch M; echo "'`, `make test
    K='zz; touch M #'` and `make sweep N='1; touch M'` ran the embedded touch. Now the folders are
    made with those names and nothing runs (no file M anywhere); the values reach pytest and the
    sweep whole, as one argument each (their own refusals quote them)."""
    base = out("make variables")
    os.makedirs(base)
    canary = os.path.join(base, "M")
    quoted = f'{base}/y"; touch {canary}; echo "'
    cases = [(["workspace", f"DIR={base}/x`touch {canary}`"], 0, "my_problem.edp"),
             (["workspace", f"DIR={quoted}"], 0, "my_problem.edp"),
             # (JOBS=0: pytest in one process, which quotes the expression it refuses)
             (["test", "JOBS=0", f"K=zz; touch {canary} #"], None,
              "Wrong expression passed to '-k': zz; touch"),
             (["sweep", f"N=1; touch {canary}"], None, "invalid int value: '1; touch")]
    env = {k: v for k, v in os.environ.items() if k not in ("K", "DIR", "N", "JOBS", "PEERS")}
    for args, expected, said in cases:
        proc = subprocess.run(["make", "-s"] + args, cwd=ROOT, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True, env=env)
        check(f"make {' '.join(args)}: nothing ran (no file M), the value reached its program",
              not os.path.exists(canary) and not os.path.exists(os.path.join(ROOT, "M"))
              and (expected is None or proc.returncode == expected) and said in proc.stdout,
              f"exit {proc.returncode}: {proc.stdout.strip()[-200:]}")
    check("make workspace: the folders are named as given",
          os.path.isfile(os.path.join(quoted, "my_problem.edp")), str(os.listdir(base)))


# Issue 42, exit 0 with a wrong answer: a result is compared with its reference only when the run
# reached the state the reference describes; the checks' bounds do not follow -tol.

BAR = "benchmarks/bar_impact.edp"


def test_time_runs_end_after_impact():
    """Issue 42, probe 6: a time run that ends before its impact is over exits 4 naming why
    (impact_over), and reports no result against a reference: bar_impact -tend 8e-6 reported
    impact_time = -1.0000007, a sentinel, and -tend 5e-5 a rebound of -12 against 100 m/s; two bars
    199 % off, a sphere 98 % off, a sphere of nu = -0.9999999 still coming back to the wall, all
    with exit 0."""
    sphere, bars = "benchmarks/sphere_impact.edp", "benchmarks/bars_head_on.edp"
    bar = ["-n", "50", "-gap", "1e-3", "-tend"]
    for label, driver, args in (("bar before the wall", BAR, bar + ["8e-6"]),
                                ("bar against the wall", BAR, bar + ["5e-5"]),
                                ("bars in contact", bars, ["-n", "40", "-tend", "2e-5"]),
                                ("sphere in contact", sphere, ["-tend", "1e-6"]),
                                ("sphere still approaching", sphere, ["-nu", "-0.9999999"])):
        o = out(f"impact {label}")
        code, output, _ = run_driver(driver, args + ["-every", "0"], o)
        s = read_summary(o)
        errors = error_lines(output)
        impact_time = (s or {}).get("results", {}).get("impact_time", {"computed": 0})["computed"]
        check(f"{label} ({' '.join(args)}): exit 4, impact_over the failed check named in one "
              "error line, no result against a reference, no impact_time sentinel",
              code == 4 and s is not None and s["checks_failed"] == ["impact_over"]
              and len(errors) == 1 and "impact_over" in errors[0] and "-tend" in errors[0]
              and impact_time >= 0 and all(q["reference"] is None for q in s["results"].values()),
              f"exit {code}; {errors}")


def test_loose_tolerance():
    """Issue 42, probe 7: the run's own check bounds come from the driver's default tolerance, not
    from -tol (balance 100 x -tol hid hertz_plane -tol 1e-3's 7.7 % off; -tol beyond 1e-5 is
    refused, in tests/bad_inputs.py): the bar at -tol 1e-5, its time steps balanced to ~1e-5,
    exits 4 naming the balance against its default bound 1e-8."""
    o = out("loose tolerance bar")
    code, output, _ = run_driver(BAR, ["-n", "50", "-every", "0", "-tol", "1e-5"], o)
    s = read_summary(o)
    errors = error_lines(output)
    check("bar at -tol 1e-5: exit 4, the balance failed against the default bound 1e-08",
          code == 4 and s is not None and s["checks_failed"] == ["dynamics_balance_rel_error"]
          and len(errors) == 1 and "bound 1e-08" in errors[0], f"exit {code}; {errors}")


def test_step_records_whole():
    """Issue 42, probe 9: summary.json holds every step's record (cube -steps 1500 kept 1,000, the
    last at load 0.667, with complete: true; -steps beyond 1000 is now refused, in
    tests/bad_inputs.py): 1500 records made as the solver makes them are all written."""
    o = out("step records")
    code, _, _ = run_driver("tests/checks_gate.edp", ["-records", "1500"], o)
    s = read_summary(o)
    check("1500 step records: all in summary.json, the last at load 1", code == 0 and s is not None
          and len(s["steps"]) == 1500 and s["steps"][-1]["load_factor"] == 1, f"exit {code}")


# Issue 42, messages: they name the parameter the user gave, quote its value as typed and shortened,
# and suggest only what the driver takes (the cases of tests/bad_inputs.py check the names).

def test_messages_suggest_what_the_driver_takes():
    """Issue 42, probe 14: drivers without -volumetric suggested '-volumetric nodal' for -nu 0.5,
    and rejected it when given; a 5,000-character value was echoed whole; README said every driver
    with contact takes -mu, which cube.edp and bar_impact.edp reject."""
    tmp = out("messages")
    for driver in ("sliding_disc.edp", "hertz_two_spheres.edp", "bar_impact.edp"):
        code, output, _ = run_driver(f"benchmarks/{driver}", ["-nu", "0.5"], tmp)
        errors = error_lines(output)
        check(f"{driver} -nu 0.5: exit 2, one line naming -nu, no suggestion of -volumetric",
              code == 2 and len(errors) == 1 and "-nu" in errors[0]
              and "-volumetric" not in errors[0],
              str(errors))
    code, output, _ = run_driver("benchmarks/cube.edp", ["-material", "x" * 5000], tmp)
    check("a 5,000-character value: one error line of less than 300 characters",
          code == 2 and len(output.splitlines()) == 1 and len(output) < 300,
          f"{len(output)} characters")
    readme = " ".join(open(os.path.join(ROOT, "README.md")).read().split())
    sentence = readme[readme.index("takes `-mu`") - 120:readme.index("takes `-mu`")]
    for driver in ("cube.edp", "bar_impact.edp"):
        code, output, _ = run_driver(f"benchmarks/{driver}", ["-mu", "0.3"], tmp)
        said = driver in sentence or "time drivers are frictionless" in readme
        check(f"{driver} refuses -mu, and the README says it does not take it",
              code == 2 and "unknown parameter -mu" in output and said, sentence)
