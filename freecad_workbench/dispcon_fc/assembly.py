"""The workbench's scripting API: assemblies of parts and joints in a FreeCAD document, solved by
dispcon. A facade: the objects are in `objects`, the bridge to the engine in `adapter`, the
operations in `operations`; scripts import this module only. Everything a designer does with the
mouse can be done from here under freecadcmd.

    import dispcon_fc.assembly as da
    asm = da.create_assembly(doc)
    crank = da.add_part(asm, crank_obj)                # an object of the document
    pin = da.import_part(asm, "/path/pin.step")        # or a STEP, IGES or BREP file
    da.add_joint(asm, "Revolute", (ground, "Edge3"), (crank, "Edge1"))
    result = da.solve(asm)                             # every joint holds, or nothing moved
    da.drag(asm, crank, placement)                     # the rest follows
    report = da.check(asm)
"""
from . import engine, geometry  # noqa: F401  (scripts reach the engine as da.engine)
from .adapter import Adapter, Result, live_curve, offered_types  # noqa: F401
from .objects import (COUPLINGS, JOINT_TYPES, AssemblyProxy, JointProxy, SubAssemblyProxy, adopt,  # noqa: F401
                      adopt_document, instance_parts, is_assembly, is_joint, is_sub_assembly, joints, nested_parts,
                      mesh_offset, part_properties, parts, phase_value, placed_parts, preferences, shape_of,
                      sub_assemblies, top_assemblies)
from .operations import (Drag, PointDrag, Transaction, add_joint, add_part, check,  # noqa: F401
                         create_assembly, drag, drivable, drivable_joints, drive, drive_limits, drive_to, drive_value,
                         driven_side, edit_joint, export_dcl,
                         import_dcl, import_part, interference, interference_along,
                         link_part, linkable_objects, set_grounded, set_limits, solve,
                         transaction)
from .subassembly import insert_sub_assembly, resolve, set_rigid  # noqa: F401
