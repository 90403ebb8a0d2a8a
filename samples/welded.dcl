/* A welded pair: a bracket welded to the world and a plate welded to the bracket (a hinge, an
   angle with max 0 and a twist: no rotation, no translation left, seed 4.2.3). 0 degrees of freedom.

   Try:  dispcon check samples/welded.dcl */

object bracket; position 0.1 0.2 0;   rotation 0.1 0 0.2; end
object plate;   position 1.2 0.1 0.1; rotation 0 0.3 0;   end

constraint object2 bracket; hinge 0 0 0  0 0 0;
  angle 0 0 1 0 0 1 max 0; twist 1 0 0 1 0 0; end
constraint object1 bracket; object2 plate; hinge 1 0 0  0 0 0;
  angle 0 0 1 0 0 1 max 0; twist 1 0 0 1 0 0; end
