/* The monocycle pushed by a horizontal force on the character's body (section 5.3.3, Fig. 7), with
   masses and inertias. The constraints are Appendix A's; a plane constraint keeps the wheel's
   centre at the floor's height (the paper's floor was a collision model). The force drags the
   character, the legs and the wheel along through the constraints' closed loops.

   Try:  dispcon animate samples/monocycle-push.dcl --duration 2 --dt 0.01 --svg monocycle.svg */

object body;        position 0 0 0;       mass 30; inertia 2 1 2;       force 20 0 0; end
object wheel;       position 0 -2 0;      mass 5;  inertia 0.6 0.3 0.3; end
object left-thigh;  position 0.4 -0.6 0;  rotation 1.2 0 0; mass 4; inertia 0.35 0.35 0.02; center 0 0 0.5; end
object right-thigh; position -0.4 -0.6 0; rotation 1.2 0 0; mass 4; inertia 0.35 0.35 0.02; center 0 0 0.5; end
object left-leg;    position 0.4 -1.4 0.6; rotation 2.6 0 0; mass 3; inertia 0.5 0.5 0.02; center 0 0 0.7; end
object right-leg;   position -0.4 -1.4 0.6; rotation 2.6 0 0; mass 3; inertia 0.5 0.5 0.02; center 0 0 0.7; end
object left-foot;   position 0.4 -2.3 -0.4; mass 1; inertia 0.01 0.01 0.01; end
object right-foot;  position -0.4 -1.8 0.5; mass 1; inertia 0.01 0.01 0.01; end

constraint object2 wheel; planar 0 1 0; hinge 0 -2 0  0 0 0; end

constraint object1 body; object2 wheel; hinge 0 -2.0 0 0 0 0; angle 1 0 0 1 0 0 max 0; end
constraint object2 body; angle 0 1 0 0 1 0 max 0.066; end
constraint object1 body; object2 left-thigh; hinge 0.4 -0.6 0 0 0 0; angle 1 0 0 1 0 0 max 0; end
constraint object1 left-thigh; object2 left-leg; hinge 0 0 1 0 0 0; angle 1 0 0 1 0 0 max 0; end
constraint object1 left-leg; object2 left-foot; hinge 0 0 1.4 0 0 -0.1; angle 1 0 0 1 0 0 max 0; end
constraint object1 wheel; object2 left-foot; hinge 0.4 0 -0.5 0 0 0; end
constraint object1 body; object2 left-foot; angle 0 0 1 0 0 1 max .1; end
constraint object1 body; object2 right-thigh; hinge -.4 -0.6 0 0 0 0; angle 1 0 0 1 0 0 max 0.04; end
constraint object1 right-thigh; object2 right-leg; hinge 0 0 1 0 0 0; angle 1 0 0 1 0 0 max 0; end
constraint object1 right-leg; object2 right-foot; hinge 0 0 1.4 0 0 -0.1; angle 1 0 0 1 0 0 max 3.14159; end
constraint object1 wheel; object2 right-foot; hinge -0.4 0 0.5 0 0 0; end
constraint object1 body; object2 right-foot; angle 0 0 1 0 0 1 max .1; end
