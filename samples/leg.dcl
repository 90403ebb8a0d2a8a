/* One leg: a crank-rocker four-bar (crank 1, coupler 3, rocker 2.5, ground 3; Grashof) whose
   coupler carries the foot at (1.5, -1.5, 0) of its frame. Drawn with the crank at 90 degrees,
   elbow up; every joint a revolute about z. One degree of freedom. samples/legs.dcl includes it
   four times.
   Try:  dispcon check samples/leg.dcl */

object crank;   rotation 0 0 1.5707963267948966; end
object coupler; position 0 1 0; rotation 0 0 0.51216119318615; end
object rocker;  position 3 0 0; rotation 0 0 1.7253864163355366; end

constraint object2 crank;                    hinge 0 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 crank;   object2 coupler; hinge 1 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 coupler; object2 rocker;  hinge 3 0 0  2.5 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object2 rocker;                   hinge 3 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end
