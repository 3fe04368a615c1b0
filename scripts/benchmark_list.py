"""The benchmark list shared by `make run` and the test suite.

Each entry: a name (also the output folder under results/) and the FreeFem++ driver
with its parameters. Adding a benchmark is one line here.
"""

BENCHMARKS = [
    ("cube_2d_mooney", "benchmarks/cube.edp", ["-material", "mooney", "-dim", "2"]),
    ("cube_2d_neohookean", "benchmarks/cube.edp", ["-material", "neohookean", "-dim", "2"]),
    ("cube_3d_mooney", "benchmarks/cube.edp", ["-material", "mooney", "-dim", "3", "-n", "4"]),
    ("cube_3d_neohookean", "benchmarks/cube.edp", ["-material", "neohookean", "-dim", "3", "-n", "4"]),
    ("cube_2d_mooney_foundation", "benchmarks/cube.edp", ["-material", "mooney", "-dim", "2", "-foundation", "1"]),
    ("cube_3d_neohookean_foundation", "benchmarks/cube.edp",
     ["-material", "neohookean", "-dim", "3", "-n", "4", "-foundation", "1"]),
    ("hertz_plane", "benchmarks/hertz_plane.edp", []),
    ("hertz_plane_neohookean", "benchmarks/hertz_plane.edp", ["-material", "neohookean"]),
    ("hertz_circle_exact", "benchmarks/hertz_circle.edp", ["-constraint", "exact"]),
    ("hertz_circle_linearized", "benchmarks/hertz_circle.edp", ["-constraint", "linearized"]),
    ("hertz_circle_vertical", "benchmarks/hertz_circle.edp", ["-constraint", "vertical"]),
    ("clamped_square", "benchmarks/clamped_square.edp", []),
    ("hertz_sphere", "benchmarks/hertz_sphere.edp", []),
    ("hertz_sphere_axisymmetric", "benchmarks/hertz_sphere.edp", ["-dim", "axi"]),
    ("cylinder_axisymmetric", "benchmarks/cube.edp", ["-material", "mooney", "-dim", "axi"]),
    ("oring_groove", "benchmarks/oring.edp", ["-case", "groove"]),
    ("oring_plates", "benchmarks/oring.edp", ["-case", "plates"]),
    ("oring_torus", "benchmarks/oring_torus.edp", []),
    ("platen_block", "benchmarks/platen_block.edp", []),
    ("cube_2d_mooney_incompressible", "benchmarks/cube.edp", ["-material", "mooney", "-dim", "2", "-nu", "0.5"]),
    ("cube_3d_neohookean_incompressible", "benchmarks/cube.edp", ["-material", "neohookean", "-dim", "3", "-n", "3", "-nu", "0.5"]),
    ("rivlin_tube", "benchmarks/rivlin_tube.edp", []),
    ("hertz_two_cylinders", "benchmarks/hertz_two_cylinders.edp", []),
    ("hertz_two_cylinders_swapped", "benchmarks/hertz_two_cylinders.edp", ["-slave", "upper"]),
    ("hertz_two_spheres", "benchmarks/hertz_two_spheres.edp", []),
    ("oring_flange_steel", "benchmarks/oring_flange.edp", []),
    ("oring_flange_soft", "benchmarks/oring_flange.edp", ["-Ef", "40", "-nuf", "0.45", "-steps", "5"]),
    ("sliding_disc", "benchmarks/sliding_disc.edp", []),
    ("hertz_plane_nu0.4999", "benchmarks/hertz_plane.edp", ["-volumetric", "nodal", "-nu", "0.4999"]),
    ("indentation_axi", "benchmarks/indentation.edp", ["-dim", "axi"]),
    ("indentation_3d", "benchmarks/indentation.edp", ["-dim", "3"]),
    ("cube_2d_mooney_platen", "benchmarks/cube.edp", ["-material", "mooney", "-load", "platen", "-compression", "0.35", "-steps", "4"]),
]
