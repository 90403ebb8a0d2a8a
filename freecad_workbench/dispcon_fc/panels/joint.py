"""The joint panel: edits a joint's type and limits (Resources/ui/joint.ui)."""
import FreeCADGui as Gui

from .. import operations
from ..feedback import report
from ..objects import JOINT_TYPES
from . import load_ui


class JointPanel:
    """Edits a joint's type and limits (ui/joint.ui)."""

    def __init__(self, joint):
        self.joint = joint
        self.form = load_ui("joint.ui")
        f = self.form
        f.jointType.addItems(JOINT_TYPES)
        f.jointType.setCurrentText(joint.JointType)
        f.hasRotation.setChecked(joint.HasRotationLimits)
        f.rotationMin.setValue(joint.RotationMin.Value)
        f.rotationMax.setValue(joint.RotationMax.Value)
        f.hasTravel.setChecked(joint.HasTravelLimits)
        f.travelMin.setValue(joint.TravelMin.Value)
        f.travelMax.setValue(joint.TravelMax.Value)
        f.cone.setValue(joint.ConeAngle.Value)

    def accept(self):
        f = self.form
        rotation = (f.rotationMin.value(), f.rotationMax.value()) if f.hasRotation.isChecked() else False
        travel = (f.travelMin.value(), f.travelMax.value()) if f.hasTravel.isChecked() else False
        try:
            operations.edit_joint(self.joint, joint_type=f.jointType.currentText(), rotation=rotation,
                                  travel=travel, cone=f.cone.value())
        except ValueError as e:  # limits that cannot hold: said, and the panel stays open
            report(str(e), error=True)
            return False
        Gui.Control.closeDialog()
        return True

    def reject(self):
        Gui.Control.closeDialog()
        return True
