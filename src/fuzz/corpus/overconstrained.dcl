// One point of a bar pinned at two places of the world one unit apart: impossible.
object bar; end
constraint object2 bar; hinge 0 0 0 0 0 0; end
constraint object2 bar; hinge 1 0 0 0 0 0; end
