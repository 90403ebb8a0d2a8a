/* The flying snake of the paper (section 5.3.1, Fig. 5): six solids joined by five point-to-point
   constraints; a point-to-segment constraint lets the tail slide along a horizontal rod, between
   x = -1 and x = 1. The snake starts stretched out to the right of its tail, at rest; gravity pulls
   it down, the tail slides to the right until the bound stops it, the snake swings under the rod
   and flies back to the left, which makes the tail slide again.

   Try:  dispcon animate samples/snake.dcl --duration 3 --dt 0.005 --gravity 0 -9.81 0 --svg snake.svg */

object tail; position 0 0 0;    mass 1; inertia 0.003 0.021 0.021; center 0.25 0 0; end
object s1;   position 0.5 0 0;  mass 1; inertia 0.003 0.021 0.021; center 0.25 0 0; end
object s2;   position 1.0 0 0;  mass 1; inertia 0.003 0.021 0.021; center 0.25 0 0; end
object s3;   position 1.5 0 0;  mass 1; inertia 0.003 0.021 0.021; center 0.25 0 0; end
object s4;   position 2.0 0 0;  mass 1; inertia 0.003 0.021 0.021; center 0.25 0 0; end
object head; position 2.5 0 0;  mass 1; inertia 0.003 0.021 0.021; center 0.25 0 0; end

// The rod: the tail's end slides along x, within [-1, 1].
constraint object2 tail; hinge 0 0 0  0 0 0; axial 1 0 0 min -1 max 1; end

constraint object1 tail; object2 s1;   hinge 0.5 0 0  0 0 0; end
constraint object1 s1;   object2 s2;   hinge 0.5 0 0  0 0 0; end
constraint object1 s2;   object2 s3;   hinge 0.5 0 0  0 0 0; end
constraint object1 s3;   object2 s4;   hinge 0.5 0 0  0 0 0; end
constraint object1 s4;   object2 head; hinge 0.5 0 0  0 0 0; end
