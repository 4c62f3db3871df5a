// Bad-input corpus: a curve embedded in the unit square in no physical curve. mfree reads an
// embedded curve as a crack named by its physical curve; refused naming curve 5.
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Point(5) = {0.2, 0.5, 0}; Point(6) = {0.8, 0.5, 0};
Line(5) = {5, 6};
Curve{5} In Surface{1};
