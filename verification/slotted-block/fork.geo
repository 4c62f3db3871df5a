// A fork: the block [0, 2] x [0, 1] x [0, 0.4] with a slot 0.04 wide (0.48 < y < 0.52) cut from
// x = 0.8 to its end x = 2, leaving two tines 0.48 wide joined by the root 0.8 long.
// OpenCASCADE; units: none.
//
// Named boundary parts (physical surfaces):
//   root     the face x = 0
//   end_a    the end x = 2 of tine a (y < 0.48)
//   end_b    the end x = 2 of tine b (y > 0.52)
//   other    every other face, the slot's walls and its bottom among them
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 0.4};
Box(2) = {0.8, 0.48, -0.1, 1.3, 0.04, 0.6};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
e = 1e-6;
root() = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 0.4 + e};
end_a() = Surface In BoundingBox{2 - e, -e, -e, 2 + e, 0.48 + e, 0.4 + e};
end_b() = Surface In BoundingBox{2 - e, 0.52 - e, -e, 2 + e, 1 + e, 0.4 + e};
other() = Abs(Boundary{Volume{3};});
other() -= {root(), end_a(), end_b()};
Physical Surface("root") = {root()};
Physical Surface("end_a") = {end_a()};
Physical Surface("end_b") = {end_b()};
Physical Surface("other") = {other()};
Physical Volume("fork") = {3};
Mesh.MeshSizeMax = 0.2;
