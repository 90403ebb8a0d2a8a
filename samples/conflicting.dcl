/* A deliberately conflicting model: the four-bar of fourbar.dcl, plus a joint that pins the
   rocker's tip to a point of the world it cannot reach. `dispcon check` names that joint (line 17)
   as the one whose removal makes the model consistent.

   Try:  dispcon check samples/conflicting.dcl */

object crank;   position 0.1 -0.1 0.05;  rotation 0 0 0.4;  end
object coupler; position 1.2 0.6 -0.1;   rotation 0 0 0.2;  end
object rocker;  position 2.9 0.2 0.1;    rotation 0 0 1.9;  end

constraint object2 crank;                    hinge 0 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 crank;   object2 coupler; hinge 1 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 coupler; object2 rocker;  hinge 3 0 0  2.5 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object2 rocker;                   hinge 3 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end

// The conflict: the rocker's tip is 2.5 from its pivot (3, 0, 0); (9, 0, 0) is 6 away.
constraint object2 rocker;                   hinge 9 0 0  2.5 0 0; end
