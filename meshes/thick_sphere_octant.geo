// One eighth of a thick sphere, a <= r <= b with x, y, z >= 0: Lamé's sphere under internal
// pressure by symmetry. OpenCASCADE: the octant of the ball of radius b minus the ball of
// radius a. Units: none (the problem's length unit).
//
// Named boundary parts (physical surfaces):
//   bore     the sphere r = a        outside  the sphere r = b
//   x_sym    the face x = 0          y_sym    the face y = 0        z_sym    the face z = 0
//
// Mesh size: constant, h = size (default 0.2; a file that sets `size` and then includes this
// one refines it). The spheres are meshed by flat triangles inscribed in them.

SetFactory("OpenCASCADE");
If (!Exists(size))
  size = 0.2;
EndIf
a = 1;  // inner radius
b = 2;  // outer radius

Sphere(1) = {0, 0, 0, b, 0, Pi / 2, Pi / 2};
Sphere(2) = {0, 0, 0, a, 0, Pi / 2, Pi / 2};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};

e = 1e-6 * b;
bore() = Surface In BoundingBox{-e, -e, -e, a + e, a + e, a + e};
x_sym() = Surface In BoundingBox{-e, -e, -e, e, b + e, b + e};
y_sym() = Surface In BoundingBox{-e, -e, -e, b + e, e, b + e};
z_sym() = Surface In BoundingBox{-e, -e, -e, b + e, b + e, e};
outside() = Abs(Boundary{Volume{3};});
outside() -= {bore(), x_sym(), y_sym(), z_sym()};

Physical Surface("bore") = {bore()};
Physical Surface("outside") = {outside()};
Physical Surface("x_sym") = {x_sym()};
Physical Surface("y_sym") = {y_sym()};
Physical Surface("z_sym") = {z_sym()};
Physical Volume("sphere") = {3};

Mesh.MeshSizeMin = size;
Mesh.MeshSizeMax = size;
