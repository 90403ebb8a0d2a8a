"""dispcon for FreeCAD: assemblies of parts joined by the displacement constraints of
Gascuel & Gascuel 1994, solved by the dispcon engine. The scripting API is in `assembly`."""
