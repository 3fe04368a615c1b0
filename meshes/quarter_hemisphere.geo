// A quarter of the hemisphere of radius R, centre (0, 0, R), touching z = 0 at the origin: the
// 3D Hertz benchmark's body (benchmarks/hertz_sphere.edp). Symmetry planes x = 0 and y = 0.
// Element size h within the distance `zone` of the contact point, growing linearly (slope
// `growth`) to hmax. Surface labels: 1 symmetry x = 0, 2 symmetry y = 0, 3 top z = R (loaded),
// 4 spherical surface (contact candidates are taken on it near the origin). Volume label 1.
// With whole = 1, the quarter of the whole sphere (z up to 2R, no face 3): benchmarks/sphere_impact.edp -dim 3.
//   gmsh -3 -format msh22 -setnumber h 0.02 meshes/quarter_hemisphere.geo -o sphere.msh
SetFactory("OpenCASCADE");
If (!Exists(R)) R = 1; EndIf
If (!Exists(h)) h = 0.02; EndIf
If (!Exists(hmax)) hmax = 0.15; EndIf
If (!Exists(zone)) zone = 0.15; EndIf
If (!Exists(growth)) growth = 0.3; EndIf
If (!Exists(whole)) whole = 0; EndIf   // 1: the quarter of the whole sphere (sphere_impact.edp -dim 3), no top face

Sphere(1) = {0, 0, R, R};
Box(2) = {0, 0, 0, R, R, R*(1 + whole)};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };

// classify the faces of the quarter by position
eps = 1e-6*R;
zTop = R*(1 + whole);
symmetryX() = Surface In BoundingBox{-eps, -eps, -eps, eps, R + eps, zTop + eps};
symmetryY() = Surface In BoundingBox{-eps, -eps, -eps, R + eps, eps, zTop + eps};
top() = Surface In BoundingBox{-eps, -eps, R - eps, R + eps, R + eps, R + eps};
all() = Surface{:};
curved() = all();
curved() -= symmetryX();
curved() -= symmetryY();
curved() -= top();
Physical Surface(1) = {symmetryX()};
Physical Surface(2) = {symmetryY()};
Physical Surface(3) = {top()};
Physical Surface(4) = {curved()};
Physical Volume(1) = {3};

Field[1] = Distance;
contactPoint() = Point In BoundingBox{-eps, -eps, -eps, eps, eps, eps};
Field[1].PointsList = {contactPoint()};
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
