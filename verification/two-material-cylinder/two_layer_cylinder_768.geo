// The two-layer quarter cylinder of meshes/two_layer_cylinder.geo with 768 straight pieces on
// the interface arc (512 on the bore, 1024 outside): chords within 8e-7 of the arcs, below the
// errors the study measures.
pieces = 768;
Include "../../meshes/two_layer_cylinder.geo";
