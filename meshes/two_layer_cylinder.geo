// The quarter of a thick cylinder of two layers, 0 <= theta <= pi/2: the inner layer
// a <= r <= c and the outer layer c <= r <= b, bonded along the arc r = c (the interface
// "inner/outer" of the domain). The composite cylinder under internal pressure, a quarter of
// it by symmetry. Units: none (the problem's length unit).
//
// Regions (physical surfaces):
//   inner   a <= r <= c            outer   c <= r <= b
// Named boundary parts (physical curves):
//   bore    the arc r = a          outside the arc r = b
//   x_axis  the edge y = 0 (both layers)
//   y_axis  the edge x = 0 (both layers)
//
// Mesh size: constant, chosen so that the interface arc (length pi c / 2) splits into
// `pieces` straight pieces of equal length; the other arcs then get pieces * r / c (32 on the
// bore and 64 outside for 48: the element size of quarter_annulus.geo). Change `pieces` to
// refine; a file that sets `pieces` and then includes this one refines it.

If (!Exists(pieces))
  pieces = 48;  // straight pieces per quarter arc on the interface
EndIf
a = 1;    // inner radius (the bore)
c = 1.5;  // radius of the interface
b = 2;    // outer radius
h = (Pi * c / 2) / pieces;

Point(1) = {0, 0, 0, h};  // the centre of the arcs
Point(2) = {a, 0, 0, h};
Point(3) = {c, 0, 0, h};
Point(4) = {b, 0, 0, h};
Point(5) = {0, b, 0, h};
Point(6) = {0, c, 0, h};
Point(7) = {0, a, 0, h};

Line(1) = {2, 3};       // on y = 0, inner layer
Line(2) = {3, 4};       // on y = 0, outer layer
Circle(3) = {4, 1, 5};  // r = b, counter-clockwise
Line(4) = {5, 6};       // on x = 0, outer layer
Line(5) = {6, 7};       // on x = 0, inner layer
Circle(6) = {7, 1, 2};  // r = a, clockwise
Circle(7) = {3, 1, 6};  // r = c, counter-clockwise: the interface

Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};

Physical Surface("inner") = {1};
Physical Surface("outer") = {2};
Physical Curve("bore") = {6};
Physical Curve("outside") = {3};
Physical Curve("x_axis") = {1, 2};
Physical Curve("y_axis") = {4, 5};
