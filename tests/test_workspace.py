"""The suite as a user meets it: the output contract, the working folder, headless runs, the template in a workspace of its own, the external programs."""

from helpers import *  # noqa: F401,F403 (check, out, run_driver, read_summary, ROOT, TMP and the shared helpers)
import glob  # noqa: E402


def test_output_contract():
    o = out("contract")
    # IPOPT on the whole problem (without contact rows the default is the condensed Newton, no IPOPT)
    # run by a Python of its own, whose only child it is: the kernel's peak resident memory of the
    # run (RUSAGE_CHILDREN), the reference of the summary's peak_memory_mib
    probe = ("import resource, subprocess, sys; subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, "
             "stderr=subprocess.DEVNULL); print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
    proc = subprocess.run([sys.executable, "-c", probe, "FreeFem++", "-nw", "benchmarks/cube.edp", "-n", "2",
                           "-condense", "no", "-out", o], cwd=ROOT, capture_output=True, text=True)
    s = read_summary(o) or {}
    for key in ("benchmark", "parameters", "ndof", "ipopt_status", "ipopt_iterations", "wall_time_s", "results"):
        check(f"summary.json has '{key}'", key in s)
    # written before the run ends: at most the run's peak, and within 10 % of it (the .vtu is
    # written before the summary)
    peak = s.get("timings", {}).get("peak_memory_mib", float("nan"))
    run_peak = int(proc.stdout.strip() or 0) / 1024
    check("timings.peak_memory_mib: within [0.9, 1] of the kernel's peak of the run",
          0.9 * run_peak <= peak <= run_peak, f"{peak} against {run_peak} MiB")
    faults = s.get("timings", {}).get("page_faults", float("nan"))
    check("timings.page_faults: a count, at least one (the run's memory faulted in)",
          faults >= 1 and faults == int(faults), f"{faults}")
    params = s.get("parameters", {})
    check("summary.json lists every parameter", all(k in params for k in
          ("material", "C10", "C01", "nu", "pressure", "dim", "n", "steps", "out")), str(sorted(params)))
    vtu = os.path.join(o, "cube.vtu")
    text = open(vtu, errors="replace").read() if os.path.exists(vtu) else ""
    check("cube.vtu holds displacement, J, von Mises",
          all(f'Name="{n}"' in text for n in ("displacement", "J", "von_Mises")))
    # its values (written from the arrays by plugin/vtu_writer.cpp, float32): the block's deformation
    # is homogeneous, so the largest |u_y| is the summary's w, J is J_min in every element and the
    # largest von Mises is the summary's, each to float32 rounding (6e-8; bound 1e-6)
    if text:
        from vtu import read_vtu
        import numpy as np
        points, cells, types, pdata, cdata = read_vtu(vtu)
        r = s.get("results", {})
        dim = 3 if s.get("parameters", {}).get("dim") == 3 else 2
        w = r.get("w", {}).get("computed", float("nan"))
        check("cube.vtu: one displacement per vertex", len(points) == s.get("ndof", 0) // dim, f"{len(points)} points")
        check("cube.vtu: largest |u_y| = w to 1e-6", abs(np.abs(pdata["displacement"][:, 1]).max() - w) <= 1e-6 * w,
              f"{np.abs(pdata['displacement'][:, 1]).max():.9g} vs {w:.9g}")
        jmin = r.get("J_min", {}).get("computed", float("nan"))
        check("cube.vtu: J = J_min in every element to 1e-6", np.abs(cdata["J"] - jmin).max() <= 1e-6, f"{np.abs(cdata['J'] - jmin).max():.1e}")
        vm = r.get("von_mises_max", {}).get("computed", float("nan"))
        check("cube.vtu: largest von Mises = the summary's to 1e-6", abs(cdata["von_Mises"].max() - vm) <= 1e-6 * vm,
              f"{cdata['von_Mises'].max():.9g} vs {vm:.9g}")
    logs = [f for f in os.listdir(o) if f.startswith("ipopt_step")] if os.path.isdir(o) else []
    check("IPOPT log is in the output folder", len(logs) == 1, str(logs))


def test_working_folder_untouched():
    """ff-Ipopt writes ipopt.out and reads ipopt.opt in the working folder: a hostile
    ipopt.opt (max_iter 0) must be ignored and nothing written next to it."""
    work = out("workdir")
    os.makedirs(work)
    with open(os.path.join(work, "freefem++.pref"), "w") as f:
        f.write('loadpath += "/usr/lib/freefem++"\nloadpath += "%s/plugin"\nincludepath += "%s/include"\nverbosity = 0\n'
                % (ROOT, ROOT))
    with open(os.path.join(work, "ipopt.opt"), "w") as f:
        f.write("max_iter 0\n")
    before = set(os.listdir(work))
    code, output, _ = run_driver(os.path.join(ROOT, "benchmarks/cube.edp"), ["-n", "2"], os.path.join(work, "o"), cwd=work)
    after = set(os.listdir(work)) - {"o"}
    check("ipopt.opt in the working folder is not read", code == 0, output.strip().splitlines()[-1:])
    check("no stray files in the working folder", after == before, str(after - before))
    # IPOPT prints it at each call, before it reads print_level 0 (plugin/run_control.cpp)
    check("IPOPT's 'Using option file' line is not printed (load steps through IPOPT)",
          "Using option file" not in output and "\n\n" not in output.strip(), output[:300])


def test_headless():
    """The README's literal command, the graphical FreeFem++ without -nw, on a machine without a
    display: with its output to a file and to a pipe it must exit 0 with the whole output (it
    used to die with SIGPIPE, exit 141, when ffglut could not open a display)."""
    o = out("headless file")
    log = os.path.join(TMP, "headless.log")
    with open(log, "w") as f:
        code = subprocess.run(["FreeFem++", "benchmarks/hertz_plane.edp", "-out", o], cwd=ROOT, env=headless_env(),
                              stdout=f, stderr=subprocess.STDOUT).returncode
    text = open(log).read()
    s = read_summary(o)
    check("headless, output to a file: exit 0", code == 0, f"exit {code}")
    check("headless, output to a file: the results are in the output and summary.json is complete",
          "  a = " in text and s is not None and s["complete"], text.strip().splitlines()[-1:])
    check("headless: IPOPT's 'Using option file' line is not printed (the condensed solve's IPOPT)",
          "Using option file" not in text, text[:300])
    proc = subprocess.run(["FreeFem++", "benchmarks/cube.edp", "-out", out("headless pipe")], cwd=ROOT, env=headless_env(),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    check("headless, output to a pipe: exit 0 with the results", proc.returncode == 0 and "  w = " in proc.stdout,
          f"exit {proc.returncode}")


def test_template_workspace():
    """docs/writing_your_own_problem.md: `make workspace DIR=...` (scripts/workspace.sh) copies the
    template driver into a folder outside the suite and writes the one setting (freefem++.pref);
    the template then runs there, and so does a suite driver given by its path. The template's
    own checks: force balance to 1e-8 of the indentation force (measured ~4e-13), no penetration."""
    work = os.path.join(TMP, "my_contact_work")
    proc = subprocess.run(["bash", os.path.join(ROOT, "scripts", "workspace.sh"), work], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    check("workspace: created with the template and freefem++.pref", proc.returncode == 0
          and os.path.exists(os.path.join(work, "my_problem.edp")) and os.path.exists(os.path.join(work, "freefem++.pref")),
          proc.stdout.strip().splitlines()[-1:])
    code, output, _ = run_driver("my_problem.edp", ["-depth", "0.2", "-steps", "2", "-h", "0.2"], os.path.join(work, "o"), cwd=work)
    s = read_summary(os.path.join(work, "o"))
    check("workspace: the template runs in its own folder", code == 0 and s is not None and s["complete"],
          output.strip().splitlines()[-2:])
    if s:
        r = s["results"]
        check("workspace: the template's indentation force balances to 1e-8, no penetration",
              r["force_balance_rel_error"]["computed"] <= 1e-8 and r["max_penetration"]["computed"] <= 1e-10 * 2
              and r["indentation_force"]["computed"] > 0, f"{r['force_balance_rel_error']['computed']:.1e}")
    # the template takes -nu 0.5 (exact incompressibility, its default -volumetric nodal); it used to
    # tell the user to add -volumetric nodal, then reject it as an unknown parameter
    code, output, _ = run_driver("my_problem.edp", ["-depth", "0.2", "-steps", "2", "-h", "0.2", "-nu", "0.5"],
                                 os.path.join(work, "o_incompressible"), cwd=work)
    s = read_summary(os.path.join(work, "o_incompressible"))
    check("workspace: the template runs at -nu 0.5, balanced to 1e-8", code == 0 and s is not None and s["complete"]
          and s["results"]["force_balance_rel_error"]["computed"] <= 1e-8, output.strip().splitlines()[-2:])
    code, output, _ = run_driver(os.path.join(ROOT, "benchmarks", "hertz_plane.edp"), ["-h", "0.004"], os.path.join(work, "hertz"),
                                 cwd=work)
    check("workspace: a suite driver runs from that folder by its path", code == 0, output.strip().splitlines()[-1:])


def test_external_commands():
    """Every external program the Makefile, scripts, tests and drivers call is either provided by
    scripts/install_deps.sh or part of a minimal Debian (tests/check_commands.py). On a bare Debian
    root `make test` used to fail on /usr/bin/time, which nothing installed."""
    import check_commands
    missing, found = check_commands.unprovided()
    check(f"external commands: the {len(found)} programs used are all provided", not missing, str(missing))


def include_files():
    """include/'s files, as paths relative to include/."""
    import glob as _glob
    paths = sorted(_glob.glob(os.path.join(ROOT, "include", "**", "*.idp"), recursive=True))
    return [os.path.relpath(p, os.path.join(ROOT, "include")) for p in paths]


def guard_of(rel):
    return "included" + "".join(p[:1].upper() + p[1:] for p in re.split(r"[\W_]", rel[:-4]))


def needs_of(text):
    """A file's header: whether it needs the driver's set-up, the suite files its Needs line names
    (a registry's member names its registry apart: 'R, which includes it'), and that registry."""
    header = "\n".join(l[2:] for l in text.splitlines() if l.startswith("//"))
    m = re.search(r"Needs:((?:[^.]|\.(?=idp|md))*)\.", header, re.S)
    needs = m.group(1) if m else ""
    registry = re.search(r"(\S+\.idp), which includes it", needs)
    if registry:
        needs = needs.replace(registry.group(0), "")
    files = re.findall(r"[\w/]+\.idp", needs.split("(docs/architecture.md")[-1] if "driver's set-up" in needs else needs)
    return "the driver's set-up" in needs, files, registry.group(1) if registry else None


# what a driver provides before model.idp (docs/architecture.md): the prelude and a law, a dimension
# file, the mesh Th and the vector space Vh
DRIVER_SETUP = ('include "prelude.idp"\nsetLinearElastic(1, 0.3);\ninclude "dim2.idp"\nmesh Th = square(3, 3);\n'
                'fespace Vh(Th, vectorFE(P1));\n')


def test_include_layout():
    """The layers (issues 27 and 41): every include/ file states what it needs, is guarded against a
    second inclusion (IFMACRO(!included<Path>) ... ENDIFMACRO; a file after the mesh first includes
    core/driver_setup.idp, the driver's set-up check), includes exactly the suite files its Needs
    line names, at its top; core/driver_setup.idp skips every file that includes it; contact does
    not reach into the body's rows; a driver that includes the prelude twice still runs;
    docs/reserved_names.md lists the names include/ defines (scripts/reserved_names.py); every
    line within 100 characters (issue 41)."""
    import glob as _glob
    files = include_files()
    check(f"layout: {len(files)} include files found", len(files) >= 40, str(len(files)))
    setup_users = []
    for rel in files:
        text = open(os.path.join(ROOT, "include", rel)).read()
        guard = guard_of(rel)
        code = [l for l in text.splitlines() if l.strip() and not l.startswith("//")]
        check(f"layout {rel}: states what it needs", "Needs:" in text)
        long_lines = [n + 1 for n, l in enumerate(text.splitlines()) if len(l) > 100]
        check(f"layout {rel}: lines within 100 characters", not long_lines, f"lines {long_lines[:5]}")
        if code[0] == 'include "core/driver_setup.idp"':
            setup_users.append(rel)
            code = code[1:]
        check(f"layout {rel}: guarded", code[:2] == [f"IFMACRO(!{guard})", f"macro {guard} 1 // EOM"]
              and code[-1] == "ENDIFMACRO", str(code[:2] + code[-1:]))
        includes = [i for i, l in enumerate(code) if l.startswith("include ")]
        # the registries include their members from a macro list at their top (laws, obstacles; the
        # laws' list one apply(...) per line)
        body_start = next((i for i, l in enumerate(code[2:], 2)
                           if not l.startswith(("include ", "load ", "macro ", "registered", "  apply("))), len(code))
        check(f"layout {rel}: includes at the top", all(i < body_start for i in includes), str(includes))
        setup, needed, _ = needs_of(text)
        included = [re.match(r'include "([^"]+)"', code[i]).group(1) for i in includes]
        included = [f for f in included if not f.startswith("laws/common") or rel != "laws/registry.idp"]
        if rel not in ("laws/registry.idp", "prelude.idp", "model.idp"):
            check(f"layout {rel}: includes what its Needs line names", sorted(set(needed)) == sorted(set(included)),
                  f"Needs {sorted(set(needed))}, includes {sorted(set(included))}")
        check(f"layout {rel}: a file needing the driver's set-up checks it first",
              setup == (rel in setup_users) or rel == "core/driver_setup.idp", f"{setup}")
    setup_text = open(os.path.join(ROOT, "include", "core", "driver_setup.idp")).read()
    listed = set(re.findall(r"^macro (included\w+) 1 // EOM", setup_text, re.M)) - {"includedCoreDriverSetup"}
    check("layout: core/driver_setup.idp skips exactly the files that include it",
          listed == {guard_of(r) for r in setup_users}, str(listed ^ {guard_of(r) for r in setup_users}))
    # every solver statistic the suite can set fits core/run.idp's table (FreeFEM's string arrays
    # do not grow): names given as literals only
    run_text = open(os.path.join(ROOT, "include", "core", "run.idp")).read()
    capacity = int(re.search(r"int solverStatisticMax = (\d+)", run_text).group(1))
    names, computed = set(), []
    for path in _glob.glob(os.path.join(ROOT, "include", "**", "*.idp"), recursive=True):
        code = "\n".join(l for l in open(path).read().splitlines() if not l.lstrip().startswith("//"))
        for call in re.findall(r"setSolverStatistic\(([^,]*),", code):
            if re.fullmatch(r'"\w+"', call.strip()):
                names.add(call.strip())
            elif "string name" not in call:
                computed.append(call)
    check(f"layout: the {len(names)} solver statistics fit the table ({capacity}), each a literal name",
          len(names) <= capacity and not computed, f"{len(names)} names, computed: {computed}")
    for path in _glob.glob(os.path.join(ROOT, "include", "contact", "**", "*.idp"), recursive=True):
        text = open(path).read()
        check(f"layout {os.path.relpath(path, ROOT)}: no reference to the body's volumetric rows",
              not re.search(r"volumetric(RowCount|FirstRow|Constrained)|vertexCount", text))
    work = out("include twice")
    os.makedirs(work)
    script = os.path.join(work, "twice.edp")
    open(script, "w").write('include "prelude.idp"\ninclude "prelude.idp"\ninclude "core/params.idp"\n'
                            'paramsDone();\ncout << "twice ok" << endl;\n')
    code, output, _ = run_driver(script, [], None)
    check("layout: a driver including the prelude twice runs", code == 0 and "twice ok" in output, output[-300:])
    proc = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "reserved_names.py")], stdout=subprocess.PIPE, text=True)
    check("layout: docs/reserved_names.md is current (scripts/reserved_names.py)",
          proc.returncode == 0 and proc.stdout == open(os.path.join(ROOT, "docs", "reserved_names.md")).read())


def test_include_alone():
    """Each include/ file, included alone after what its Needs line says a driver provides (the
    driver's set-up: DRIVER_SETUP; a registry's member through its registry), parses and runs its
    top level: its includes are its real contract, not model.idp's order (issue 41). Without the
    set-up, a file after the mesh stops at once with one line, exit code 2."""
    work = out("include alone")
    os.makedirs(work, exist_ok=True)
    for rel in include_files():
        setup, _, registry = needs_of(open(os.path.join(ROOT, "include", rel)).read())
        script = os.path.join(work, re.sub(r"\W", "_", rel) + ".edp")
        open(script, "w").write((DRIVER_SETUP if setup else "") + f'include "{registry or rel}"\n'
                                'cout << "alone ok" << endl;\n')
        code, output, _ = run_driver(script, [], None)
        check(f"alone {rel}: runs after {'the driver set-up' if setup else 'nothing'}",
              code == 0 and "alone ok" in output, output.strip().splitlines()[-2:])
    for rel in ("solve/sqp.idp", "model.idp"):
        script = os.path.join(work, "without_" + re.sub(r"\W", "_", rel) + ".edp")
        open(script, "w").write(f'include "prelude.idp"\ninclude "{rel}"\ncout << "not reached" << endl;\n')
        code, output, _ = run_driver(script, [], None)
        lines = [l for l in output.splitlines() if l.strip()]
        check(f"alone {rel} without a dimension file: one error line, exit 2",
              code == 2 and len(lines) == 1 and lines[0].startswith("error:") and "dimension file" in lines[0],
              f"exit {code}: {lines[:3]}")


def test_check_driver():
    """`make check-driver F=...` (scripts/check_driver.py): a driver declaring `int floor` at its top
    (issue 41: FreeFEM's floor() hidden, the error reported inside a solver file) is warned about on
    its line, as is one reusing a suite name inside a block; exit 1. Every shipped driver, the
    template and the tests' own .edp files hide nothing: exit 0. A missing file: exit 2."""
    work = os.path.join(TMP, "check_driver")
    os.makedirs(work, exist_ok=True)
    driver = os.path.join(work, "clash.edp")
    with open(driver, "w") as f:
        f.write('include "prelude.idp"\nint floor = 2;\nreal nu = 0.3;\n{\n  real[int] contactNodalActive(3);\n}\n')
    proc = subprocess.run(["make", "--no-print-directory", "check-driver"], cwd=ROOT, env=dict(os.environ, F=driver),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    warnings = [l for l in proc.stdout.splitlines() if l.startswith("warning:")]
    check("check-driver: int floor named with its line 2 and FreeFEM's floor",
          any(f"{driver}:2: 'floor' hides FreeFEM's built-in floor" in w for w in warnings), str(warnings))
    check("check-driver: a suite name inside a block named with its line 5 and its file",
          any(":5: 'contactNodalActive' hides the suite's" in w and "include/contact/" in w for w in warnings), str(warnings))
    check("check-driver: nu (no clash) not named, two warnings", len(warnings) == 2, str(warnings))
    check("check-driver: exit code non-zero with a clash (make passes the script's 1 on)", proc.returncode != 0, str(proc.returncode))
    shipped = sorted(glob.glob(os.path.join(ROOT, "benchmarks", "*.edp")) + glob.glob(os.path.join(ROOT, "tests", "*.edp"))
                     + [os.path.join(ROOT, "docs", "template", "my_problem.edp")])
    for path in shipped:
        proc = subprocess.run([sys.executable, "scripts/check_driver.py", path], cwd=ROOT,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        check(f"check-driver: {os.path.relpath(path, ROOT)} hides nothing (exit 0)", proc.returncode == 0, proc.stdout.strip()[-300:])
    proc = subprocess.run([sys.executable, "scripts/check_driver.py", os.path.join(work, "missing.edp")], cwd=ROOT,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    check("check-driver: a missing file is one error line, exit 2",
          proc.returncode == 2 and proc.stdout.startswith("error:"), proc.stdout)


def test_allocator_keeps_blocks():
    """plugin/run_control.cpp tells glibc's malloc, as it loads, to keep freed blocks for the next
    (issue 43: every factorization's factors and every tangent's arrays had their pages faulted in
    anew; at 200k dofs a factorization 15.1 s -> 12.0 s). allocator_check.edp: a second array of
    160 MB reuses the first's pages (its bounds there)."""
    check_script_cases("allocator_check", 2, prefix="allocator_check case=")


def test_progress_lines_live():
    """Progress lines reach a pipe as they are printed (`FreeFem++ ... | tee run.log`):
    plugin/run_control.cpp makes the standard output line-buffered as it loads (FreeFEM's endl does
    not flush; a 200k dofs run's step lines had shown minutes late). live_output_check.edp prints a
    line, then waits until a flag file exists, which this test creates only once it has read that
    line: read while the script still runs, or not at all within 60 s (the line buffered)."""
    import queue
    import threading
    folder = out("live_output")
    os.makedirs(folder, exist_ok=True)
    flag = os.path.join(folder, "flag")
    if os.path.exists(flag):
        os.remove(flag)
    proc = subprocess.Popen(["FreeFem++", "-nw", "tests/live_output_check.edp", "-flag", flag], cwd=ROOT,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    lines = queue.Queue()
    threading.Thread(target=lambda: [lines.put(l) for l in proc.stdout] + [lines.put(None)], daemon=True).start()
    live = False
    try:
        while True:
            line = lines.get(timeout=60)
            if line is None:
                break
            if line.startswith("live_output_check: waiting"):
                live = proc.poll() is None
                break
    except queue.Empty:
        pass
    open(flag, "w").close()
    proc.wait(timeout=300)
    rest = []
    while True:
        try:
            line = lines.get(timeout=10)
        except queue.Empty:
            break
        if line is None:
            break
        rest.append(line)
    check("the progress line was read from the pipe while the script still ran", live)
    check("the script ended once the flag existed, exit 0",
          proc.returncode == 0 and any(l.startswith("live_output_check: done") for l in rest),
          f"exit {proc.returncode}")
