// Large but accepted numbers, so that mutations reach the ranges' edges (1e15) and beyond.
object arm; position 1e14 -2e13 5e12; rotation 0 0 1e5; mass 1e14; inertia 1e-14 1e14 1; velocity 1e15 0 0; end
constraint object2 arm; hinge 1e14 0 0  0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object1 arm; object2 world; axial 1 1 0 min -1e15 max 1e15; end
