// A block with a hole and a notch: [0, 1] x [0, 0.8] x [0, 0.6] minus the corner x > 0.6,
// y > 0.45 (a re-entrant edge along z at (0.6, 0.45)) and minus a round hole of radius 0.15
// through it along z, centred at (0.3, 0.4). OpenCASCADE; units: none.
//
// Named boundary parts (physical surfaces):
//   x_min    the face x = 0          y_min    the face y = 0
//   other    every other face: the top and bottom (z = 0, 0.6), the far faces, the notch's
//            two faces and the hole's wall
//
// Mesh size: constant, h = size (default 0.1; a file that sets `size` and then includes this
// one refines it).

SetFactory("OpenCASCADE");
If (!Exists(size))
  size = 0.1;
EndIf

Box(1) = {0, 0, 0, 1, 0.8, 0.6};
Box(2) = {0.6, 0.45, -0.1, 1, 1, 1};
Cylinder(3) = {0.3, 0.4, -0.1, 0, 0, 0.8, 0.15};
BooleanDifference(4) = {Volume{1}; Delete;}{Volume{2, 3}; Delete;};

e = 1e-6;
x_min() = Surface In BoundingBox{-e, -e, -e, e, 0.8 + e, 0.6 + e};
y_min() = Surface In BoundingBox{-e, -e, -e, 1 + e, e, 0.6 + e};
other() = Abs(Boundary{Volume{4};});
other() -= {x_min(), y_min()};

Physical Surface("x_min") = {x_min()};
Physical Surface("y_min") = {y_min()};
Physical Surface("other") = {other()};
Physical Volume("block") = {4};

Mesh.MeshSizeMin = size;
Mesh.MeshSizeMax = size;
