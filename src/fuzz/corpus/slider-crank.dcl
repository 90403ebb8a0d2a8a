/* A slider-crank (an engine's crank, connecting rod and piston): crank r = 1 about z, rod l = 3,
   piston sliding along x with offset e = 0.2 (the slider's line is y = 0.2). The piston's
   position is x = r cos t + sqrt(l^2 - (r sin t - e)^2).
   The slider is a hinge with an `axial` guide (point to segment, seed 4.1.1) whose rotation is
   welded (`angle z z max 0` + `twist x x`, seed 4.2.3).

   Try:  dispcon drag samples/slider-crank.dcl --body crank --to 0 0 0 --rotation 0 0 3 --steps 60 */

object crank;  position 0 0 0.1;       rotation 0 0 0.5;  end
object rod;    position 0.7 0.5 0;     rotation 0 0 -0.3; end
object piston; position 3.4 0.4 -0.1;  end

constraint object2 crank;                hinge 0 0 0  0 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object1 crank; object2 rod;   hinge 1 0 0  0 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object1 rod;   object2 piston; hinge 3 0 0  0 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object2 piston;
  hinge 0 0.2 0  0 0 0;
  axial 1 0 0;
  angle 0 0 1 0 0 1 max 0;
  twist 1 0 0 1 0 0;
end
