// The square plate [-1, 1] x [-1, 1] with an edge crack of length a = 0.75 along y = 0, from
// its mouth (-1, 0) on the left side to its tip (-0.25, 0). The crack is two embedded curves
// that meet at (-0.5, 0), the second drawn tip to middle: mfree chains them into one crack
// running the way its lowest-numbered curve (5) runs, mouth to tip. The mouth is a point of
// the left side (curves 4 and 6), so the side is split there. Every curve is straight: one
// element each. The crack is "crack1", as a WKT file names its first crack.
lc = 10;
Point(1) = {-1, -1, 0, lc}; Point(2) = {1, -1, 0, lc}; Point(3) = {1, 1, 0, lc}; Point(4) = {-1, 1, 0, lc};
Point(5) = {-1, 0, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(6) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 6};
Plane Surface(1) = {1};

Point(6) = {-0.5, 0, 0, lc}; Point(7) = {-0.25, 0, 0, lc};
Line(5) = {5, 6}; Line(7) = {7, 6};
Curve{5, 7} In Surface{1};

Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4, 6};
Physical Curve("crack1") = {5, 7};
