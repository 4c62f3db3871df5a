// The square plate [-2, 2] x [-2, 2] with a central circular hole of radius 0.5: the
// plate-with-a-hole (Kirsch) problem, the curved-hole counterpart of plate_with_hole.wkt.
// Units: none (the problem's length unit).
//
// Named boundary parts (physical curves): left (x = -2), right (x = 2), bottom (y = -2),
// top (y = 2) and hole (r = 0.5, four quarter arcs).
//
// Built with the OpenCASCADE kernel so that gmsh can export it as CAD
// (plate_with_hole.step, see README.md); the entities are given one by one, not by
// Boolean operations, so that their tags (and the physical curves below) are fixed.
// Mesh size: `hole_pieces` equal pieces around the hole, `side_pieces` along each side.

hole_pieces = 64;  // straight pieces around the whole hole
side_pieces = 16;  // straight pieces along each side of the plate
r = 0.5;           // hole radius
L = 2;             // half the side of the plate

SetFactory("OpenCASCADE");

h_hole = 2 * Pi * r / hole_pieces;
h_side = 2 * L / side_pieces;

Point(1) = {-L, -L, 0, h_side};
Point(2) = { L, -L, 0, h_side};
Point(3) = { L,  L, 0, h_side};
Point(4) = {-L,  L, 0, h_side};
Point(5) = {0, 0, 0, h_hole};  // the centre of the hole
Point(6) = { r, 0, 0, h_hole};
Point(7) = {0,  r, 0, h_hole};
Point(8) = {-r, 0, 0, h_hole};
Point(9) = {0, -r, 0, h_hole};

Line(1) = {1, 2};  // bottom
Line(2) = {2, 3};  // right
Line(3) = {3, 4};  // top
Line(4) = {4, 1};  // left
Circle(5) = {6, 5, 7};
Circle(6) = {7, 5, 8};
Circle(7) = {8, 5, 9};
Circle(8) = {9, 5, 6};

Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};

Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("hole") = {5, 6, 7, 8};
// The surface as a group too, so that a 2D mesh saved as .msh keeps its triangles.
Physical Surface("plate") = {1};
