// The indentation benchmark's block in the axisymmetric mode (benchmarks/indentation.edp, -dim axi):
// the meridian section (r, z) = (x, y) of the cylinder of radius B and height B, [0, B] x [0, B];
// the indenter touches its top y = B at the axis. Element size h within the distance `zone` of the
// contact point, then growing in proportion to the distance (h d / zone), so that halving h gives
// ~4x the nodes. Line labels: 1 bottom y = 0 (on the rigid plane), 2 the lateral surface x = B
// (free), 3 top y = B (contact candidates near the axis), 4 the axis x = 0. Surface label 1.
//   gmsh -2 -format msh22 -setnumber h 0.05 meshes/indentation_section.geo -o section.msh
If (!Exists(B)) B = 10; EndIf
If (!Exists(h)) h = 0.05; EndIf
If (!Exists(zone)) zone = 0.6; EndIf

Point(1) = {0, 0, 0};
Point(2) = {B, 0, 0};
Point(3) = {B, B, 0};
Point(4) = {0, B, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Line(1) = {1};
Physical Line(2) = {2};
Physical Line(3) = {3};
Physical Line(4) = {4};
Physical Surface(1) = {1};

Field[1] = MathEval;
Field[1].F = Sprintf("%g*Max(1, Sqrt(x*x + (y - %g)*(y - %g))/%g)", h, B, B, zone);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
