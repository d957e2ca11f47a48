// The hollow ball (hollow_ball_shape.inc) at mesh size 0.2: the built-in
// scenes hollow-ball and hollow-ball-fcm.
Include "hollow_ball_shape.inc";
Mesh.CharacteristicLengthMax = 0.2;
