// The two-layer sphere's octant of meshes/two_layer_sphere_octant.geo at mesh size 0.1: the
// finer levels of the study (node spacing 0.133 and 0.1), whose geometric error must stay
// below the discretisation's.
size = 0.1;
Include "../../meshes/two_layer_sphere_octant.geo";
