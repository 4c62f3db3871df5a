// The quarter annulus a <= r <= b, 0 <= theta <= pi/2: the thick cylinder under internal
// pressure (Lame), a quarter of it by symmetry. Units: none (the problem's length unit).
//
// Named boundary parts (physical curves):
//   inner   the arc r = a          outer   the arc r = b
//   x_axis  the edge y = 0         y_axis  the edge x = 0
//
// Mesh size: constant, chosen so that the outer arc (length pi b / 2) splits into
// `pieces` straight pieces of equal length; the inner arc then gets pieces * a / b.
// Change `pieces` to refine; everything else follows. A file that sets `pieces` and then
// includes this one refines it (verification/lame/quarter_annulus_1024.geo).

If (!Exists(pieces))
  pieces = 64;  // straight pieces per quarter arc on the outer circle
EndIf
a = 1;        // inner radius
b = 2;        // outer radius
h = (Pi * b / 2) / pieces;

Point(1) = {0, 0, 0, h};  // the centre of both arcs
Point(2) = {a, 0, 0, h};
Point(3) = {b, 0, 0, h};
Point(4) = {0, b, 0, h};
Point(5) = {0, a, 0, h};

Line(1) = {2, 3};             // on y = 0
Circle(2) = {3, 1, 4};        // r = b, counter-clockwise
Line(3) = {4, 5};             // on x = 0
Circle(4) = {5, 1, 2};        // r = a, clockwise

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Physical Curve("x_axis") = {1};
Physical Curve("outer") = {2};
Physical Curve("y_axis") = {3};
Physical Curve("inner") = {4};
// The surface as a group too, so that a 2D mesh saved as .msh keeps its triangles.
Physical Surface("body") = {1};
