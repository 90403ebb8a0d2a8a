/* The monocycle of Gascuel & Gascuel 1994 (section 5.3.3, Fig. 7 and 8).

   The constraint blocks below are Appendix A of the paper, verbatim (its last code block is the
   beginning of the file, the block before it the end). Oy is vertical. The object blocks are
   ours: every part starts at a rough position, off its joints, so that `dispcon assemble` shows
   the automatic search of valid positions (seed 2.3). Lengths: thigh 1, leg 1.4, pedals at 0.5
   from the wheel's centre, the wheel's centre 2 below the body's origin.

   Try:  dispcon assemble samples/monocycle.dcl
         dispcon drag samples/monocycle.dcl --body wheel --to 0 -2 0 --rotation 1.5 0 0 --steps 150
*/

object body;        position 0 0 0;            end
object wheel;       position 0.05 -2.1 0.1;    rotation 0.3 0 0;   end
object left-thigh;  position 0.4 -0.6 0;       rotation 1.0 0 0;   end
object right-thigh; position -0.4 -0.6 0;      rotation 1.3 0 0;   end
object left-leg;    position 0.4 -1.4 0.5;     rotation 2.5 0 0;   end
object right-leg;   position -0.4 -1.4 0.6;    rotation 2.7 0 0;   end
object left-foot;   position 0.4 -2.3 -0.4;    end
object right-foot;  position -0.4 -1.8 0.5;    end

/* Constraint between the wheel and the
character's body */
constraint object1 body; object2 wheel;
hinge 0 -2.0 0 0 0 0;
angle 1 0 0 1 0 0 max 0; end

/* Angle constraint preventing the character
from falling */
constraint object2 body; /* default object1:
world-fixed coordinate system */
angle 0 1 0 0 1 0 max 0.066; end

/* Constraints along the left leg */
constraint object1 body; object2 left-thigh;
hinge 0.4 -0.6 0 0 0 0;
angle 1 0 0 1 0 0 max 0; end

constraint object1 left-thigh;
object2 left-leg; hinge 0 0 1 0 0 0;
angle 1 0 0 1 0 0 max 0; end

constraint object1 left-leg;
object2 left-foot; hinge 0 0 1.4 0 0 -0.1;
angle 1 0 0 1 0 0 max 0; end

constraint object1 wheel; object2 left-foot;
hinge 0.4 0 -0.5 0 0 0; end

constraint object1 body; object2 left-foot;
angle 0 0 1 0 0 1 max .1; end

/* Constraints along the right leg */
constraint object1 body;
object2 right-thigh;
hinge -.4 -0.6 0 0 0 0;
angle 1 0 0 1 0 0 max 0.04; end

constraint object1 right-thigh;
object2 right-leg; hinge 0 0 1 0 0 0;
angle 1 0 0 1 0 0 max 0; end

constraint object1 right-leg;
object2 right-foot; hinge 0 0 1.4 0 0 -0.1;
angle 1 0 0 1 0 0 max 9; end

constraint object1 wheel;
object2 right-foot;
hinge -0.4 0 0.5 0 0 0; end

constraint object1 body; object2 right-foot;
angle 0 0 1 0 0 1 max .1; end
