// A closed box hull, 5.0 x 2.1 x 1.6 m, its floor centred on the origin, for flexbond's
// tests: gmsh -2 -format msh41 box_hull.geo -o box_hull.msh (gmsh 4.8.4, Debian bookworm).
SetFactory("Built-in");
L = 5.0; W = 2.1; H = 1.6; h = 0.25;
Point(1) = {-L/2, -W/2, 0, h}; Point(2) = {L/2, -W/2, 0, h};
Point(3) = {L/2, W/2, 0, h};   Point(4) = {-L/2, W/2, 0, h};
Point(5) = {-L/2, -W/2, H, h}; Point(6) = {L/2, -W/2, H, h};
Point(7) = {L/2, W/2, H, h};   Point(8) = {-L/2, W/2, H, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Line(9) = {1, 5}; Line(10) = {2, 6}; Line(11) = {3, 7}; Line(12) = {4, 8};
Curve Loop(1) = {1, 2, 3, 4};   Plane Surface(1) = {1};   // floor
Curve Loop(2) = {5, 6, 7, 8};   Plane Surface(2) = {2};   // roof
Curve Loop(3) = {1, 10, -5, -9}; Plane Surface(3) = {3};  // right side
Curve Loop(4) = {3, 12, -7, -11}; Plane Surface(4) = {4}; // left side
Curve Loop(5) = {2, 11, -6, -10}; Plane Surface(5) = {5}; // front
Curve Loop(6) = {4, 9, -8, -12}; Plane Surface(6) = {6};  // rear
// Load points embedded in the floor, so that they are nodes.
Point(20) = {-1.5, -0.5, 0, h}; Point(21) = {-1.5, 0.5, 0, h};
Point(22) = {1.5, -0.5, 0, h};  Point(23) = {1.5, 0.5, 0, h};
Point{20, 21, 22, 23} In Surface{1};
Transfinite Surface{2, 3, 4, 5, 6};
Recombine Surface{:};
Physical Surface("FLOOR") = {1};
Physical Surface("ROOF") = {2};
Physical Surface("SIDES") = {3, 4};
Physical Surface("ENDS") = {5, 6};
Physical Point("LOAD") = {20, 21, 22, 23};
Physical Point("FRONT_EDGE") = {3, 2};
Physical Point("REAR_EDGE") = {4, 1};
