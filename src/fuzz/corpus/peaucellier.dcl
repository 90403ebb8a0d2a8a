/* The Peaucellier-Lipkin straight-line linkage. O (the world's origin) and O' = (1, 0, 0) are
   fixed. Two arms of length l = 2 go from O to B and D; a rhombus of side s = 1.2 joins B and D to
   the inner point A and the outer point P; a crank of length r = 1 keeps A on the circle of centre
   O' through O. P is the inverse of A about O (|OA| |OP| = l^2 - s^2 = 2.56), so it moves on the
   straight line x = (l^2 - s^2) / (2 r) = 1.28. Every joint is a revolute about z. The crank can
   turn while l - s <= |OA|, that is within about +-2.3 rad of the x axis.

   Try:  dispcon sweep samples/peaucellier.dcl --body crank --from 0 --to 1.5 --steps 30 --csv p.csv */

object crank; position 1 0 0;          rotation 0 0 1.0;   end   // O' -> A
object ob;    position 0 0 0;          rotation 0 0 1.1;   end   // O -> B
object od;    position 0 0 0;          rotation 0 0 -0.1;  end   // O -> D
object ab;    position 1.5 0.8 0;      rotation 0 0 2.2;   end   // A -> B
object ad;    position 1.6 0.9 0;      rotation 0 0 -1.2;  end   // A -> D
object pb;    position 1.3 0.7 0;      rotation 0 0 2.0;   end   // P -> B
object pd;    position 1.25 0.65 0;    rotation 0 0 -0.9;  end   // P -> D

constraint object2 crank;             hinge 1 0 0    0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object2 ob;                hinge 0 0 0    0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object2 od;                hinge 0 0 0    0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 crank; object2 ab; hinge 1 0 0    0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 ab; object2 ad;    hinge 0 0 0    0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 ob; object2 ab;    hinge 2 0 0    1.2 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object1 od; object2 ad;    hinge 2 0 0    1.2 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object1 ob; object2 pb;    hinge 2 0 0    1.2 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object1 od; object2 pd;    hinge 2 0 0    1.2 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object1 pb; object2 pd;    hinge 0 0 0    0 0 0;    angle 0 0 1 0 0 1 max 0; end
