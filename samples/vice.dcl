/* A screw vice: the lead screw (pitch 0.2, right-handed) turns and travels along x in a nut of
   the frame (a cylindrical pair plus a `screw` coupling); it pushes the moving jaw, which slides
   along x on the frame and turns freely on the screw's end. One turn of the screw moves the jaw
   0.2. One degree of freedom.

   Try:  dispcon drag samples/vice.dcl --body jaw --to 1.4 0 0 --steps 20
         dispcon check samples/vice.dcl */

object screw; end
object jaw; position 1 0 0; end

constraint object2 screw; hinge 0 0 0  0 0 0; axial 1 0 0; angle 1 0 0 1 0 0 max 0;
                          screw 0 0 0  1 0 0  0 0 0  1 0 0 pitch 0.2; end
constraint object2 jaw;   hinge 1 0 0  0 0 0; axial 1 0 0; angle 0 0 1 0 0 1 max 0; twist 1 0 0 1 0 0; end
constraint object1 screw; object2 jaw; hinge 1 0 0  0 0 0; angle 1 0 0 1 0 0 max 0; end
