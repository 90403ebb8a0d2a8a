/* The equilibrist otary of the paper (section 5.3.2, Fig. 6): head, body and tail joined by
   point-to-point joints with angle and twist limits; a tray held on the nose by a point-to-point
   joint and kept almost horizontal by an angle constraint with the world; a ball on the tray by a
   point-to-ring constraint (a disc of radius 0.4). Forces and torques on the head and the tail make
   it move; the body is held by the world at its hip.

   Try:  dispcon animate samples/otary.dcl --duration 2 --dt 0.005 --gravity 0 -9.81 0 --svg otary.svg */

object body; position 0 0 0;      mass 4; inertia 0.4 0.8 0.8; center 0.5 0 0; end
object head; position 1.0 0.2 0;  mass 1; inertia 0.05 0.1 0.1; center 0.3 0 0; torque 0 0 0.8; end
object tail; position -0.8 0 0;   mass 1; inertia 0.05 0.1 0.1; center -0.3 0 0; force 0 3 0; end
object tray; position 1.6 0.3 0;  mass 0.3; inertia 0.02 0.04 0.02; end
object ball; position 1.7 0.45 0; mass 0.1; inertia 0.001 0.001 0.001; end

constraint object2 body; hinge 0 0 0  0 0 0; angle 0 0 1 0 0 1 max 0.2; twist 1 0 0 1 0 0 min -0.3 max 0.3; end
constraint object1 body; object2 head; hinge 1 0 0  0 0 0; angle 0 0 1 0 0 1 max 0.2; twist 1 0 0 1 0 0 min -0.8 max 0.8; end
constraint object1 body; object2 tail; hinge 0 0 0  0 0 0; angle 0 0 1 0 0 1 max 0.2; twist 1 0 0 1 0 0 min -0.8 max 0.8; end
// The tray on the nose, kept almost horizontal.
constraint object1 head; object2 tray; hinge 0.6 0.1 0  0 -0.05 0; end
constraint object2 tray; angle 0 1 0 0 1 0 max 0.1; end
// The ball on the tray: a disc of radius 0.4, 0.05 above the tray's origin.
constraint object1 tray; object2 ball; hinge 0 0.05 0  0 0 0; planar 0 1 0 max 0.4; end
