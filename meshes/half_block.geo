// A block on a rigid sphere: benchmarks/mindlin_sphere.edp -setup rigid. The half y >= 0 of a
// cylinder of radius L and height L, axis z, its bottom z = 0 touching the sphere at the origin
// (the tangential load along x leaves y = 0 a symmetry plane). Element size h within the distance
// `zone` of the contact point, growing linearly (slope `growth`) to hmax.
// Surface labels: 1 symmetry y = 0, 2 bottom z = 0 (the contact face), 3 top z = L (the platen),
// 4 the lateral surface (free). Volume 1.
//   gmsh -3 -format msh22 -setnumber h 0.05 meshes/half_block.geo -o block.msh
SetFactory("OpenCASCADE");
If (!Exists(L)) L = 5; EndIf
If (!Exists(h)) h = 0.05; EndIf
If (!Exists(hmax)) hmax = 1; EndIf
If (!Exists(zone)) zone = 0.3; EndIf
If (!Exists(growth)) growth = 0.3; EndIf

Cylinder(1) = {0, 0, 0, 0, 0, L, L, Pi};

eps = 1e-6*L;
symmetry() = Surface In BoundingBox{-L - eps, -eps, -eps, L + eps, eps, L + eps};
bottom() = Surface In BoundingBox{-L - eps, -eps, -eps, L + eps, L + eps, eps};
top() = Surface In BoundingBox{-L - eps, -eps, L - eps, L + eps, L + eps, L + eps};
lateral() = Surface{:};
lateral() -= symmetry();
lateral() -= bottom();
lateral() -= top();
Physical Surface(1) = {symmetry()};
Physical Surface(2) = {bottom()};
Physical Surface(3) = {top()};
Physical Surface(4) = {lateral()};
Physical Volume(1) = {1};

Field[1] = MathEval;   // the distance to the contact point
Field[1].F = "Sqrt(x*x + y*y + z*z)";
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
