/* A Bennett linkage: the spatial four-bar of four revolutes that moves although Gruebler's count
   says it should not (overconstrained, yet mobile). Opposite links are equal, a = 1 with twist
   alpha = 30 deg and b = sqrt(3) with twist beta = 60 deg, and a / sin(alpha) = b / sin(beta).
   Link i has joint i at its origin with axis z and joint i+1 at (a_i, 0, 0) with axis
   Rx(alpha_i) z = (0, -sin alpha_i, cos alpha_i). The world is link 1. Consecutive joint angles
   obey tan(t2/2) tan(t3/2) = -sin((beta + alpha)/2) / sin((beta - alpha)/2) (angles about z_i
   from the previous link's x to this link's x). The moving links start off their joints.

   Try:  dispcon check samples/bennett.dcl
         dispcon sweep samples/bennett.dcl --body link2 --axis 0 -0.5 0.8660254 --from 0 --to 6.2832 --steps 72 */

object link2; position 1.050 -0.040 0.030; rotation 0.483 -0.249 0.928;  end
object link3; position 2.108 1.140 0.764;  rotation -0.127 1.539 -1.400; end
object link4; position 1.672 0.448 0.212;  rotation -0.221 1.281 -2.340; end

// joint 2: world (link 1, a = 1, alpha = 30 deg) -> link2
constraint object1 world; object2 link2;
  hinge 1 0 0  0 0 0;  angle 0 -0.5 0.8660254037844387  0 0 1  max 0; end
// joint 3: link2 (b = sqrt 3, beta = 60 deg) -> link3
constraint object1 link2; object2 link3;
  hinge 1.7320508075688772 0 0  0 0 0;  angle 0 -0.8660254037844386 0.5  0 0 1  max 0; end
// joint 4: link3 (a = 1, alpha = 30 deg) -> link4
constraint object1 link3; object2 link4;
  hinge 1 0 0  0 0 0;  angle 0 -0.5 0.8660254037844387  0 0 1  max 0; end
// joint 1: link4 (b = sqrt 3, beta = 60 deg) -> the world's origin, axis z
constraint object1 link4; object2 world;
  hinge 1.7320508075688772 0 0  0 0 0;  angle 0 -0.8660254037844386 0.5  0 0 1  max 0; end
