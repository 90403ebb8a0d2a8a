/* A Sarrus linkage: a platform joined to the fixed base by two limbs of three parallel revolutes
   each, the two limbs' axes at right angles (x for limb a, y for limb b). Each limb alone lets the
   platform move in its own plane; together they leave one straight-line translation along z.
   Links are 1 long, along their local z; the platform starts tilted and off its place.

   Try:  dispcon drag samples/sarrus.dcl --body top --to 0 0 1.2 --steps 40
         dispcon check samples/sarrus.dcl */

object a1;  position 0 -0.5 0;     rotation -0.7 0 0;   end
object a2;  position 0 -1.1 0.8;   rotation 0.8 0 0;    end
object b1;  position 0.5 0 0;      rotation 0 0.6 0;    end
object b2;  position 1.0 0 0.9;    rotation 0 -0.7 0;   end
object top; position 0.1 0.05 1.5; rotation 0.05 0.1 0; end

// limb a: axes along x
constraint object2 a1;               hinge 0 -0.5 0  0 0 0;  angle 1 0 0 1 0 0 max 0; end
constraint object1 a1; object2 a2;   hinge 0 0 1     0 0 0;  angle 1 0 0 1 0 0 max 0; end
constraint object1 a2; object2 top;  hinge 0 0 1   0 -0.5 0; angle 1 0 0 1 0 0 max 0; end
// limb b: axes along y
constraint object2 b1;               hinge 0.5 0 0   0 0 0;  angle 0 1 0 0 1 0 max 0; end
constraint object1 b1; object2 b2;   hinge 0 0 1     0 0 0;  angle 0 1 0 0 1 0 max 0; end
constraint object1 b2; object2 top;  hinge 0 0 1   0.5 0 0;  angle 0 1 0 0 1 0 max 0; end
