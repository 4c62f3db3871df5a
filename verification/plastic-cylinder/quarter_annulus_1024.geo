// The quarter annulus of meshes/quarter_annulus.geo with 1024 straight pieces on the outer
// arc (512 on the inner): the polygon's sagitta on r = a is a (1 - cos(pi / 2048)) = 1.2e-6,
// below the discretisation errors the Lamé study measures.
pieces = 1024;
Include "../../meshes/quarter_annulus.geo";
