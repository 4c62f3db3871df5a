// Two blocks 1 x 0.5 x 0.5 across a gap of 0.03: block a on 0 <= y <= 0.5, block b on
// 0.53 <= y <= 1.03 (x and z from 0 to 1 and 0.5). The gap is narrower than every support
// of the scenes that use it. OpenCASCADE; units: none.
//
// Named boundary parts (physical surfaces):
//   a_x0, a_y0, a_z0   block a's faces x = 0, y = 0, z = 0
//   a_end              block a's face x = 1
//   b_x0               block b's face x = 0
//   walls              the gap's two walls y = 0.5 and y = 0.53
//   other              every other face
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.5, 0.5};
Box(2) = {0, 0.53, 0, 1, 0.5, 0.5};
e = 1e-6;
a_x0() = Surface In BoundingBox{-e, -e, -e, e, 0.5 + e, 0.5 + e};
a_y0() = Surface In BoundingBox{-e, -e, -e, 1 + e, e, 0.5 + e};
a_z0() = Surface In BoundingBox{-e, -e, -e, 1 + e, 0.5 + e, e};
a_end() = Surface In BoundingBox{1 - e, -e, -e, 1 + e, 0.5 + e, 0.5 + e};
b_x0() = Surface In BoundingBox{-e, 0.53 - e, -e, e, 1.03 + e, 0.5 + e};
walls() = Surface In BoundingBox{-e, 0.5 - e, -e, 1 + e, 0.53 + e, 0.5 + e};
other() = Abs(Boundary{Volume{1, 2};});
other() -= {a_x0(), a_y0(), a_z0(), a_end(), b_x0(), walls()};
Physical Surface("a_x0") = {a_x0()};
Physical Surface("a_y0") = {a_y0()};
Physical Surface("a_z0") = {a_z0()};
Physical Surface("a_end") = {a_end()};
Physical Surface("b_x0") = {b_x0()};
Physical Surface("walls") = {walls()};
Physical Surface("other") = {other()};
Physical Volume("blocks") = {1, 2};
Mesh.MeshSizeMax = 0.25;
