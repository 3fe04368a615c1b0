"""Peer benchmark: the Hertz plane-strain contact of benchmarks/hertz_plane.edp solved by DOLFINx.

The problem is the one of hertz_plane.edp with its defaults: the quarter of the disc of radius
R = 1 m, centre (0, R), pressed by a pressure f = 2.75 MPa on its top face (boundary label 2)
onto the rigid plane y = 0; linear elasticity in plane strain (E = 2.1 GPa, nu = 0.3), P1
vector elements, u_x = 0 on the symmetry axis x = 0 (label 1), and the frictionless contact
condition y + u_y >= 0 at the vertices of boundary label 3 (the arc near the origin). The
vertical rigid motion of the body is held by the contact alone.

Same discrete problem as our suite, different solver:
  * the mesh is the project's own: FreeFem++ runs scripts/performance/hertz_mesh.edp (quarterDiscMesh with
    hertz_plane.edp's parameters) and saves it as a FreeFEM .msh file, which is read here and
    handed to dolfinx.mesh.create_mesh; the boundary labels are carried over through the
    original vertex numbers (DOLFINx renumbers vertices);
  * the contact condition is a bound on the y-dofs of the candidate nodes, u_y >= -y, solved by
    PETSc's reduced-space variational-inequality Newton (SNES vinewtonrsls) with a direct
    MUMPS LU factorisation of the reduced Jacobian at every iteration. The problem is linear
    apart from the bounds, so the stiffness K and load vector b are assembled once; the
    residual is F(u) = K u - b (Dirichlet rows: u_x itself);
  * the pressure post-processing replicates include/contact/report.idp and
    include/report/hertz_report.idp (computeContactPressure, fitEllipticalPressure,
    pressureL2RelativeError): nodal force = the residual of the elastic equations at the
    candidate's y-dof (the obstacle's reaction, positive in compression), divided by the
    node's lumped weight on the label-3 boundary (half of each adjacent label-3 edge);
    active when the gap y + u_y <= 1e-9 * body size; p^2 = p_max^2 (1 - x^2/a^2) fitted by
    least squares over the active nodes with x <= last active x - 1e-3 h; the relative L2
    error of the nodal pressures against Hertz with the lumped weights as quadrature.

Initial guess. The body's vertical rigid motion is held by the contact alone, and PETSc's
reduced-space method counts a bounded dof as active only when it lies on its bound with a
strictly positive residual. At u = 0 the origin touches the plane but carries no force yet
(F = 0 there), so the first reduced Jacobian is singular (the rigid translation is free) and
the iteration wanders off (DIVERGED_LINE_SEARCH, or contact lost). The default start is
therefore the rigid approach u_y = -c f R / E everywhere (c = 1, --approach-factor), which
SNES projects onto the bounds: the candidates within about a of the origin start on the plane.
--start zero keeps the u = 0 start for comparison.

Solver settings (see --help): snes_rtol 1e-10 (atol and stol off); snes_vi_zero_tolerance
1e-12 f R / E instead of PETSc's absolute 1e-8 m (displacements here are ~1e-3 m); PETSc's
default backtracking line search; MUMPS with its default ordering. Other PETSc options for
the solver: --petsc NAME=VALUE (e.g. --petsc mat_mumps_icntl_7=0 for AMD).

Run it with Debian's Python (python3-dolfinx 0.5.2 is a Debian package), from anywhere:
    OMP_NUM_THREADS=1 /usr/bin/python3 scripts/peers/dolfinx_hertz.py --h 0.001836226277597457
    OMP_NUM_THREADS=1 /usr/bin/python3 scripts/peers/dolfinx_hertz.py --h 0.00068858484625
    /usr/bin/python3 scripts/peers/dolfinx_hertz.py --h a/30 --mesh-only-from /tmp/hertz.msh
--h is the element size in the contact zone, in metres or as a/N with Hertz's exact a (a/30
is hertz_plane.edp's default h); scripts/performance/studies.py's levels use a rounded to 0.0550867877, so
pass its h = 0.0550867877/N as a number to get the same meshes. --h sets the mesh and the fit
margin as in hertz_plane.edp. Without --mesh-only-from the script calls FreeFem++ (timed
apart as freefem_mesh_s); with it, the file must be the mesh of that h. The first run also
compiles the forms (forms_s; cached in ~/.cache/fenics afterwards).
It prints one line "RESULT {json}": sizes, SNES iterations and converged reason, the time
split (mesh read and creation, form compilation, assembly and solver setup, SNES solve,
post-processing, and total_wall_s: the process's wall time since its start, imports
included), a, p_max and their relative errors against Hertz, the pressure's relative L2
error, the contact force against the applied f R, and checks of the solution (equilibrium
residual, penetration, smallest active pressure, largest force at an inactive candidate).
Exit status: 0, 1 on bad input or missing dolfinx, 3 when SNES fails or the Hertz report
cannot be made (the RESULT line then has an "error" field).
"""
import time

SCRIPT_START = time.perf_counter()

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))   # scripts/peers/ -> the suite
MESH_SCRIPT = os.path.join("bench", "hertz_mesh.edp")

# hertz_plane.edp's defaults (m, Pa)
YOUNG_MODULUS = 2.1e9
POISSON_RATIO = 0.3
DISC_RADIUS = 1.0
TOP_PRESSURE = 2.75e6

SYMMETRY_LABEL, TOP_LABEL, CONTACT_LABEL, FREE_ARC_LABEL = 1, 2, 3, 4


def seconds_since_process_start():
    """Wall time since the process started (interpreter start-up included, 10 ms resolution),
    or since this module's first line where /proc is not available."""
    try:
        with open("/proc/self/stat") as stat:
            fields_after_name = stat.read().rsplit(")", 1)[1].split()
        start_ticks = int(fields_after_name[19])  # field 22 of proc(5), "starttime"
        with open("/proc/uptime") as uptime:
            seconds_since_boot = float(uptime.read().split()[0])
        return seconds_since_boot - start_ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return time.perf_counter() - SCRIPT_START


def hertz_half_width():
    """a = sqrt(8 f R Reff (1 - nu^2) / (pi E)), Reff = R for the plane (analytic/hertz.idp)."""
    return math.sqrt(8 * TOP_PRESSURE * DISC_RADIUS * DISC_RADIUS * (1 - POISSON_RATIO**2)
                     / (math.pi * YOUNG_MODULUS))


def hertz_peak_pressure(half_width):
    return 4 * TOP_PRESSURE * DISC_RADIUS / (math.pi * half_width)


def hertz_pressure(x, half_width, peak_pressure):
    inside = np.abs(x) < half_width
    return np.where(inside, peak_pressure * np.sqrt(np.clip(1 - (x / half_width) ** 2, 0, None)), 0.0)


def parse_element_size(text):
    """A length in metres, or "a/N" for Hertz's half-width over N."""
    if text.startswith("a/"):
        return hertz_half_width() / float(text[2:])
    return float(text)


def parse_arguments():
    parser = argparse.ArgumentParser(description="Hertz plane-strain contact (hertz_plane.edp) with DOLFINx and PETSc SNES VI.")
    parser.add_argument("--h", default="a/30", help="element size in the contact zone: metres, or a/N (default a/30)")
    parser.add_argument("--mesh-only-from", metavar="FILE", help="read this FreeFEM .msh file instead of running FreeFem++")
    parser.add_argument("--start", choices=("zero", "approach"), default="approach",
                        help="initial guess: u = 0 (touching at the origin), or the rigid approach u_y = -c f R / E")
    parser.add_argument("--approach-factor", type=float, default=1.0, help="c of --start approach (default 1)")
    parser.add_argument("--snes-rtol", type=float, default=1e-10, help="SNES relative tolerance (default 1e-10)")
    parser.add_argument("--snes-atol", type=float, default=1e-50, help="SNES absolute tolerance (default 1e-50: off)")
    parser.add_argument("--vi-zero-tolerance", type=float, default=None,
                        help="distance to a bound under which a dof counts as on it (PETSc's default 1e-8 m; "
                             "default here 1e-12 f R / E)")
    parser.add_argument("--snes-max-it", type=int, default=100)
    parser.add_argument("--petsc", action="append", default=[], metavar="NAME=VALUE",
                        help="extra PETSc option for the solver (prefix hertz_ is added), repeatable")
    parser.add_argument("--monitor", action="store_true", help="print SNES's residual history on stderr")
    parser.add_argument("--pressure-csv", metavar="FILE", help="write the candidates' gaps and pressures (sorted by x)")
    arguments = parser.parse_args()
    try:
        arguments.element_size = parse_element_size(arguments.h)
    except ValueError:
        parser.error("--h must be a length or a/N, got " + repr(arguments.h))
    if not arguments.element_size > 0:
        parser.error("--h must be > 0")
    return arguments


def fail(message):
    print("error: " + message, file=sys.stderr)
    sys.exit(1)


class ReportError(Exception):
    """The solution does not allow the Hertz comparison (as hertz_report.idp's fail())."""


def build_mesh_file(element_size, mesh_path):
    """Run scripts/performance/hertz_mesh.edp from the repository root (where freefem++.pref is)."""
    command = ["FreeFem++", "-nw", MESH_SCRIPT, "-h", repr(element_size), "-meshfile", mesh_path]
    try:
        run = subprocess.run(command, cwd=REPO_ROOT, capture_output=True, text=True)
    except FileNotFoundError:
        fail("FreeFem++ is not on PATH (needed to build the mesh; or give --mesh-only-from FILE)")
    if run.returncode != 0 or not os.path.exists(mesh_path):
        last_lines = (run.stdout + run.stderr).strip().splitlines()[-3:]
        fail("FreeFem++ " + MESH_SCRIPT + " failed (exit " + str(run.returncode) + "): " + " | ".join(last_lines))


def read_freefem_mesh(path):
    """FreeFEM's .msh text format: "nv nt nbe", nv lines "x y label", nt lines "i j k region",
    nbe lines "i j label" (1-based). Returns the vertices (nv x 2), triangles and boundary
    edges (0-based) and the edges' labels."""
    with open(path) as mesh_file:
        numbers = mesh_file.read().split()
    vertex_count, triangle_count, edge_count = (int(n) for n in numbers[:3])
    expected = 3 + 3 * vertex_count + 4 * triangle_count + 3 * edge_count
    if len(numbers) != expected:
        fail(path + " is not a FreeFEM .msh file (" + str(len(numbers)) + " numbers, expected " + str(expected) + ")")
    start = 3
    vertex_rows = np.array(numbers[start:start + 3 * vertex_count], dtype=float).reshape(-1, 3)
    start += 3 * vertex_count
    triangle_rows = np.array(numbers[start:start + 4 * triangle_count], dtype=np.int64).reshape(-1, 4)
    start += 4 * triangle_count
    edge_rows = np.array(numbers[start:start + 3 * edge_count], dtype=np.int64).reshape(-1, 3)
    return vertex_rows[:, :2], triangle_rows[:, :3] - 1, edge_rows[:, :2] - 1, edge_rows[:, 2]


def create_dolfinx_mesh(vertices, triangles):
    """The DOLFINx mesh and, for each original vertex, its DOLFINx (topology) vertex index."""
    domain = ufl.Mesh(ufl.VectorElement("Lagrange", ufl.triangle, 1))
    mesh = dolfinx.mesh.create_mesh(MPI.COMM_WORLD, triangles, vertices, domain)
    cell_vertices = mesh.topology.connectivity(2, 0).array.reshape(-1, 3)
    cell_nodes = mesh.geometry.dofmap.array.reshape(-1, 3)
    vertex_of_node = np.empty(mesh.geometry.x.shape[0], dtype=np.int64)
    vertex_of_node[cell_nodes] = cell_vertices      # P1: geometry nodes and vertices in the same local order
    vertex_of_original = np.full(vertices.shape[0], -1, dtype=np.int64)
    vertex_of_original[np.asarray(mesh.geometry.input_global_indices)] = vertex_of_node
    if (vertex_of_original < 0).any():
        fail("the mesh file has vertices that belong to no triangle")
    return mesh, vertex_of_original


def tag_boundary_facets(mesh, vertex_of_original, edges, edge_labels):
    """Facet tags with the mesh file's boundary labels 1-4 (internal label-5 arcs left out)."""
    mesh.topology.create_connectivity(1, 0)
    facet_vertices = np.sort(mesh.topology.connectivity(1, 0).array.reshape(-1, 2), axis=1).astype(np.int64)
    vertex_count = mesh.topology.index_map(0).size_local + mesh.topology.index_map(0).num_ghosts
    facet_keys = facet_vertices[:, 0] * vertex_count + facet_vertices[:, 1]
    facet_order = np.argsort(facet_keys)
    exterior = np.isin(edge_labels, (SYMMETRY_LABEL, TOP_LABEL, CONTACT_LABEL, FREE_ARC_LABEL))
    edge_vertices = np.sort(vertex_of_original[edges[exterior]], axis=1)
    edge_keys = edge_vertices[:, 0] * vertex_count + edge_vertices[:, 1]
    positions = np.searchsorted(facet_keys, edge_keys, sorter=facet_order)
    facets = facet_order[np.minimum(positions, len(facet_order) - 1)]
    if not np.array_equal(facet_keys[facets], edge_keys):
        fail("a boundary edge of the mesh file is not an edge of the DOLFINx mesh")
    order = np.argsort(facets)
    return dolfinx.mesh.meshtags(mesh, 1, facets[order].astype(np.int32), edge_labels[exterior][order].astype(np.int32))


def contact_candidates(vertices, edges, edge_labels):
    """The label-3 vertices (in the original numbering, as FreeFEM orders its dofs) and their
    lumped boundary weights: the integral of the P1 basis function over the label-3 edges,
    i.e. half the length of each adjacent label-3 edge (one edge at either end of the zone)."""
    contact_edges = edges[edge_labels == CONTACT_LABEL]
    nodes = np.unique(contact_edges)
    lengths = np.linalg.norm(vertices[contact_edges[:, 1]] - vertices[contact_edges[:, 0]], axis=1)
    weight_of_vertex = np.zeros(vertices.shape[0])
    np.add.at(weight_of_vertex, contact_edges[:, 0], lengths / 2)
    np.add.at(weight_of_vertex, contact_edges[:, 1], lengths / 2)
    return nodes, weight_of_vertex[nodes]


def vertex_dof_blocks(space, mesh):
    """For each DOLFINx vertex, its dof block in the P1 vector space (dof = 2 block + component)."""
    cell_vertices = mesh.topology.connectivity(2, 0).array.reshape(-1, 3)
    cell_blocks = space.dofmap.list.array.reshape(-1, 3)
    block_of_vertex = np.empty(mesh.topology.index_map(0).size_local + mesh.topology.index_map(0).num_ghosts, dtype=np.int64)
    block_of_vertex[cell_vertices] = cell_blocks
    return block_of_vertex


class ElasticContactProblem:
    """Plane-strain linear elasticity on P1: the stiffness K and load b (u_x = 0 on label 1,
    the pressure on label 2), SNES's residual F(u) = K u - b, and the UFL residual form for
    the reactions at the converged solution."""

    def __init__(self, mesh, facet_tags):
        self.space = dolfinx.fem.VectorFunctionSpace(mesh, ("Lagrange", 1))
        self.displacement = dolfinx.fem.Function(self.space)
        mu = YOUNG_MODULUS / (2 * (1 + POISSON_RATIO))
        lmbda = YOUNG_MODULUS * POISSON_RATIO / ((1 + POISSON_RATIO) * (1 - 2 * POISSON_RATIO))
        trial, test = ufl.TrialFunction(self.space), ufl.TestFunction(self.space)

        def strain(w):
            return ufl.sym(ufl.grad(w))

        def stress(w):
            return 2 * mu * strain(w) + lmbda * ufl.tr(strain(w)) * ufl.Identity(2)

        traction = dolfinx.fem.Constant(mesh, PETSc.ScalarType((0.0, -TOP_PRESSURE)))
        ds = ufl.Measure("ds", domain=mesh, subdomain_data=facet_tags)
        self.bilinear_form = dolfinx.fem.form(ufl.inner(stress(trial), strain(test)) * ufl.dx)
        self.load_form = dolfinx.fem.form(ufl.dot(traction, test) * ds(TOP_LABEL))
        self.residual_form = dolfinx.fem.form(ufl.inner(stress(self.displacement), strain(test)) * ufl.dx
                                              - ufl.dot(traction, test) * ds(TOP_LABEL))
        symmetry_facets = facet_tags.indices[facet_tags.values == SYMMETRY_LABEL]
        symmetry_dofs = dolfinx.fem.locate_dofs_topological(self.space.sub(0), 1, symmetry_facets)
        self.symmetry_condition = dolfinx.fem.dirichletbc(PETSc.ScalarType(0), symmetry_dofs, self.space.sub(0))
        self.fixed_dofs = np.asarray(symmetry_dofs, dtype=np.int64)

    def assemble(self):
        self.stiffness = dolfinx.fem.petsc.assemble_matrix(self.bilinear_form, bcs=[self.symmetry_condition])
        self.stiffness.assemble()
        self.load = dolfinx.fem.petsc.assemble_vector(self.load_form)
        dolfinx.fem.petsc.apply_lifting(self.load, [self.bilinear_form], bcs=[[self.symmetry_condition]])
        self.load.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        dolfinx.fem.petsc.set_bc(self.load, [self.symmetry_condition])

    def residual(self, snes, x, residual_vector):
        self.stiffness.mult(x, residual_vector)
        residual_vector.axpy(-1.0, self.load)

    def jacobian(self, snes, x, jacobian_matrix, preconditioner_matrix):
        pass   # K is constant: assembled once

    def reactions(self, solution):
        """The residual of the elastic equations (no Dirichlet rows) at `solution`: the force the
        obstacle and the supports must apply to the body, per dof."""
        self.displacement.vector.array[:] = solution.array
        self.displacement.x.scatter_forward()
        residual_vector = dolfinx.fem.petsc.assemble_vector(self.residual_form)
        residual_vector.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        return residual_vector.array.copy()


def configure_snes(problem, lower_bound, upper_bound, arguments):
    options = PETSc.Options()
    prefix = "hertz_"
    settings = {
        "snes_type": "vinewtonrsls",
        "snes_rtol": arguments.snes_rtol,
        "snes_atol": arguments.snes_atol,
        "snes_stol": 0.0,
        "snes_max_it": arguments.snes_max_it,
        "snes_vi_zero_tolerance": arguments.vi_zero_tolerance,
        "ksp_type": "preonly",
        "pc_type": "lu",
        "pc_factor_mat_solver_type": "mumps",
    }
    for item in arguments.petsc:
        name, _, value = item.partition("=")
        settings[name.lstrip("-")] = value
    for name, value in settings.items():
        options[prefix + name] = value
    snes = PETSc.SNES().create(MPI.COMM_WORLD)
    snes.setOptionsPrefix(prefix)
    snes.setFunction(problem.residual, problem.stiffness.createVecLeft())
    snes.setJacobian(problem.jacobian, problem.stiffness)
    snes.setFromOptions()
    snes.setVariableBounds(lower_bound, upper_bound)
    snes.setConvergenceHistory()
    if arguments.monitor:
        snes.setMonitor(lambda s, iteration, norm: print("SNES %3d |F| = %.6e" % (iteration, norm), file=sys.stderr))
    return snes, settings


def elliptical_pressure_fit(x, pressure, fitted):
    """fitEllipticalPressure: the least-squares line p^2 = A + B x^2 through the fitted nodes;
    returns (a, p_max) = (sqrt(-A/B), sqrt(A))."""
    x2, p2 = x[fitted] ** 2, pressure[fitted] ** 2
    s0, s1, s2 = float(len(x2)), x2.sum(), (x2 ** 2).sum()
    t0, t1 = p2.sum(), (x2 * p2).sum()
    if s0 < 3:
        raise ReportError("only %d active contact nodes: refine the contact zone (--h)" % s0)
    slope = (s0 * t1 - s1 * t0) / (s0 * s2 - s1 ** 2)
    intercept = (t0 - slope * s1) / s0
    if not (intercept > 0 and slope < 0):
        raise ReportError("the contact pressure is not elliptical (p^2 = %g + %g x^2)" % (intercept, slope))
    return math.sqrt(-intercept / slope), math.sqrt(intercept)


def pressure_l2_relative_error(x, pressure, weight, half_width, peak_pressure):
    exact = hertz_pressure(x, half_width, peak_pressure)
    return math.sqrt((weight * (pressure - exact) ** 2).sum() / (weight * exact ** 2).sum())


def relative_error(computed, reference):
    return abs(computed - reference) / abs(reference)


def import_solver_modules():
    """DOLFINx, its PETSc/MPI bindings and NumPy, as module globals (after the arguments are
    parsed, so that --help works without them)."""
    global np, MPI, PETSc, dolfinx, ufl
    try:
        import numpy as np
        from mpi4py import MPI
        from petsc4py import PETSc
        import dolfinx
        import dolfinx.fem.petsc
        import dolfinx.mesh
        import ufl
    except ImportError:
        print("dolfinx is not installed: apt-get install python3-dolfinx", file=sys.stderr)
        sys.exit(1)


def load_mesh(arguments, timings):
    """The mesh file (built by FreeFem++ unless given), read and turned into the DOLFINx mesh
    with its boundary facet tags."""
    temporary_folder = None
    if arguments.mesh_only_from:
        mesh_path = arguments.mesh_only_from
        timings["freefem_mesh_s"] = 0.0
    else:
        temporary_folder = tempfile.TemporaryDirectory(prefix="dolfinx_hertz_")
        mesh_path = os.path.join(temporary_folder.name, "hertz.msh")
        started = time.perf_counter()
        build_mesh_file(arguments.element_size, mesh_path)
        timings["freefem_mesh_s"] = time.perf_counter() - started
    started = time.perf_counter()
    vertices, triangles, edges, edge_labels = read_freefem_mesh(mesh_path)
    if temporary_folder is not None:
        temporary_folder.cleanup()
    for label in (SYMMETRY_LABEL, TOP_LABEL, CONTACT_LABEL):
        if not (edge_labels == label).any():
            fail("the mesh has no boundary edge of label %d" % label)
    mesh, vertex_of_original = create_dolfinx_mesh(vertices, triangles)
    facet_tags = tag_boundary_facets(mesh, vertex_of_original, edges, edge_labels)
    timings["mesh_s"] = time.perf_counter() - started
    return vertices, triangles, edges, edge_labels, mesh, vertex_of_original, facet_tags


def hertz_report(candidate_x, pressure, weights, active, element_size):
    """reportHertz's comparison: the p^2-x^2 fit over the active nodes left of
    lastActive - 1e-3 h, and the L2 error of p against Hertz over all candidates."""
    half_width = hertz_half_width()
    peak_pressure = hertz_peak_pressure(half_width)
    last_active_x = float(candidate_x[active].max()) if active.any() else 0.0
    if not last_active_x < 1.5 * half_width - element_size:
        raise ReportError("the contact zone reaches the end of the candidate zone")
    fitted = active & (np.abs(candidate_x) <= last_active_x - 1e-3 * element_size)
    fitted_half_width, fitted_peak_pressure = elliptical_pressure_fit(candidate_x, pressure, fitted)
    return {
        "a": fitted_half_width,
        "a_hertz": half_width,
        "a_rel_error": relative_error(fitted_half_width, half_width),
        "p_max": fitted_peak_pressure,
        "p_max_hertz": peak_pressure,
        "p_max_rel_error": relative_error(fitted_peak_pressure, peak_pressure),
        "pressure_l2_rel_error": pressure_l2_relative_error(candidate_x, pressure, weights, half_width, peak_pressure),
        "last_active_node_x": last_active_x,
        "active_nodes": int(active.sum()),
        "fitted_nodes": int(fitted.sum()),
    }


def write_pressure_csv(path, candidate_x, candidate_y, u_y, gap, active, pressure):
    """The candidates sorted by x, in the columns of our pressure.csv (without x_def)."""
    half_width = hertz_half_width()
    reference = hertz_pressure(candidate_x, half_width, hertz_peak_pressure(half_width))
    with open(path, "w") as csv:
        csv.write("s,x_ref,y_ref,y_def,gap,active,pressure,reference_pressure\n")
        for n in np.argsort(candidate_x, kind="stable"):
            csv.write("%.12g,%.12g,%.12g,%.12g,%.12g,%d,%.12g,%.12g\n" % (
                candidate_x[n], candidate_x[n], candidate_y[n], candidate_y[n] + u_y[n], gap[n], active[n],
                pressure[n], reference[n]))


def main():
    arguments = parse_arguments()
    import_solver_modules()
    displacement_scale = TOP_PRESSURE * DISC_RADIUS / YOUNG_MODULUS
    if arguments.vi_zero_tolerance is None:
        arguments.vi_zero_tolerance = 1e-12 * displacement_scale
    timings = {}
    vertices, triangles, edges, edge_labels, mesh, vertex_of_original, facet_tags = load_mesh(arguments, timings)

    started = time.perf_counter()
    problem = ElasticContactProblem(mesh, facet_tags)
    timings["forms_s"] = time.perf_counter() - started

    started = time.perf_counter()
    problem.assemble()
    candidates, candidate_weights = contact_candidates(vertices, edges, edge_labels)
    block_of_vertex = vertex_dof_blocks(problem.space, mesh)
    candidate_y_dofs = 2 * block_of_vertex[vertex_of_original[candidates]] + 1
    candidate_x, candidate_y = vertices[candidates, 0], vertices[candidates, 1]
    lower_bound = problem.stiffness.createVecRight()
    upper_bound = problem.stiffness.createVecRight()
    lower_bound.set(PETSc.NINFINITY)
    upper_bound.set(PETSc.INFINITY)
    lower_bound.array[candidate_y_dofs] = -candidate_y
    solution = problem.stiffness.createVecRight()
    solution.set(0.0)
    if arguments.start == "approach":
        solution.array[1::2] = -arguments.approach_factor * displacement_scale
    snes, settings = configure_snes(problem, lower_bound, upper_bound, arguments)
    timings["assembly_setup_s"] = time.perf_counter() - started

    started = time.perf_counter()
    snes.solve(None, solution)
    timings["solve_s"] = time.perf_counter() - started
    reason = snes.getConvergedReason()
    reason_names = {value: name for name, value in vars(PETSc.SNES.ConvergedReason).items() if isinstance(value, int)}
    residual_history = snes.getConvergenceHistory()[0]
    result = {
        "solver": "dolfinx %s, PETSc %s SNES vinewtonrsls + MUMPS LU" % (dolfinx.__version__, ".".join(map(str, PETSc.Sys.getVersion()))),
        "h": arguments.element_size,
        "ndof": problem.space.dofmap.index_map.size_global * problem.space.dofmap.index_map_bs,
        "vertices": int(vertices.shape[0]),
        "triangles": int(triangles.shape[0]),
        "candidates": int(candidates.size),
        "start": arguments.start if arguments.start == "zero" else "approach c=%g" % arguments.approach_factor,
        "snes_iterations": snes.getIterationNumber(),
        "snes_converged_reason": "%s (%d)" % (reason_names.get(reason, "?"), reason),
        "snes_initial_residual": float(residual_history[0]) if len(residual_history) else None,
        "snes_final_residual": float(residual_history[-1]) if len(residual_history) else None,
        "snes_options": {name: str(value) for name, value in settings.items()},
    }
    error = None if reason > 0 else "SNES did not converge"

    started = time.perf_counter()
    if error is None:
        reactions = problem.reactions(solution)
        u_y = solution.array[candidate_y_dofs]
        contact_forces = reactions[candidate_y_dofs]   # the obstacle's push on the body, > 0 in compression
        pressure = contact_forces / candidate_weights
        gap = candidate_y + u_y
        active = gap <= 1e-9 * np.ptp(vertices, axis=0).max()
        try:
            result.update(hertz_report(candidate_x, pressure, candidate_weights, active, arguments.element_size))
        except ReportError as report_error:
            error = str(report_error)
        applied_force = TOP_PRESSURE * DISC_RADIUS
        equilibrium_dofs = np.ones(reactions.size, dtype=bool)
        equilibrium_dofs[problem.fixed_dofs] = False
        equilibrium_dofs[candidate_y_dofs[active]] = False
        result.update({
            "contact_force": abs(contact_forces.sum()),
            "applied_force": applied_force,
            "contact_force_rel_error": relative_error(abs(contact_forces.sum()), applied_force),
            "equilibrium_residual_rel": float(np.linalg.norm(reactions[equilibrium_dofs]) / np.linalg.norm(problem.load.array)),
            "max_penetration": float(max(0.0, -gap.min())),
            "min_active_pressure": float(pressure[active].min()) if active.any() else None,
            "max_inactive_force_rel": float(np.abs(contact_forces[~active]).max() / applied_force) if (~active).any() else 0.0,
        })
        if arguments.pressure_csv:
            write_pressure_csv(arguments.pressure_csv, candidate_x, candidate_y, u_y, gap, active, pressure)
    timings["post_s"] = time.perf_counter() - started

    result.update({name: round(seconds, 4) for name, seconds in timings.items()})
    result["total_wall_s"] = round(seconds_since_process_start(), 3)
    if error is not None:
        result["error"] = error
    print("RESULT " + json.dumps(result))
    if error is not None:
        sys.exit(3)


if __name__ == "__main__":
    main()
