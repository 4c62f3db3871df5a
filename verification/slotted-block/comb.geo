// A comb: the block [0, 2] x [0, 1.1] x [0, 0.3] with two slots 0.03 wide (0.45 < y < 0.48 and
// 0.62 < y < 0.65) cut from x = 0.6 to its end, leaving a thin wall 0.14 wide between them.
// OpenCASCADE; units: none.
//
// Named boundary parts (physical surfaces):
//   root       the face x = 0
//   wall_end   the thin wall's end x = 2
// (every other face is traction-free and needs no name)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1.1, 0.3};
Box(2) = {0.6, 0.45, -0.1, 1.5, 0.03, 0.5};
Box(3) = {0.6, 0.62, -0.1, 1.5, 0.03, 0.5};
BooleanDifference(4) = {Volume{1}; Delete;}{Volume{2, 3}; Delete;};
e = 1e-6;
Physical Surface("root") = Surface In BoundingBox{-e, -e, -e, e, 1.1 + e, 0.3 + e};
Physical Surface("wall_end") = Surface In BoundingBox{2 - e, 0.48 - e, -e, 2 + e, 0.62 + e, 0.3 + e};
Physical Volume("comb") = {4};
