// The thick sphere's octant of meshes/thick_sphere_octant.geo at mesh size 0.2: the report's
// quick mode (a coarse solid, so that its error rule is cheap).
size = 0.2;
Include "../../meshes/thick_sphere_octant.geo";
