#!/usr/bin/env python3
"""Bad input for every driver: the cases the test suite checks (one `error:` line naming the
problem, a non-zero exit, no summary.json) and the table in docs/robustness.md, printed by
    python3 tests/bad_inputs.py"""

import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
from freefem import run_driver  # noqa: E402

CUBE, PLANE, CIRCLE = "benchmarks/cube.edp", "benchmarks/hertz_plane.edp", "benchmarks/hertz_circle.edp"
SPHERE, CLAMPED, ORING = "benchmarks/hertz_sphere.edp", "benchmarks/clamped_square.edp", "benchmarks/oring.edp"
PLATEN, TUBE, TORUS = "benchmarks/platen_block.edp", "benchmarks/rivlin_tube.edp", "benchmarks/oring_torus.edp"
CYLINDERS, SPHERES = "benchmarks/hertz_two_cylinders.edp", "benchmarks/hertz_two_spheres.edp"
FLANGE, SLIDING = "benchmarks/oring_flange.edp", "benchmarks/sliding_disc.edp"
INDENTATION, CATTANEO, BAR = "benchmarks/indentation.edp", "benchmarks/cattaneo.edp", "benchmarks/bar_impact.edp"
PATCH, SPHERE_IMPACT, BARS = "benchmarks/patch_test.edp", "benchmarks/sphere_impact.edp", "benchmarks/bars_head_on.edp"
DISCS, MINDLIN = "benchmarks/discs_head_on.edp", "benchmarks/mindlin_sphere.edp"
SEAL, GASKET = "benchmarks/seal.edp", "benchmarks/gasket.edp"

# (driver, arguments ({tmp} is a scratch folder holding the files of make_files), the word the
# error line must contain)
CASES = [
    (CUBE, ["-nu", "0.5", "-volumetric", "penalty"], "-nu"),
    (CUBE, ["-nu", "0.6"], "-nu"),
    (CUBE, ["-volumetric", "soft"], "-volumetric"),
    (CUBE, ["-nu", "-1"], "-nu"),
    (CUBE, ["-C10", "-1"], "-C10"),
    (CUBE, ["-C10", "0", "-C01", "0"], "-C10"),
    (CUBE, ["-pressure", "abc"], "-pressure"),
    (CUBE, ["-dim", "4"], "-dim"),
    (CUBE, ["-n", "0"], "-n"),
    (CUBE, ["-nuu", "0.3"], "-nuu"),
    (CUBE, ["-material", "rubber"], "-material"),
    (CUBE, ["-nu", "0.3", "-nu", "0.4"], "-nu"),
    (CUBE, ["-steps", "1.5"], "-steps"),
    (PLANE, ["-R", "0"], "-R"),
    (PLANE, ["-condense", "maybe"], "-condense"),
    (PLANE, ["-krylov", "maybe"], "-krylov"),
    (PLANE, ["-factors", "half"], "-factors"),
    (PLANE, ["-anderson", "11"], "-anderson"),
    (PLANE, ["-anderson", "1.5"], "-anderson"),
    (PLANE, ["-reuse", "1"], "-reuse"),
    (PLANE, ["-E", "-2e9"], "-E"),
    (PLANE, ["-pressure", "0"], "-pressure"),
    (PLANE, ["-constraint", "exakt"], "-constraint"),
    (PLANE, ["-material", "steel"], "-material"),
    (PLANE, ["-h", "0"], "-h"),
    (PLANE, ["-zone", "2"], "-zone"),
    (PLANE, ["-gap", "-1e-3"], "penetrates"),
    (PLANE, ["-mesh", "{tmp}/missing.msh"], "-mesh"),
    (PLANE, ["-mu", "-1"], "-mu"),
    (PLANE, ["-mu", "abc"], "-mu"),
    (PLANE, ["-mu", "0.3", "-g", "1"], "-g"),
    (PLANE, ["-friction", "tresca"], "-g"),
    (PLANE, ["-friction", "stick"], "-friction"),
    (PLANE, ["-mu", "0.3", "-facets", "2"], "-facets"),
    (BAR, ["-dt", "0"], "-dt"),
    (BAR, ["-dim", "axi"], "-dim"),
    (BAR, ["-dt", "-1e-6"], "-dt"),
    (BAR, ["-tend", "1e-9"], "-tend"),
    (BAR, ["-tend", "1"], "-tend"),
    (BAR, ["-rho", "0"], "-rho"),
    (BAR, ["-scheme", "leapfrog"], "-scheme"),
    (BAR, ["-mass", "diagonal"], "-mass"),
    (BAR, ["-v0", "inf"], "-v0"),
    (SPHERE_IMPACT, ["-v0", "0"], "-v0"),
    (SPHERE_IMPACT, ["-material", "mooney"], "-material"),
    (SPHERE_IMPACT, ["-dt", "0"], "-dt"),
    (SPHERE_IMPACT, ["-zone", "1e-5"], "-zone"),
    (SPHERE_IMPACT, ["-rho", "-1"], "-rho"),
    (SPHERE_IMPACT, ["-dim", "2"], "-dim"),
    (SPHERE_IMPACT, ["-dim", "3", "-candidates", "1e-5"], "-candidates"),
    (BARS, ["-gap", "1"], "-gap"),
    (BARS, ["-nA", "1"], "-nA"),
    (BARS, ["-tend", "0"], "-tend"),
    (DISCS, ["-gap", "0.01"], "-gap"),
    (DISCS, ["-v0", "-1"], "-v0"),
    (DISCS, ["-tend", "0"], "-tend"),
    (DISCS, ["-dim", "2"], "-dim"),
    (DISCS, ["-dim", "3", "-candidates", "1e-5"], "-candidates"),
    (MINDLIN, ["-mu", "0", "-steps", "3"], "-steps"),
    (MINDLIN, ["-friction", "tresca", "-g", "0.1"], "-friction"),
    (MINDLIN, ["-ratio", "1.5"], "-ratio"),
    (MINDLIN, ["-steps", "0"], "-steps"),
    (MINDLIN, ["-setup", "rigid", "-block", "5"], "-block"),
    (MINDLIN, ["-constraint", "exact"], "-constraint"),
    (PATCH, ["-n1", "0"], "-n1"),
    (PATCH, ["-pass", "three"], "-pass"),
    (PATCH, ["-pressure", "-1"], "-pressure"),
    (CATTANEO, ["-mu", "0", "-hold", "2"], "-hold"),
    (CATTANEO, ["-friction", "tresca", "-g", "0.1"], "-friction"),
    (CATTANEO, ["-ratio", "1.2"], "-ratio"),
    (CATTANEO, ["-setup", "flat"], "-setup"),
    (CATTANEO, ["-travel", "0.1", "-hold", "3"], "-travel"),
    (PLANE, ["-mesh", "{tmp}/corrupt.msh"], "-mesh"),
    (CIRCLE, ["-R2", "0"], "-R2"),
    (CIRCLE, ["-R", "-1"], "-R"),
    (CIRCLE, ["-spline", "2"], "-spline"),
    (CIRCLE, ["-splinepoints", "3"], "at least 4 points"),
    (CIRCLE, ["-splinefile", "{tmp}/missing.txt"], "-splinefile"),
    (CIRCLE, ["-splinefile", "{tmp}/decreasing.txt"], "increase"),
    (CIRCLE, ["-splinefile", "{tmp}/garbled.txt"], "-splinefile"),
    (CIRCLE, ["-gap", "-1e-3", "-spline", "0"], "penetrates"),
    (SPHERE, ["-R", "0"], "-R"),
    (SPHERE, ["-pressure", "-1"], "-pressure"),
    (SPHERE, ["-mesh", "{tmp}/disc2d.msh"], "-mesh"),
    (SPHERE, ["-dim", "2"], "-dim"),
    (SPHERE, ["-axisymmetric", "1"], "-axisymmetric"),
    (SPHERE, ["-dim", "axi", "-mesh", "{tmp}/disc2d.msh"], "-mesh"),
    (SPHERE, ["-candidates", "-0.1"], "-candidates"),
    (CYLINDERS, ["-nu1", "0.5"], "-nu1"),
    (CYLINDERS, ["-E2", "0"], "-E2"),
    (CYLINDERS, ["-R2", "-1"], "-R2"),
    (CYLINDERS, ["-slave", "middle"], "-slave"),
    (CYLINDERS, ["-constraint", "finite"], "-constraint"),
    (CYLINDERS, ["-normal", "slave"], "-normal"),
    (CYLINDERS, ["-gap", "-1e-3"], "overlap"),
    (SPHERES, ["-nu2", "0.7"], "-nu2"),
    (SPHERES, ["-E1", "-1"], "-E1"),
    (SPHERES, ["-zone", "0.9"], "-zone"),
    (SPHERES, ["-constraint", "large"], "-constraint"),
    (FLANGE, ["-Ef", "0"], "-Ef"),
    (FLANGE, ["-nuf", "0.5"], "-nuf"),
    (FLANGE, ["-nu", "0.5"], "-nu"),
    (FLANGE, ["-W", "0.6"], "-W"),
    (FLANGE, ["-T", "-1"], "-T"),
    (FLANGE, ["-C10", "0"], "-C10"),
    (FLANGE, ["-cmax", "1.2"], "-cmax"),
    (FLANGE, ["-constraint", "finite"], "-constraint"),
    (INDENTATION, ["-dim", "2"], "-dim"),
    (INDENTATION, ["-block", "2"], "-block"),
    (INDENTATION, ["-depth", "0.8"], "-depth"),
    (INDENTATION, ["-h", "0.5"], "-h"),
    (INDENTATION, ["-nu", "0.5", "-volumetric", "penalty"], "-nu"),
    (CUBE, ["-compression", "0.2", "-pressure", "3"], "-compression"),
    (CUBE, ["-load", "dead"], "-load"),
    (CUBE, ["-perturb", "0.5"], "-perturb"),
    (SLIDING, ["-E1", "0"], "-E1"),
    (SLIDING, ["-nu", "0.5"], "-nu"),
    (SLIDING, ["-press", "0.1"], "-press"),
    (SLIDING, ["-L", "0.6"], "-L"),
    (SLIDING, ["-slidesteps", "2"], "-slidesteps"),
    (SLIDING, ["-h", "0.5"], "-h"),
    (CLAMPED, ["-rho", "0"], "-rho"),
    (CLAMPED, ["-E", "0"], "-E"),
    (CLAMPED, ["-order", "3"], "-order"),
    (CLAMPED, ["-n", "0"], "-n"),
    (CLAMPED, ["-volumetric", "nodal"], "P1"),
    (ORING, ["-case", "pipe"], "-case"),
    (ORING, ["-C10", "0"], "-C10"),
    (ORING, ["-nu", "0.5", "-volumetric", "penalty"], "-nu"),
    (ORING, ["-cmax", "1"], "-cmax"),
    (ORING, ["-side", "0.5"], "-side"),
    (SEAL, ["-pressure", "-1"], "-pressure"),
    (SEAL, ["-pressure", "30"], "-pressure"),
    (SEAL, ["-clearance", "0.5"], "-clearance"),
    (SEAL, ["-corner", "0.96"], "-corner"),
    (SEAL, ["-radius", "2"], "-radius"),
    (SEAL, ["-dim", "axi", "-radius", "0"], "-radius"),
    (SEAL, ["-refine", "0"], "-refine"),
    (SEAL, ["-bracket", "21"], "-bracket"),
    (SEAL, ["-seal", "rod"], "-seal"),
    (SEAL, ["-stroke", "0.1"], "-stroke"),
    (SEAL, ["-pressure", "0", "-stroke", "0.1"], "-stroke"),
    (SEAL, ["-dim", "axi", "-seal", "rod", "-pressure", "0", "-stroke", "0.1", "-friction", "tresca", "-g", "0.1"], "-stroke"),
    (SEAL, ["-mu", "0.3", "-bracket", "2"], "-bracket"),
    (SEAL, ["-pressure", "0", "-cycles", "0"], "-cycles"),
    (SEAL, ["-dim", "axi", "-seal", "rod", "-radius", "1"], "-radius"),
    (GASKET, ["-pressure", "-1"], "-pressure"),
    (GASKET, ["-squeeze", "0.6"], "-squeeze"),
    (GASKET, ["-W", "1e6"], "-h"),
    (GASKET, ["-bracket", "-1"], "-bracket"),
    (ORING, ["-h", "1"], "-h"),
    (PLATEN, ["-nu", "0.5"], "-nu"),
    (TUBE, ["-inner", "0.9"], "-inner"),
    (TORUS, ["-meanradius", "0.3"], "-meanradius"),
    (TORUS, ["-holdcentre", "2"], "-holdcentre"),
    (TORUS, ["-case", "radial", "-holdcentre", "1"], "-holdcentre"),
    (TORUS, ["-stretch", "-0.1"], "-stretch"),
    (TORUS, ["-nu", "0.5", "-volumetric", "penalty"], "-nu"),
    (TUBE, ["-B", "0.5"], "-B"),
    (TUBE, ["-nu", "0.5", "-volumetric", "penalty"], "-nu"),
    (PLATEN, ["-push", "0.3"], "-push"),
    (PLATEN, ["-waves", "0"], "-waves"),
    (PLATEN, ["-floormargin", "-0.1"], "-floormargin"),
    # numbers out of range (issue 26): non-finite, overflowing, or out of the problem's scale
    (CUBE, ["-pressure", "1e400"], "-pressure"),
    (CUBE, ["-pressure", "inf"], "-pressure"),
    (CUBE, ["-pressure", "nan"], "-pressure"),
    (CUBE, ["-pressure", "1" + "0" * 400], "-pressure"),
    (CUBE, ["-pressure", "1e308"], "-pressure"),
    (CUBE, ["-pressure", "1e-12"], "-pressure"),
    (CUBE, ["-pressure", "6e-6"], "-pressure"),
    (CUBE, ["-n", "1000000000000"], "-n"),
    (CUBE, ["-dim", "3", "-n", "80"], "-n"),
    (PLANE, ["-pressure", "1e-12"], "too small"),
    (PLANE, ["-E", "1e309"], "-E"),
    (PLANE, ["-E", "1e-12"], "too large"),
    (PLANE, ["-h", "1e-5", "-zone", "0.5"], "-h"),
    (CIRCLE, ["-R2", "1e7"], "-R2"),
    (CIRCLE, ["-splinepoints", "1000000000"], "-splinepoints"),
    (CYLINDERS, ["-gap", "1e308"], "-gap"),
    (CYLINDERS, ["-gap", "1e400"], "-gap"),
    (CYLINDERS, ["-gap", "2"], "-gap"),
    (CYLINDERS, ["-R2", "1e308"], "-R2"),
    (CYLINDERS, ["-R2", "1e400"], "-R2"),
    (CYLINDERS, ["-pressure", "3e5"], "too large"),
    (SPHERE, ["-dim", "axi", "-pressure", "1e6"], "too large"),
    (SPHERE, ["-pressure", "1e-9"], "too small"),
    (SPHERES, ["-E1", "1e-12"], "-E1"),
    (TORUS, ["-C10", "1e308"], "-C10"),
    (TORUS, ["-meanradius", "5" * 400], "-meanradius"),
    (SLIDING, ["-E1", "1e-12"], "-E1"),
    (ORING, ["-cmax", "1e-9"], "-cmax"),
    (ORING, ["-h", "1e-4"], "-h"),
    (TUBE, ["-inner", "1.0000000001"], "-inner"),
    (PLATEN, ["-push", "1e-9"], "-push"),
    (INDENTATION, ["-dim", "3", "-h", "0.001", "-depth", "0.5"], "-h"),
    (CLAMPED, ["-n", "5000"], "-n"),
    # hostile paths: refused at parse time, nothing run (a shell would have created 'pwned')
    (PLANE, ["-out", "{tmp}/o';touch pwned;'"], "-out"),
    (PLANE, ["-out", "-rf"], "-out"),
    (PLANE, ["-out", "{tmp}/new\nline"], "-out"),
    (PLANE, ["-mesh", "{tmp}/m';touch pwned;'.msh"], "-mesh"),
    (SPHERE, ["-mesh", "--help"], "-mesh"),
    (CIRCLE, ["-splinefile", "{tmp}/s\";touch pwned;\".txt"], "-splinefile"),
    # corrupt meshes, validated before use; the built-in mesh's sizes are refused with -mesh
    (PLANE, ["-mesh", "{tmp}/node999999.msh"], "999999"),
    (PLANE, ["-mesh", "{tmp}/nan.msh"], "finite"),
    (PLANE, ["-mesh", "{tmp}/degenerate.msh"], "degenerate"),
    (PLANE, ["-mesh", "{tmp}/noboundary.msh"], "boundary"),
    (SPHERE, ["-mesh", "{tmp}/flat_tet.msh"], "degenerate"),
    (PLANE, ["-mesh", "{tmp}/square.msh", "-h", "0.01"], "-h"),
    (SPHERE, ["-mesh", "{tmp}/flat_tet.msh", "-zone", "0.1"], "-zone"),
    # issue 42: a -tol loose enough that the contact set spreads with every check passing, a floor
    # the mesh cannot resolve, more load steps than a run takes (their records were cut at 1000)
    (PLANE, ["-tol", "1e-3", "-condense", "no"], "-tol"),
    (PLATEN, ["-waves", "1000000"], "-waves"),
    (PLATEN, ["-splinepoints", "20"], "-splinepoints"),
    (CUBE, ["-steps", "1500"], "-steps"),
    # issue 42: runaway work refused before meshing (GBs of memory, hours of load steps)
    (PATCH, ["-H", "1e5", "-n1", "20", "-n2", "20"], "-H"),
    (PATCH, ["-n1", "2000", "-n2", "2000"], "-n1"),
    (ORING, ["-steps", "100000"], "-steps"),
    (CATTANEO, ["-steps", "1000000"], "-steps"),
    (BAR, ["-n", "20000", "-ny", "1000"], "-n"),
    # issue 42: FreeFEM's own errors, each now one line (Div by 0, border points too close, Strange
    # catch exception, an assertion; a mesh inverted or 1000 times too large reached the solver)
    (BAR, ["-v0", "0"], "-v0"),
    (BARS, ["-v0", "0"], "-v0"),
    (BARS, ["-n", "0"], "-n"),
    (CATTANEO, ["-zone", "0"], "-zone"),
    (FLANGE, ["-T", "1e-30"], "-T"),
    (PLANE, ["-mesh", "{tmp}/a_folder"], "-mesh"),
    (SPHERE, ["-mesh", "{tmp}/a_folder"], "-mesh"),
    (PLANE, ["-mesh", "{tmp}/clockwise.msh"], "clockwise"),
    (SPHERE, ["-mesh", "{tmp}/inverted_tet.msh"], "inverted"),
    (PLANE, ["-mesh", "{tmp}/thousandfold.msh"], "factor 2"),
    # issue 42: messages name the parameter the user gave, quote its value as typed and shortened
    (BARS, ["-n", "-5"], "-n"),
    (INDENTATION, ["-depth", "1e-9"], "-depth"),
    (SPHERES, ["-R1", "1e-30"], "-R1"),
    (CUBE, ["-nu", "0.5000001", "-volumetric", "nodal"], "0.5000001"),
    (CUBE, ["-nu", "0.4999999999"], "-nu"),
    (CUBE, ["-material", "x" * 5000], "(5000 characters)"),
    (CIRCLE, ["-splinefile", "{tmp}/a_folder"], "-splinefile"),
    (BAR, ["-dt", "1e-12"], "-dt"),
]


def make_files(tmp):
    """The bad files some cases read: a truncated mesh, a 2D mesh for the 3D driver, spline
    data that goes backwards or holds a non-number."""
    with open(os.path.join(tmp, "corrupt.msh"), "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n1 0 0 0\n2 1 0 0\n")
    with open(os.path.join(tmp, "disc2d.msh"), "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
                "$Elements\n1\n1 2 2 1 1 1 2 3\n$EndElements\n")
    square = ("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 {x4} 1 0\n$EndNodes\n"
              "$Elements\n{count}\n1 2 2 1 1 1 2 3\n2 2 2 1 1 1 3 {t2}\n{lines}$EndElements\n")
    lines = "3 1 2 3 3 1 2\n4 1 2 2 2 2 3\n5 1 2 2 2 3 4\n6 1 2 1 1 4 {e6}\n"
    for name, x4, t2, e6, with_lines in (("square", "0", "4", "1", True), ("node999999", "0", "4", "999999", True),
                                         ("nan", "nan", "4", "1", True), ("degenerate", "0", "1", "1", True),
                                         ("noboundary", "0", "4", "1", False)):
        with open(os.path.join(tmp, name + ".msh"), "w") as f:
            f.write(square.format(x4=x4, t2=t2, count=6 if with_lines else 2,
                                  lines=lines.format(e6=e6) if with_lines else ""))
    with open(os.path.join(tmp, "flat_tet.msh"), "w") as f:   # four nodes in one plane
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 1 1 0\n$EndNodes\n"
                "$Elements\n2\n1 2 2 1 1 1 2 3\n2 4 2 1 1 1 2 3 4\n$EndElements\n")
    # issue 42: clockwise triangles (FreeFEM's "Assertion fail: (area > 0)"), an inverted
    # tetrahedron (FreeFEM's "Error of mesh orientation") and a mesh 1000 times too large (it
    # reached the solver, exit 3)
    with open(os.path.join(tmp, "clockwise.msh"), "w") as f:
        f.write(square.format(x4="0", t2="4", count=6, lines=lines.format(e6="1"))
                .replace("1 2 2 1 1 1 2 3\n2 2 2 1 1 1 3 4", "1 2 2 1 1 1 3 2\n2 2 2 1 1 1 4 3"))
    with open(os.path.join(tmp, "thousandfold.msh"), "w") as f:
        f.write(square.format(x4="0", t2="4", count=6, lines=lines.format(e6="1"))
                .replace("2 1 0 0\n3 1 1 0\n4 0 1 0", "2 1000 0 0\n3 1000 1000 0\n4 0 1000 0"))
    with open(os.path.join(tmp, "inverted_tet.msh"), "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
                "4 0 0 1\n$EndNodes\n$Elements\n2\n1 2 2 1 1 1 2 3\n2 4 2 1 1 1 3 2 4\n"
                "$EndElements\n")
    os.makedirs(os.path.join(tmp, "a_folder"), exist_ok=True)
    with open(os.path.join(tmp, "decreasing.txt"), "w") as f:
        f.write("0 0\n0.1 -0.01\n0.05 -0.002\n0.2 -0.03\n0.3 -0.04\n")
    with open(os.path.join(tmp, "garbled.txt"), "w") as f:
        f.write("# x y\n0 0\n0.1 abc\n")


def run_case(driver, args, tmp, out_dir):
    """(exit code, the first output line, whether a summary.json was left)."""
    args = [a.replace("{tmp}", tmp) for a in args]
    if "-out" in args:   # the case is about -out itself: the run must not write to out_dir either
        code, output, _ = run_driver(driver, args, None)
    else:
        code, output, _ = run_driver(driver, args, out_dir)
    first = output.strip().splitlines()[0] if output.strip() else ""
    return code, first, os.path.exists(os.path.join(out_dir, "summary.json"))


def main():
    tmp = tempfile.mkdtemp(prefix="bad-input-")
    make_files(tmp)
    print("| driver | input | message | exit code |\n|---|---|---|---|")
    for i, (driver, args, _) in enumerate(CASES):
        code, first, _ = run_case(driver, args, tmp, os.path.join(tmp, f"out{i}"))
        shown = " ".join(a if len(a) <= 40 else f"{a[:4]}...({len(a)} characters)" for a in args).replace(tmp, "/tmp").replace("\n", "\\n")
        message = first.replace(tmp, "/tmp").replace("|", "\\|")
        print(f"| {os.path.basename(driver)} | `{shown}` | `{message}` | {code} |")


if __name__ == "__main__":
    main()
