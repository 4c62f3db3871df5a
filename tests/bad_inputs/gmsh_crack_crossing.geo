// Bad-input corpus: two embedded physical curves, two cracks, that cross at (0.5, 0.5)
// without a shared point. Cracks do not cross; refused naming both cracks and their curves.
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Point(5) = {0.2, 0.5, 0, 1}; Point(6) = {0.8, 0.5, 0, 1}; Point(7) = {0.5, 0.2, 0, 1}; Point(8) = {0.5, 0.8, 0, 1};
Line(5) = {5, 6}; Line(6) = {7, 8};
Curve{5, 6} In Surface{1};
Physical Curve("a") = {5};
Physical Curve("b") = {6};
