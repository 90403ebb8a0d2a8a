/* A Grashof double-rocker: the coupler is the shortest link (input rocker a = 2.5, coupler b = 1,
   output rocker c = 2.8, ground d = 3; 1 + 3 <= 2.5 + 2.8), so neither rocker turns fully. The
   input locks where the coupler and the output rocker line up: |AD| = b + c or c - b, that is at
   input angles acos((a^2 + d^2 - (b +- c)^2) / (2 a d)) = 1.5168 and 0.6425 rad.

   Try:  dispcon sweep samples/double-rocker.dcl --body input --from 0 --to 1 --steps 50 --plot lock.svg */

object input;   position 0 0 0;        rotation 0 0 1.0;  end
object coupler; position 1.35 2.1 0;   rotation 0 0 0.1;  end
object output;  position 3 0 0;        rotation 0 0 1.7;  end

constraint object2 input;                    hinge 0 0 0    0 0 0;   angle 0 0 1 0 0 1 max 0; end
constraint object1 input;   object2 coupler; hinge 2.5 0 0  0 0 0;   angle 0 0 1 0 0 1 max 0; end
constraint object1 coupler; object2 output;  hinge 1 0 0    2.8 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object2 output;                   hinge 3 0 0    0 0 0;   angle 0 0 1 0 0 1 max 0; end
