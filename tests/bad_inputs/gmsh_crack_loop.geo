// Bad-input corpus: a closed loop of curves embedded in the unit square as a crack. A crack is
// an open line; an inner boundary is a hole of the surface. Refused naming curves 5, 6 and 7.
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Point(5) = {0.2, 0.2, 0}; Point(6) = {0.8, 0.2, 0}; Point(7) = {0.5, 0.8, 0};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 5};
Curve{5, 6, 7} In Surface{1};
Physical Curve("ring") = {5, 6, 7};
