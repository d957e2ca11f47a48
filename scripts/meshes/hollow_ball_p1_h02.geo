// The hollow ball (hollow_ball_shape.inc) at mesh size 0.2 in linear
// tetrahedra (Tet4 runs of scripts/studies/hollow-ball.json).
// make-meshes order: 1
Include "hollow_ball_shape.inc";
Mesh.CharacteristicLengthMax = 0.2;
