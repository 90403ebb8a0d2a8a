// Crossed bounds refused by the model, with what a shell needs to say them in its own words.
#pragma once

#include <string>
#include <utility>

#include "dispcon/model/model.hpp"

namespace dispcon {

// A joint's bounds refused because min is above max: keyword() is the statement whose bounds
// they are ("twist", "axial", "angle", ...), min() and max() the bounds as given, in the
// statement's unit (radians for an angle, the model's length otherwise), so that a shell can say
// them in its own words and units, naming the joint as it knows it, without reading the message.
// Its what() is the command line's message.
class BoundsError : public JointError {
 public:
  enum class Unit { Length, Angle };
  BoundsError(const std::string& who, std::string keyword, std::string detail, double min,
              double max, Unit unit)
      : JointError(who, std::move(keyword), std::move(detail)), min_(min), max_(max), unit_(unit) {}
  double min() const { return min_; }
  double max() const { return max_; }
  Unit unit() const { return unit_; }

 private:
  double min_, max_;
  Unit unit_;
};

}  // namespace dispcon
