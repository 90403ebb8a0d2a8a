/* A Bricard 6R linkage (the threefold-symmetric orthogonal one): six links of length 1 in a
   closed loop, each joint's axis at a right angle to the next (twists alternately +90 and -90
   degrees), no offsets. Six revolutes in a loop should leave no motion at all (Gruebler: 6 x 6 -
   6 x 5 - 6 = 0), yet this loop moves with one degree of freedom. Link i has joint i at its origin
   with axis z and joint i+1 at (1, 0, 0) with axis (0, -sin alpha_i, cos alpha_i); the world is
   link 1. The moving links start off their joints.

   Try:  dispcon check samples/bricard.dcl */

object link2; position 1.0300 -0.0200 0.0400; rotation 1.4266 -0.7793 0.7793; end
object link3; position 1.5703 -0.0200 0.8815; rotation -0.9312 -0.6771 1.7046; end
object link4; position 1.4037 0.9313 0.6221; rotation 0.6290 0.6092 2.5618; end
object link5; position 0.5995 1.4292 0.9467; rotation 1.0004 0.6554 -1.6725; end
object link6; position 0.4803 0.9371 0.0843; rotation 1.2832 -1.3923 -1.5780; end

// alpha = +90 deg: the next axis is -y in the link's frame; alpha = -90 deg: +y.
constraint object1 world; object2 link2; hinge 1 0 0  0 0 0; angle 0 -1 0  0 0 1  max 0; end
constraint object1 link2; object2 link3; hinge 1 0 0  0 0 0; angle 0 1 0   0 0 1  max 0; end
constraint object1 link3; object2 link4; hinge 1 0 0  0 0 0; angle 0 -1 0  0 0 1  max 0; end
constraint object1 link4; object2 link5; hinge 1 0 0  0 0 0; angle 0 1 0   0 0 1  max 0; end
constraint object1 link5; object2 link6; hinge 1 0 0  0 0 0; angle 0 -1 0  0 0 1  max 0; end
constraint object1 link6; object2 world; hinge 1 0 0  0 0 0; angle 0 1 0   0 0 1  max 0; end
