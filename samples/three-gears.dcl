/* A three-gear train on axles fixed to the frame: pitch radii 1, 2 and 1.5 (20, 40 and 30 teeth)
   at x = 0, 3 and 6.5. g1 drives g2 (ratio 1/2), g2 drives g3 (ratio 4/3): g3 turns 2/3 of g1's
   turn, the same way. Each gear is a revolute (hinge + angle z z max 0); each mesh a `gear`
   coupling between the two centres, turns measured from the line of centres. One degree of
   freedom.

   Try:  dispcon drag samples/three-gears.dcl --body g1 --to 0 0 0 --rotation 0 0 3 --steps 30
         dispcon check samples/three-gears.dcl */

object g1; end
object g2; position 3 0 0; end
object g3; position 6.5 0 0; end

constraint object2 g1; hinge 0 0 0  0 0 0;   angle 0 0 1 0 0 1 max 0; end
constraint object2 g2; hinge 3 0 0  0 0 0;   angle 0 0 1 0 0 1 max 0; end
constraint object2 g3; hinge 6.5 0 0  0 0 0; angle 0 0 1 0 0 1 max 0; end

constraint object1 g1; object2 g2; gear 0 0 0  0 0 1  0 0 0  0 0 1 ratio 0.5; end
constraint object1 g2; object2 g3; gear 0 0 0  0 0 1  0 0 0  0 0 1 ratio 1.3333333333333333; end
