// Typed ids: a body id cannot be passed where a joint id is expected.
#pragma once

namespace dispcon {

struct BodyId {
  int value = -1;
  friend bool operator==(BodyId a, BodyId b) { return a.value == b.value; }
  friend bool operator!=(BodyId a, BodyId b) { return a.value != b.value; }
};

struct JointId {
  int value = -1;
  friend bool operator==(JointId a, JointId b) { return a.value == b.value; }
  friend bool operator!=(JointId a, JointId b) { return a.value != b.value; }
};

}  // namespace dispcon
