/* A crank-rocker four-bar (Grashof: shortest + longest <= the other two): crank 1, coupler 3,
   rocker 2.5, ground 3. Every joint is a revolute about z (a hinge plus `angle z z max 0`), so the
   planar linkage modelled in 3D has three redundant equations that the solver takes in its stride.
   The parts start off their joints; `dispcon assemble` puts them together.

   Try:  dispcon drag samples/fourbar.dcl --body crank --to 0 0 0 --rotation 0 0 3 --steps 60
         dispcon check samples/fourbar.dcl */

object crank;   position 0.1 -0.1 0.05;  rotation 0 0 0.4;  end
object coupler; position 1.2 0.6 -0.1;   rotation 0 0 0.2;  end
object rocker;  position 2.9 0.2 0.1;    rotation 0 0 1.9;  end

constraint object2 crank;                    hinge 0 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 crank;   object2 coupler; hinge 1 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 coupler; object2 rocker;  hinge 3 0 0  2.5 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object2 rocker;                   hinge 3 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end
