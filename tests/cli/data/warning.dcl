// A hinge whose angle limit is out of range: read with a warning, clamped to pi.
object bar; end
constraint object2 bar; hinge 0 0 0 0 0 0; angle 0 0 1 0 0 1 max 9; end
