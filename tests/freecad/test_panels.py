"""What the joint and Drive panels rely on, in real FreeCAD (freecadcmd): joints named from their
parts (unique, in the Check's report, through a save and a reopen; an earlier document's names
kept), a sub-assembly instance's Grounded where it means holding the instance and hidden where
it means nothing, and a joint's Move explained. Each class opens and closes its own documents;
the panels themselves are tested under Xvfb (gui_workbench.py's TestPanelFixes)."""
import os
import re
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "freecad_workbench"))
sys.path.insert(0, os.path.join(REPO, "samples", "freecad"))
sys.path.insert(0, HERE)
os.environ["DISPCON_IMPORT_ONLY"] = "1"  # test_headless's helpers, not its tests
os.environ["DISPCON_SUB_IMPORT_ONLY"] = "1"  # test_subassembly's helpers, not its tests

import FreeCAD as App  # noqa: E402

import dispcon_fc.assembly as da  # noqa: E402
from dispcon_fc import objects, operations  # noqa: E402
import parts  # noqa: E402
import test_headless as th  # noqa: E402
import test_subassembly as ts  # noqa: E402

DUPLICATE_LABELS = "User parameter:BaseApp/Preferences/Document"


def close_all():
    for name in list(App.listDocuments()):
        App.closeDocument(name)


def pin(obj, local):
    return (obj, parts.circle_edge(obj.Shape, App.Vector(*local)))


def fourbar_by_parts(doc, tmp):
    """test_headless's four-bar, its joints made again as the joint panel makes them (named from
    their parts); returns (asm, ground, crank, coupler, rocker)."""
    asm, g, crank, coupler, rocker = th.fourbar(doc, tmp)
    crank.Label, rocker.Label = "Crank", "Rocker"
    for j in da.joints(asm):
        doc.removeObject(j.Name)
    for a, b in (((g, (0, 0, 0)), (crank, (0, 0, 0))), ((crank, (th.A, 0, 0)), (coupler, (0, 0, 0))),
                 ((coupler, (th.B, 0, 0)), (rocker, (th.C, 0, 0))), ((g, (th.D, 0, 0)), (rocker, (0, 0, 0)))):
        da.add_joint(asm, "Revolute", pin(*a), pin(*b), named_by_parts=True)
    return asm, g, crank, coupler, rocker


class JointNames(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.doc = App.newDocument("names")
        self.duplicates = App.ParamGet(DUPLICATE_LABELS).GetBool("DuplicateLabels", False)

    def tearDown(self):
        App.ParamGet(DUPLICATE_LABELS).SetBool("DuplicateLabels", self.duplicates)  # as it was
        close_all()

    def test_named_from_their_parts_unique_in_the_check_and_through_a_reopen(self):
        asm, g, crank, coupler, rocker = fourbar_by_parts(self.doc, self.tmp)
        names = ["Ground-Crank", "Crank-Coupler", "Coupler-Rocker", "Ground-Rocker"]
        self.assertEqual([j.Label for j in da.joints(asm)], names)
        self.assertTrue(all(operations.named_from_parts(j) for j in da.joints(asm)))
        self.assertTrue(da.solve(asm).converged)
        # The Check's report and the Drive's list name them so (a planar four-bar of revolutes
        # repeats one joint's equations: named by its parts).
        c = da.check(asm)
        self.assertEqual(c["dof"], 1)
        self.assertTrue(c["redundant"])
        for j in c["redundant"]:
            self.assertIn(j.Label, names)
        self.assertEqual([j.Label for j in da.drivable_joints(asm)], names)
        # Another joint between the same parts: numbered as FreeCAD numbers labels, even where
        # FreeCAD is told to allow duplicate labels.
        App.ParamGet(DUPLICATE_LABELS).SetBool("DuplicateLabels", True)
        again = da.add_joint(asm, "Revolute", pin(g, (0, 0, 0)), pin(crank, (0, 0, 0)), named_by_parts=True)
        self.assertEqual(again.Label, "Ground-Crank001")
        third = da.add_joint(asm, "Revolute", pin(g, (0, 0, 0)), pin(crank, (0, 0, 0)), named_by_parts=True)
        self.assertEqual(third.Label, "Ground-Crank002")
        self.assertTrue(operations.named_from_parts(third))
        self.doc.removeObject(again.Name)
        self.doc.removeObject(third.Name)
        # A script's joint is named by its type, as FreeCAD 1.x names joints (what --joint takes).
        scripted = da.add_joint(asm, "Revolute", pin(g, (0, 0, 0)), pin(crank, (0, 0, 0)))
        self.assertRegex(scripted.Label, r"^Revolute\d*$")
        self.assertFalse(operations.named_from_parts(scripted))
        self.doc.removeObject(scripted.Name)
        path = os.path.join(self.tmp, "named.FCStd")
        self.doc.saveAs(path)
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        asm = da.top_assemblies(self.doc)[0]
        self.assertEqual([j.Label for j in da.joints(asm)], names)
        self.assertTrue(all(operations.named_from_parts(j) for j in da.joints(asm)))
        self.assertTrue(da.solve(asm).converged)
        # Exported, the .dcl file's labels are the joints'.
        dcl = os.path.join(self.tmp, "named.dcl")
        da.export_dcl(asm, dcl)
        text = open(dcl).read()
        for name in names:
            self.assertIn('label "%s";' % name, text)

    def test_an_earlier_documents_joints_keep_their_names(self):
        path, _ = th.saved_fourbar(self.tmp)
        close_all()
        self.doc = App.openDocument(path)
        asm = da.top_assemblies(self.doc)[0]
        labels = [j.Label for j in da.joints(asm)]
        self.assertEqual(labels, ["Revolute", "Revolute001", "Coupler to rocker", "Revolute003"])
        self.assertFalse(any(operations.named_from_parts(j) for j in da.joints(asm)))
        self.assertTrue(da.solve(asm).converged)
        da.edit_joint(da.joints(asm)[0], rotation=(-30, 30))
        self.assertEqual([j.Label for j in da.joints(asm)], labels)


class InstanceGrounded(unittest.TestCase):
    """A sub-assembly instance's Grounded: shown where the instance is one body of the solve
    (rigid) and holding it there; hidden, and refused, where it would mean nothing (flexible)."""

    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.leg = ts.make_leg(self.tmp)
        self.doc, self.asm, self.frame, self.subs = ts.make_walker(self.tmp, self.leg, rigid=False,
                                                                  hip_joints=("Revolute",) * 4)

    def tearDown(self):
        close_all()

    def test_shown_and_holding_where_rigid_hidden_and_refused_where_flexible(self):
        leg = self.subs[0]
        self.assertEqual(leg.getEditorMode("Grounded"), ["Hidden"])
        self.assertIn("rigid instance only", leg.getDocumentationOfProperty("Grounded"))
        count = len(self.doc.UndoNames)
        with self.assertRaisesRegex(ValueError, "Leg1 cannot be grounded: it is flexible"):
            da.set_grounded(leg)
        self.assertFalse(leg.Grounded)
        self.assertEqual(len(self.doc.UndoNames), count)
        da.set_rigid(leg, True)
        self.assertEqual(leg.getEditorMode("Grounded"), [])
        self.assertTrue(da.solve(self.asm).converged)
        crank = ts.part(leg, "Crank")
        # Rigid and free on its hip's revolute, the leg turns whole when its crank is dragged.
        start = crank.Placement
        turned = App.Placement(start.Base, App.Rotation(App.Vector(0, 0, 1), 25).multiply(start.Rotation))
        da.drag(self.asm, crank, turned)
        self.assertGreater(crank.Placement.Rotation.multiply(start.Rotation.inverted()).Angle, 0.1)
        da.set_grounded(leg)
        self.assertTrue(leg.Grounded)
        held = [p.Placement for p in da.instance_parts(leg)]
        with self.assertRaisesRegex(ValueError, "Leg1 is grounded"):
            da.drag(self.asm, crank, App.Placement(App.Vector(1, 1, 1), App.Rotation()))
        self.assertTrue(da.solve(self.asm).converged)
        for p, q in zip(da.instance_parts(leg), held):
            self.assertTrue(th.same(p.Placement, q, 1e-12), p.Label)
        # Saved and reopened: shown on the rigid one, hidden on the flexible ones.
        self.doc.save()
        name = self.doc.Name
        App.closeDocument(name)
        self.doc = App.openDocument(os.path.join(self.tmp, "walker.FCStd"))
        subs = {s.Label: s for s in da.sub_assemblies(da.top_assemblies(self.doc)[0])}
        self.assertTrue(subs["Leg1"].Grounded)
        self.assertEqual(subs["Leg1"].getEditorMode("Grounded"), [])
        self.assertEqual(subs["Leg2"].getEditorMode("Grounded"), ["Hidden"])
        # Made flexible again (the property editor too): hidden.
        subs["Leg1"].Rigid = False
        self.assertEqual(subs["Leg1"].getEditorMode("Grounded"), ["Hidden"])


class MoveExplained(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.doc = App.newDocument("move")

    def tearDown(self):
        close_all()

    def test_move_says_what_minus_one_zero_and_one_do_also_in_an_earlier_document(self):
        asm, g, crank, coupler, rocker = th.fourbar(self.doc, self.tmp)
        j = da.joints(asm)[1]
        doc = j.getDocumentationOfProperty("Move")
        for words in ("ability to move", "-1 (the default)", "0: part 1 stays", "1: part 1 does it all",
                      "m2 / (m1 + m2)"):
            self.assertIn(words, doc)
        # A joint saved with the earlier words reads the new ones once reopened.
        j.setDocumentationOfProperty("Move", "part 1's share of a correction (-1: from the masses)")
        path = os.path.join(self.tmp, "move.FCStd")
        self.doc.saveAs(path)
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        j = da.joints(da.top_assemblies(self.doc)[0])[1]
        self.assertEqual(j.getDocumentationOfProperty("Move"), objects.MOVE_DOC)
        self.assertEqual(j.Move, -1)


def kinds_of(obj):
    """The DOCS tables (objects.DOCS) that say `obj`'s properties, by what the object is."""
    out = ["Any"]
    if objects.is_assembly(obj):
        out.append("Assembly")
    elif objects.is_joint(obj):
        out.append("Joint")
    elif objects.is_sub_assembly(obj):
        out += ["SubAssembly"] + (["NestedInstance"] if getattr(obj, "SourceName", "") else [])
    elif obj.TypeId == "App::Link" and "LocalPlacement" in obj.PropertiesList:
        out.append("InstanceLink")
    elif getattr(obj, "DispconType", "") in ("ExplodedView", "BOM"):
        out.append(obj.DispconType)
    elif "Grounded" in obj.PropertiesList:
        out.append("Part")
    else:
        return []
    return out


class PropertyDocs(unittest.TestCase):
    """Every property of every dispcon object (assembly, joints, parts, sub-assembly instances,
    nested ones and their links, an exploded view, a bill of materials) has its tooltip from one
    table, objects.DOCS, as made and once a document saved with older words is reopened."""

    def setUp(self):
        os.environ["DISPCON_NESTED_IMPORT_ONLY"] = "1"
        import test_nested as tn

        self.tmp = tempfile.mkdtemp()
        _, walker, _ = tn.make_walker_file(self.tmp, hip_joints=("Revolute",) * 4)
        self.doc, self.asm, track, walks = tn.make_parade(self.tmp, walker, rigid=False)
        from dispcon_fc import bom, exploded

        exploded.new_exploded_view(self.asm)
        bom.write_sheet(self.asm)
        self.doc.recompute()

    def tearDown(self):
        close_all()

    def dispcon_properties(self, doc):
        """{(object name, property): (its tooltip, the table's)} for every property the workbench
        gave an object of `doc` (those a bare object of its type lacks)."""
        bare = {}
        scratch = App.newDocument("bare")
        out, kinds = {}, set()
        try:
            for o in doc.Objects:
                tables = kinds_of(o)
                if not tables:
                    continue
                kinds.update(tables)
                if o.TypeId not in bare:
                    bare[o.TypeId] = set(scratch.addObject(o.TypeId, "Bare").PropertiesList)
                for name in set(o.PropertiesList) - bare[o.TypeId]:
                    if o.TypeId == "Spreadsheet::Sheet" and re.match(r"^[A-Z]+[0-9]+$", name):
                        continue  # a cell of the sheet (FreeCAD's own, a property each)
                    want = [objects.DOCS[t][name] for t in tables if name in objects.DOCS[t]]
                    out[(o.Name, name)] = (o.getDocumentationOfProperty(name), want[0] if want else None)
        finally:
            App.closeDocument(scratch.Name)
        return out, kinds

    def test_every_property_has_the_tables_tooltip_made_and_reopened(self):
        made, kinds = self.dispcon_properties(self.doc)
        self.assertEqual(kinds, set(objects.DOCS), "an object of each kind in the parade")
        missing = sorted(k for k, (_, want) in made.items() if want is None)
        self.assertEqual(missing, [], "properties the table does not say")
        self.assertEqual({k: v for k, v in made.items() if v[0] != v[1]}, {})
        self.assertIn(("Track", "Density"), made)
        self.assertGreater(len(made), 200)
        # Saved with older words on every one of them, reopened: the table's words.
        for (name, prop) in made:
            self.doc.getObject(name).setDocumentationOfProperty(prop, "older words")
        self.assertEqual(self.doc.getObject("Track").getDocumentationOfProperty("Density"), "older words")
        path = self.doc.FileName
        self.doc.save()
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        reopened, _ = self.dispcon_properties(self.doc)
        self.assertEqual(set(reopened), set(made))
        self.assertEqual(sorted(k for k, v in reopened.items() if v[0] != v[1]), [])
        self.assertFalse(self.doc.isTouched())


if True:  # run by freecadcmd as a script
    suite = unittest.TestSuite(unittest.defaultTestLoader.loadTestsFromTestCase(c)
                               for c in (JointNames, InstanceGrounded, MoveExplained, PropertyDocs)
                               if not os.environ.get("DISPCON_PANELS_ONLY") or c.__name__ == os.environ["DISPCON_PANELS_ONLY"])
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    failed = len(result.failures) + len(result.errors)
    print("%d passed, %d failed" % (result.testsRun - failed, failed))
    # freecadcmd would open the arguments after this script as documents.
    sys.exit(1 if failed else 0)
