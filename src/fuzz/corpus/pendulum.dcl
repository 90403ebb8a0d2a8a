// A bar hinged to the world at its end, free to turn about z.
object bar; position 0.2 -0.1 0.05; rotation 0 0 0.3; end
constraint object2 bar; hinge 0 0 0 0 0 0; angle 0 0 1 0 0 1 max 0; end
