// Bad-input corpus: a .geo file that asks gmsh to run a command. The reader's child process
// may start no program: gmsh finds no shell, the file is refused, and no file "touched"
// appears in the folder the run started in.
SystemCall "touch touched";
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Surface("body") = {1};
