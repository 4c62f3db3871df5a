// The thick sphere's octant of meshes/thick_sphere_octant.geo at mesh size 0.1 (half the
// scene's node spacing 0.2).
size = 0.1;
Include "../../meshes/thick_sphere_octant.geo";
