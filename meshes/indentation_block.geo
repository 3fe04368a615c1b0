// The indentation benchmark's block (benchmarks/indentation.edp, -dim 3): a quarter of the cylinder of
// radius B and height B, axis z, bottom z = 0; the indenter touches its top z = B at the axis.
// Symmetry planes x = 0 and y = 0. Element size h within the distance `zone` of the contact point,
// then growing in proportion to the distance (h d / zone), so that halving h gives ~8x the nodes.
// Surface labels: 1 symmetry x = 0, 2 symmetry y = 0, 3 top z = B (contact candidates near the
// axis), 4 bottom z = 0 (on the rigid plane), 5 the lateral surface (free). Volume label 1.
//   gmsh -3 -format msh22 -setnumber h 0.05 meshes/indentation_block.geo -o block.msh
SetFactory("OpenCASCADE");
If (!Exists(B)) B = 10; EndIf
If (!Exists(h)) h = 0.05; EndIf
If (!Exists(zone)) zone = 0.6; EndIf

Cylinder(1) = {0, 0, 0, 0, 0, B, B, Pi/2};

eps = 1e-6*B;
symmetryX() = Surface In BoundingBox{-eps, -eps, -eps, eps, B + eps, B + eps};
symmetryY() = Surface In BoundingBox{-eps, -eps, -eps, B + eps, eps, B + eps};
top() = Surface In BoundingBox{-eps, -eps, B - eps, B + eps, B + eps, B + eps};
bottom() = Surface In BoundingBox{-eps, -eps, -eps, B + eps, B + eps, eps};
lateral() = Surface{:};
lateral() -= symmetryX();
lateral() -= symmetryY();
lateral() -= top();
lateral() -= bottom();
Physical Surface(1) = {symmetryX()};
Physical Surface(2) = {symmetryY()};
Physical Surface(3) = {top()};
Physical Surface(4) = {bottom()};
Physical Surface(5) = {lateral()};
Physical Volume(1) = {1};

Field[1] = MathEval;
Field[1].F = Sprintf("%g*Max(1, Sqrt(x*x + y*y + (z - %g)*(z - %g))/%g)", h, B, B, zone);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
