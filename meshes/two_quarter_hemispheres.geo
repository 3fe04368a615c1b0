// Two quarter hemispheres touching at the origin: the two-sphere Hertz benchmark's bodies
// (benchmarks/hertz_two_spheres.edp). The upper one has radius R (centre (0, 0, R)), the lower one
// radius R2 (centre (0, 0, -R2)); both in the quarter x >= 0, y >= 0 (symmetry planes x = 0 and
// y = 0). The two volumes are not fused: each keeps its own vertex at the origin.
// Element size h within the distance `zone` of the contact point, growing linearly (slope
// `growth`) to hmax. Surface labels: upper 1 symmetry x = 0, 2 symmetry y = 0, 3 top z = R
// (loaded), 4 spherical surface; lower the same plus 10 (13: its flat face z = -R2). Volumes 1
// (upper) and 2 (lower). With half = 1, the halves y >= 0 instead (x from -R; no faces 1 and 11):
// benchmarks/mindlin_sphere.edp, whose tangential load along x leaves only y = 0 a symmetry plane.
//   gmsh -3 -format msh22 -setnumber h 0.05 meshes/two_quarter_hemispheres.geo -o spheres.msh
SetFactory("OpenCASCADE");
If (!Exists(R)) R = 1; EndIf
If (!Exists(R2)) R2 = 1.2; EndIf
If (!Exists(h)) h = 0.05; EndIf
If (!Exists(hmax)) hmax = 0.2; EndIf
If (!Exists(zone)) zone = 0.15; EndIf
If (!Exists(growth)) growth = 0.3; EndIf
If (!Exists(gap)) gap = 0; EndIf   // the lower body moved down by gap
If (!Exists(half)) half = 0; EndIf   // 1: the halves y >= 0

Sphere(1) = {0, 0, R, R};
Box(2) = {-half*R, 0, 0, R*(1 + half), R, R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Sphere(4) = {0, 0, -R2 - gap, R2};
Box(5) = {-half*R2, 0, -R2 - gap, R2*(1 + half), R2, R2};
BooleanIntersection(6) = { Volume{4}; Delete; }{ Volume{5}; Delete; };

// classify each body's faces by position
eps = 1e-6*(R + R2);
upper() = Boundary{ Volume{3}; };
lower() = Boundary{ Volume{6}; };
xUpper() = Surface In BoundingBox{-eps, -eps, -eps, eps, R + eps, R + eps};
yUpper() = Surface In BoundingBox{-half*R - eps, -eps, -eps, R + eps, eps, R + eps};
topUpper() = Surface In BoundingBox{-half*R - eps, -eps, R - eps, R + eps, R + eps, R + eps};
xLower() = Surface In BoundingBox{-eps, -eps, -R2 - gap - eps, eps, R2 + eps, -gap + eps};
yLower() = Surface In BoundingBox{-half*R2 - eps, -eps, -R2 - gap - eps, R2 + eps, eps, -gap + eps};
bottomLower() = Surface In BoundingBox{-half*R2 - eps, -eps, -R2 - gap - eps, R2 + eps, R2 + eps, -R2 - gap + eps};
curvedUpper() = upper();
curvedUpper() -= xUpper();
curvedUpper() -= yUpper();
curvedUpper() -= topUpper();
curvedLower() = lower();
curvedLower() -= xLower();
curvedLower() -= yLower();
curvedLower() -= bottomLower();
If (!half)
  Physical Surface(1) = {xUpper()};
  Physical Surface(11) = {xLower()};
EndIf
Physical Surface(2) = {yUpper()};
Physical Surface(3) = {topUpper()};
Physical Surface(4) = {curvedUpper()};
Physical Surface(12) = {yLower()};
Physical Surface(13) = {bottomLower()};
Physical Surface(14) = {curvedLower()};
Physical Volume(1) = {3};
Physical Volume(2) = {6};

Field[1] = Distance;
contactPoints() = Point In BoundingBox{-eps, -eps, -gap - eps, eps, eps, eps};
Field[1].PointsList = {contactPoints()};
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
