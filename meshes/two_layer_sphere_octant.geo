// One eighth of a thick sphere of two bonded layers, x, y, z >= 0: the inner layer
// a <= r <= c and the outer layer c <= r <= b, the composite sphere under internal pressure by
// symmetry. OpenCASCADE: the octants of the balls of radii b and c less the ball of radius a,
// fragmented so that the two layers share the interface sphere r = c (a conforming mesh).
// Units: none (the problem's length unit).
//
// Regions (physical volumes):
//   inner    a <= r <= c           outer    c <= r <= b
// Named boundary parts (physical surfaces):
//   bore     the sphere r = a      outside  the sphere r = b
//   x_sym    the face x = 0        y_sym    the face y = 0        z_sym    the face z = 0
//
// Mesh size: constant, h = size (default 0.2; a file that sets `size` and then includes this
// one refines it). The spheres are meshed by flat triangles inscribed in them.

SetFactory("OpenCASCADE");
If (!Exists(size))
  size = 0.2;
EndIf
a = 1;    // inner radius (the bore)
c = 1.5;  // radius of the interface
b = 2;    // outer radius

Sphere(1) = {0, 0, 0, b, 0, Pi / 2, Pi / 2};
Sphere(2) = {0, 0, 0, c, 0, Pi / 2, Pi / 2};
Sphere(3) = {0, 0, 0, a, 0, Pi / 2, Pi / 2};
BooleanDifference(4) = {Volume{1}; Delete;}{Volume{2}; };
BooleanDifference(5) = {Volume{2}; Delete;}{Volume{3}; Delete;};
v() = BooleanFragments{Volume{4, 5}; Delete;}{};

e = 1e-6 * b;
inner() = Volume In BoundingBox{-e, -e, -e, c + e, c + e, c + e};
outer() = Volume{:};
outer() -= {inner()};
bore() = Surface In BoundingBox{-e, -e, -e, a + e, a + e, a + e};
x_sym() = Surface In BoundingBox{-e, -e, -e, e, b + e, b + e};
y_sym() = Surface In BoundingBox{-e, -e, -e, b + e, e, b + e};
z_sym() = Surface In BoundingBox{-e, -e, -e, b + e, b + e, e};
// The outer sphere: the boundary of the outer layer less its plane faces and the interface.
interface() = Surface In BoundingBox{-e, -e, -e, c + e, c + e, c + e};
interface() -= {bore(), x_sym(), y_sym(), z_sym()};
outside() = Abs(Boundary{Volume{outer()};});
outside() -= {interface(), x_sym(), y_sym(), z_sym()};

Physical Volume("inner") = {inner()};
Physical Volume("outer") = {outer()};
Physical Surface("bore") = {bore()};
Physical Surface("outside") = {outside()};
Physical Surface("x_sym") = {x_sym()};
Physical Surface("y_sym") = {y_sym()};
Physical Surface("z_sym") = {z_sym()};

Mesh.MeshSizeMin = size;
Mesh.MeshSizeMax = size;
