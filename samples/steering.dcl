/* A rack-and-pinion steering linkage, planar (axes along z): the pinion (pitch radius 0.3) turns
   on the frame at the origin; the rack slides along x below it; tie rods join the rack's ends to
   the steering arms of two knuckles pivoting on the frame (kingpins at x = -2 and 2). The rack
   travels 0.3 times the pinion's turn. One degree of freedom (the planar loops modelled in 3D
   repeat some equations, which `check` lists as redundant).

   Try:  dispcon drag samples/steering.dcl --body pinion --to 0 0 0 --rotation 0 0 0.6 --steps 12
         dispcon check samples/steering.dcl */

object pinion; end
object rack;      position 0 -0.3 0; end
object tie_l;     position -1 -0.3 0; end
object tie_r;     position 1 -0.3 0; end
object knuckle_l; position -2 -1.1 0; end
object knuckle_r; position 2 -1.1 0; end

constraint object2 pinion; hinge 0 0 0  0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object2 rack;   hinge 0 -0.3 0  0 0 0; axial 1 0 0; angle 0 0 1 0 0 1 max 0; twist 1 0 0 1 0 0; end
constraint object1 pinion; object2 rack; rack 0 0 0  0 0 1  0 0 0  1 0 0 radius 0.3; end

constraint object2 knuckle_l; hinge -2 -1.1 0  0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object2 knuckle_r; hinge 2 -1.1 0  0 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object1 rack; object2 tie_l;      hinge -1 0 0  0 0 0;         angle 0 0 1 0 0 1 max 0; end
constraint object1 rack; object2 tie_r;      hinge 1 0 0  0 0 0;          angle 0 0 1 0 0 1 max 0; end
constraint object1 knuckle_l; object2 tie_l; hinge 0.2 0.8 0  -0.8 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 knuckle_r; object2 tie_r; hinge -0.2 0.8 0  0.8 0 0;    angle 0 0 1 0 0 1 max 0; end
