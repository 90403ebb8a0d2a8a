"""The joint panel: edits a joint's type and limits (Resources/ui/joint.ui)."""
import FreeCADGui as Gui

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
        f, j = self.form, self.joint
        doc = j.Document
        doc.openTransaction("Edit joint")
        j.JointType = f.jointType.currentText()
        j.HasRotationLimits = f.hasRotation.isChecked()
        j.RotationMin, j.RotationMax = f.rotationMin.value(), f.rotationMax.value()
        j.HasTravelLimits = f.hasTravel.isChecked()
        j.TravelMin, j.TravelMax = f.travelMin.value(), f.travelMax.value()
        j.ConeAngle = f.cone.value()
        doc.commitTransaction()
        Gui.Control.closeDialog()
        return True

    def reject(self):
        Gui.Control.closeDialog()
        return True
