// The square plate [-1, 1] x [-1, 1] with a centre crack of length 2a = 0.5 along y = 0, from
// (-0.25, 0) to (0.25, 0): a curve embedded in the surface and put in a physical curve, which
// mfree reads as the crack "crack1" (two tips; named as a WKT file names its first crack).
// Every curve is straight, so one element each (lc above every length) gives the exact polygon.
// centre_crack.msh is its 1D mesh (gmsh -1).
lc = 10;
Point(1) = {-1, -1, 0, lc}; Point(2) = {1, -1, 0, lc}; Point(3) = {1, 1, 0, lc}; Point(4) = {-1, 1, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Point(5) = {-0.25, 0, 0, lc}; Point(6) = {0.25, 0, 0, lc};
Line(5) = {5, 6};
Curve{5} In Surface{1};

Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("crack1") = {5};
