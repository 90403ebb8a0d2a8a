/* A planetary gear set: sun (20 teeth, pitch radius 1), three planets (10 teeth, 0.5) on a
   carrier (arm 1.5), ring (40 teeth, internal, 2). Sun, carrier and ring turn about z on the
   frame; each planet turns on the carrier. Each planet meshes the sun (`gear`, ratio 20/10) and
   the ring (internal mesh: `belt`, the same sense, ratio 10/40); turns are measured from the line
   of centres, which turns with the carrier, so Willis' formula
   (w_sun - w_carrier) / (w_ring - w_carrier) = -40/20 follows.
   Two degrees of freedom (hold the ring to get a 1 : 3 reduction from sun to carrier); the second
   and third planets' couplings repeat the first's equations, as the textbook says.

   Try:  dispcon check samples/planetary.dcl
         dispcon drag samples/planetary.dcl --body sun --to 0 0 0 --rotation 0 0 3 --steps 30 */

object sun; end
object ring; end
object carrier; end
object planet1; position 1.5 0 0; end
object planet2; position -0.75 1.299038105676658 0; end
object planet3; position -0.75 -1.299038105676658 0; end

constraint object2 sun;     hinge 0 0 0  0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object2 ring;    hinge 0 0 0  0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object2 carrier; hinge 0 0 0  0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object1 carrier; object2 planet1; hinge 1.5 0 0  0 0 0;                angle 0 0 1 0 0 1 max 0; end
constraint object1 carrier; object2 planet2; hinge -0.75 1.299038105676658 0  0 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object1 carrier; object2 planet3; hinge -0.75 -1.299038105676658 0  0 0 0; angle 0 0 1 0 0 1 max 0; end

constraint object1 sun; object2 planet1; gear 0 0 0  0 0 1  0 0 0  0 0 1 ratio 2; end
constraint object1 sun; object2 planet2; gear 0 0 0  0 0 1  0 0 0  0 0 1 ratio 2; end
constraint object1 sun; object2 planet3; gear 0 0 0  0 0 1  0 0 0  0 0 1 ratio 2; end
constraint object1 planet1; object2 ring; belt 0 0 0  0 0 1  0 0 0  0 0 1 ratio 0.25; end
constraint object1 planet2; object2 ring; belt 0 0 0  0 0 1  0 0 0  0 0 1 ratio 0.25; end
constraint object1 planet3; object2 ring; belt 0 0 0  0 0 1  0 0 0  0 0 1 ratio 0.25; end
