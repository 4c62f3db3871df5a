// A bar of two bonded materials, 2 x 0.2 x 0.2: steel on 0 <= x <= 1, aluminium beyond, meshed
// conformingly (Coherence) so that the two volumes share the face x = 1. Regions (physical
// volumes) steel and aluminium; parts (physical surfaces) left (x = 0) and right (x = 2).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.2, 0.2};
Box(2) = {1, 0, 0, 1, 0.2, 0.2};
Coherence;
Physical Volume("steel") = {1};
Physical Volume("aluminium") = {2};
e = 1e-6;
Physical Surface("left") = Surface In BoundingBox{-e, -e, -e, e, 0.2 + e, 0.2 + e};
Physical Surface("right") = Surface In BoundingBox{2 - e, -e, -e, 2 + e, 0.2 + e, 0.2 + e};
Mesh.MeshSizeMax = 0.1;
