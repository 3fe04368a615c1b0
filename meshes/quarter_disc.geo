// Quarter of a disc of radius R, centre (0, R), touching y = 0 at the origin: the Hertz
// benchmarks' body (preprint 4.2). Element size h within the distance `zone` of the
// contact point, growing linearly (slope `growth`) to hmax.
// Boundary labels: 1 symmetry x = 0, 2 top y = R (loaded), 3 arc within `zone` of the
// origin (contact candidates), 4 rest of the arc. Surface label 1.
// Used by benchmarks/hertz_*.edp through include/gmsh_mesh.idp, which sets the numbers:
//   gmsh -2 -format msh22 -setnumber h 0.002 meshes/quarter_disc.geo -o disc.msh
If (!Exists(R)) R = 1; EndIf
If (!Exists(h)) h = 0.005; EndIf
If (!Exists(hmax)) hmax = 0.05; EndIf
If (!Exists(zone)) zone = 0.15; EndIf
If (!Exists(growth)) growth = 0.2; EndIf

theta = 2*Asin(zone/(2*R));   // the arc point at distance `zone` from the origin
Point(1) = {0, 0, 0};
Point(2) = {0, R, 0};
Point(3) = {R, R, 0};
Point(4) = {R*Sin(theta), R - R*Cos(theta), 0};
Circle(4) = {1, 2, 4};    // counter-clockwise: FreeFEM needs positively oriented triangles
Circle(3) = {4, 2, 3};
Line(2) = {3, 2};
Line(1) = {2, 1};
Curve Loop(1) = {4, 3, 2, 1};
Plane Surface(1) = {1};
Physical Curve(1) = {1};
Physical Curve(2) = {2};
Physical Curve(3) = {4};
Physical Curve(4) = {3};
Physical Surface(1) = {1};

Field[1] = Distance;
Field[1].PointsList = {1};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h;
Field[2].SizeMax = hmax;
Field[2].DistMin = zone;
Field[2].DistMax = zone + (hmax - h)/growth;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
