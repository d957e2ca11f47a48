// Hollow ball with three orthogonal holes (the second seed's Fig. 1 / §6.4
// geometry in spirit: outer radius 1, inner radius 0.7, holes of radius 0.3
// along x, y and z). Meshed by scripts/make-meshes into hollow_ball.msh.
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1.0};
Sphere(2) = {0, 0, 0, 0.7};
Cylinder(3) = {-1.5, 0, 0, 3, 0, 0, 0.3};
Cylinder(4) = {0, -1.5, 0, 0, 3, 0, 0.3};
Cylinder(5) = {0, 0, -1.5, 0, 0, 3, 0.3};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2, 3, 4, 5}; Delete; }
Mesh.CharacteristicLengthMax = 0.2;
Physical Volume("ball") = {1};
