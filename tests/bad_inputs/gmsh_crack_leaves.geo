// Bad-input corpus: an embedded physical curve from (0.5, 0.5) to (1.5, 0.5), leaving the unit
// square through its right side. Refused naming the crack's point outside and its curve.
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Point(5) = {0.5, 0.5, 0, 1}; Point(6) = {1.5, 0.5, 0, 1};
Line(5) = {5, 6};
Curve{5} In Surface{1};
Physical Curve("long") = {5};
