"""The parts' centres of mass the adapter keeps (adapter.Centres), in real FreeCAD (freecadcmd):
kept by the assembly they were integrated for, integrated again when a part's shape changes (a
part moved keeps its centre, which is in its own frame), never saved, and gone with the document
when it closes. Each test opens and closes its own documents."""
import gc
import os
import sys
import tempfile
import unittest
import weakref

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "freecad_workbench"))

import FreeCAD as App  # noqa: E402
import Part  # noqa: E402

import dispcon_fc.assembly as da  # noqa: E402
from dispcon_fc import adapter, geometry  # noqa: E402

Z = App.Vector(0, 0, 1)


class Integrations:
    """Counts OpenCascade's integrations of a centre of mass (geometry.center_of_mass, the real
    one, called through) while it is in use."""

    def __enter__(self):
        self.count = 0
        self.real = geometry.center_of_mass

        def counted(shape):
            self.count += 1
            return self.real(shape)

        geometry.center_of_mass = counted
        return self

    def __exit__(self, *exc):
        geometry.center_of_mass = self.real


def bar_assembly(doc, length):
    """A grounded plate and a bar `length` x 1 x 1 (its centre (length / 2, 0.5, 0.5) in its own
    frame) placed off the origin and turned."""
    asm = da.create_assembly(doc)
    plate = doc.addObject("Part::Feature", "Plate")
    plate.Shape = Part.makeBox(4, 4, 0.5)
    da.add_part(asm, plate, grounded=True)
    bar = doc.addObject("Part::Feature", "Bar")
    bar.Shape = Part.makeBox(length, 1, 1)
    da.add_part(asm, bar)
    bar.Placement = App.Placement(App.Vector(5, -2, 1), App.Rotation(Z, 30))
    return asm, bar


def centre(a, part):
    """The centre the adapter `a` gave `part`'s body, in the part's frame."""
    return App.Vector(*a.model.body(a.names[part.Name]).center)


class CentresFollowTheShapes(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("centres")

    def tearDown(self):
        if self.doc.Name in App.listDocuments():
            App.closeDocument(self.doc.Name)

    def assertVector(self, v, want, tol=1e-12):
        self.assertLessEqual((v - App.Vector(*want)).Length, tol, "%s, not %s" % (v, want))

    def test_a_changed_shape_is_integrated_again_and_a_moved_part_is_not(self):
        asm, bar = bar_assembly(self.doc, 2.0)
        with Integrations() as n:
            first = adapter.Adapter(asm)
        self.assertEqual(n.count, 2)  # the plate's and the bar's
        self.assertVector(centre(first, bar), (1.0, 0.5, 0.5))
        # Moved and turned: the same centre in its frame, from what was kept (no integration).
        bar.Placement = App.Placement(App.Vector(-3, 7, 2), App.Rotation(App.Vector(1, 1, 0), 70))
        with Integrations() as n:
            moved = adapter.Adapter(asm)
        self.assertEqual(n.count, 0)
        self.assertIs(moved.centres, first.centres)
        self.assertEqual(centre(moved, bar), centre(first, bar))
        # A new shape, twice as long: integrated again, the bar's alone.
        bar.Shape = Part.makeBox(4, 1, 1)
        bar.Placement = App.Placement(App.Vector(1, 2, 3), App.Rotation(Z, -40))
        with Integrations() as n:
            longer = adapter.Adapter(asm)
        self.assertEqual(n.count, 1)
        self.assertVector(centre(longer, bar), (2.0, 0.5, 0.5))
        # A parametric part recomputed with a new length: integrated again too.
        box = self.doc.addObject("Part::Box", "Block")
        box.Length, box.Width, box.Height = 1.0, 2.0, 3.0
        self.doc.recompute()
        da.add_part(asm, box)
        self.assertVector(centre(adapter.Adapter(asm), box), (0.5, 1.0, 1.5))
        box.Length = 5.0
        box.Placement = App.Placement(App.Vector(0, 0, 9), App.Rotation(Z, 15))
        self.doc.recompute()
        with Integrations() as n:
            grown = adapter.Adapter(asm)
        self.assertEqual(n.count, 1)
        self.assertVector(centre(grown, box), (2.5, 1.0, 1.5))
        self.assertVector(centre(grown, bar), (2.0, 0.5, 0.5))
        # The part's solid gone (a face has no volume): no centre, and none kept from before.
        bar.Shape = Part.makePlane(2, 1)
        flat = adapter.Adapter(asm)
        self.assertEqual(tuple(centre(flat, bar)), (0.0, 0.0, 0.0))  # the engine's default: the part's origin
        self.assertIsNone(flat.centres.known[self.doc.Name, bar.Name][1])

    def test_each_assembly_keeps_its_own_and_saves_none(self):
        asm, bar = bar_assembly(self.doc, 2.0)
        other = App.newDocument("centresOther")
        try:
            asm2, bar2 = bar_assembly(other, 3.0)  # the same object names in another document
            a, b = adapter.Adapter(asm), adapter.Adapter(asm2)
            self.assertIsNot(a.centres, b.centres)
            self.assertEqual({k[0] for k in a.centres.known}, {self.doc.Name})
            self.assertEqual({k[0] for k in b.centres.known}, {other.Name})
            self.assertVector(centre(a, bar), (1.0, 0.5, 0.5))
            self.assertVector(centre(b, bar2), (1.5, 0.5, 0.5))
        finally:
            App.closeDocument(other.Name)
        # Saved and read again: the assembly's proxy comes back with nothing kept, and the parts'
        # shapes (read from the file) are integrated anew.
        bar_name = bar.Name
        path = os.path.join(tempfile.mkdtemp(), "centres.FCStd")
        self.doc.saveAs(path)
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        asm = next(o for o in self.doc.Objects if da.is_assembly(o))
        self.assertIsNone(getattr(asm.Proxy, "centres", None))
        with Integrations() as n:
            a = adapter.Adapter(asm)
        self.assertEqual(n.count, 2)
        self.assertVector(centre(a, self.doc.getObject(bar_name)), (1.0, 0.5, 0.5))


class CentresGoWithTheDocument(unittest.TestCase):
    def test_closing_the_document_frees_its_centres(self):
        doc = App.newDocument("centresClosed")
        name = doc.Name
        asm, bar = bar_assembly(doc, 2.0)
        a = adapter.Adapter(asm)
        self.assertEqual(len(a.centres), 2)
        kept = weakref.ref(a.centres)
        del a, asm, bar
        App.closeDocument(name)
        gc.collect()
        self.assertIsNone(kept(), "the closed document's centres are still held")
        # Nothing of it anywhere else either: no Centres alive holds an entry of that document.
        left = [c for c in gc.get_objects() if isinstance(c, adapter.Centres) and any(k[0] == name for k in c.known)]
        self.assertEqual(left, [])


if True:  # run by freecadcmd as a script
    suite = unittest.TestSuite(unittest.defaultTestLoader.loadTestsFromTestCase(c)
                               for c in (CentresFollowTheShapes, CentresGoWithTheDocument))
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    failed = len(result.failures) + len(result.errors)
    print("%d passed, %d failed" % (result.testsRun - failed, failed))
    # freecadcmd would open the arguments after this script as documents.
    sys.exit(1 if failed else 0)
