/* A robot arm with joint limits: a base turning about the vertical y (+-2.5 rad), a shoulder and
   an elbow bending about z (shoulder -0.2..1.6 rad, elbow 0.2..2.4 rad: never quite straight), a hand on a ball joint
   whose tilt is kept within a cone of 0.5 rad and whose twist within +-1 rad. A limited revolute
   is a hinge, `angle a a max 0` (one axis) and a `twist` with bounds (the turn about it).
   Upper arm and forearm are 1 long, along their local x.

   Try:  dispcon drag samples/robot-arm.dcl --body hand --to 1.2 1.3 0.3 --steps 40
         dispcon drag samples/robot-arm.dcl --body hand --to 3 0.5 0 --steps 40   (beyond reach: stops) */

object base;     position 0 0.1 0;      end
object upper;    position 0.1 0.6 0;    rotation 0 0 0.7;  end
object forearm;  position 0.8 1.1 0.1;  rotation 0 0 -0.2; end
object hand;     position 1.6 1.0 0;    rotation 0 0 0.5;  end

constraint object2 base;
  hinge 0 0 0  0 0 0;  angle 0 1 0 0 1 0 max 0;  twist 1 0 0 1 0 0 min -2.5 max 2.5; end
constraint object1 base; object2 upper;
  hinge 0 0.5 0  0 0 0;  angle 0 0 1 0 0 1 max 0;  twist 1 0 0 1 0 0 min -0.2 max 1.6; end
constraint object1 upper; object2 forearm;
  hinge 1 0 0  0 0 0;  angle 0 0 1 0 0 1 max 0;  twist 1 0 0 1 0 0 min 0.2 max 2.4; end
constraint object1 forearm; object2 hand;
  hinge 1 0 0  0 0 0;  angle 1 0 0 1 0 0 max 0.5;  twist 0 1 0 0 1 0 min -1 max 1; end
