// A disk of radius b = 1 (the matrix) holding a concentric disk of radius c = 0.5 (the
// inclusion), bonded along the circle r = c: the interface "matrix/inclusion", which closes
// on itself. Units: none (the problem's length unit).
//
// Regions (physical surfaces):  inclusion  r <= c        matrix  c <= r <= b
// Named boundary part (physical curve):  outside  the circle r = b
//
// Mesh size: constant, chosen so that the interface circle splits into `pieces` straight
// pieces of equal length (the outside then gets pieces * b / c). Chords of 1024 pieces lie
// within c (1 - cos(pi / 1024)) = 2.4e-6 of the circle.

If (!Exists(pieces))
  pieces = 1024;  // straight pieces round the interface
EndIf
c = 0.5;  // radius of the inclusion
b = 1;    // outer radius
h = (2 * Pi * c) / pieces;

Point(1) = {0, 0, 0, h};
Point(2) = {c, 0, 0, h};
Point(3) = {-c, 0, 0, h};
Point(4) = {b, 0, 0, h};
Point(5) = {-b, 0, 0, h};

Circle(1) = {2, 1, 3};  // r = c, upper half
Circle(2) = {3, 1, 2};  // r = c, lower half
Circle(3) = {4, 1, 5};  // r = b, upper half
Circle(4) = {5, 1, 4};  // r = b, lower half

Curve Loop(1) = {1, 2};
Plane Surface(1) = {1};
Curve Loop(2) = {3, 4};
Plane Surface(2) = {2, 1};

Physical Surface("inclusion") = {1};
Physical Surface("matrix") = {2};
Physical Curve("outside") = {3, 4};
