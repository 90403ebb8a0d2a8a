object bar; end
constraint object2 bar;
  hinge 0 0 0 0 0 0
end
