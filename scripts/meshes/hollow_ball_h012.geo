// The hollow ball (hollow_ball_shape.inc) at mesh size 0.12, for the study
// scripts/studies/hollow-ball.json.
Include "hollow_ball_shape.inc";
Mesh.CharacteristicLengthMax = 0.12;
// gmsh's second-order nodes on the curved surface can fold a thin element (an
// inverted Tet10, refused by hofem); its high-order optimiser untangles them.
Mesh.HighOrderOptimize = 2;
