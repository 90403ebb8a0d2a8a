// The joint vocabulary (joint_kinds.hpp) and the engine's defaults, as plain Python data: what
// the workbench and scripts read instead of repeating them.
#include "bindings.hpp"
#include "dispcon/model/bounds_error.hpp"
#include "dispcon/model/joint_kinds.hpp"

namespace dispcon::py {

namespace {

const char* to_string(AngleUse u) {
  switch (u) {
    case AngleUse::None:
      return "none";
    case AngleUse::Fixed:
      return "fixed";
    case AngleUse::Cone:
      return "cone";
    case AngleUse::Range:
      return "range";
  }
  return "?";
}

const char* to_string(TwistUse u) {
  switch (u) {
    case TwistUse::None:
      return "none";
    case TwistUse::Weld:
      return "weld";
    case TwistUse::Turn:
      return "turn";
  }
  return "?";
}

const char* to_string(Arg a) {
  switch (a) {
    case Arg::Point:
      return "point";
    case Arg::Direction:
      return "direction";
    case Arg::PositiveLength:
      return "positive length";
    case Arg::NonNegativeLength:
      return "non-negative length";
    case Arg::Points:
      return "points";
    case Arg::NamedPositive:
      return "named positive number";
    case Arg::Flag:
      return "flag";
    case Arg::NamedOption:
      return "named option";
  }
  return "?";
}

pyb::list limit_names(unsigned limits) {
  pyb::list out;
  const std::pair<unsigned, const char*> names[] = {{kTurnLimit, "turn"},
                                                    {kTravelLimit, "travel"},
                                                    {kConeLimit, "cone"},
                                                    {kAngleLimit, "angle"},
                                                    {kDistanceLimit, "distance"}};
  for (const auto& [flag, name] : names)
    if (limits & flag) out.append(name);
  return out;
}

}  // namespace

void warn(const std::string& message) {
  const pyb::object category = pyb::module_::import("dispcon").attr("ModelWarning");
  pyb::module_::import("warnings").attr("warn")(message, category, 2);
}

void bind_vocabulary(pyb::module_& m) {
  // A subclass of UserWarning, so that `warnings.simplefilter("error", dispcon.ModelWarning)`
  // turns a clamp into an exception.
  m.attr("ModelWarning") = pyb::reinterpret_steal<pyb::object>(
      PyErr_NewExceptionWithDoc("dispcon.ModelWarning",
                                "The model changed a value it was given (a bound clamped into "
                                "its natural range).",
                                PyExc_UserWarning, nullptr));
  // A ValueError, with the command line's message, that also says what it refused, so that a
  // shell (the workbench) names the joint and says the bounds in its own units without checking
  // them again or reading the message: statement ("twist", "axial", "angle", ...), min and max
  // as given, unit "angle" (radians) or "length".
  m.attr("LimitError") = pyb::reinterpret_steal<pyb::object>(PyErr_NewExceptionWithDoc(
      "dispcon.LimitError",
      "A joint's bounds with min above max (a ValueError): statement, min, max and unit "
      "('angle', radians, or 'length') say which.",
      PyExc_ValueError, nullptr));
  pyb::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const BoundsError& e) {
      const pyb::object type = pyb::module_::import("dispcon").attr("LimitError");
      const pyb::object error = type(e.what());
      error.attr("statement") = e.keyword();
      error.attr("min") = e.min();
      error.attr("max") = e.max();
      error.attr("unit") = e.unit() == BoundsError::Unit::Angle ? "angle" : "length";
      PyErr_SetObject(type.ptr(), error.ptr());
    }
  });
  const SolveOptions defaults;
  m.attr("DEFAULT_TOLERANCE") = defaults.tolerance;
  m.attr("DEFAULT_MAX_ITERATIONS") = defaults.max_iterations;
  m.def(
      "joint_kinds",
      [] {
        pyb::list out;
        for (const JointKindRow& r : joint_kinds()) {
          pyb::dict d;
          d["name"] = r.name;
          d["title"] = r.title;
          d["meaning"] = r.meaning;
          d["hinge"] = r.hinge;
          d["guide"] = r.guide ? pyb::object(pyb::str(to_string(*r.guide))) : pyb::none();
          d["angle"] = to_string(r.angle);
          d["angle_value"] = r.angle_value;
          d["twist"] = to_string(r.twist);
          d["limits"] = limit_names(r.limits);
          d["needs_points"] = r.needs_points();
          d["needs_axis"] = r.needs_axis();
          d["needs_across"] = r.needs_across();
          d["needs_curve"] = r.needs_curve();
          // A coupling's statement and what add_joint takes for it beside the anchors.
          pyb::list takes;
          if (r.coupling) {
            for (const ArgSpec& a : component(*r.coupling).args)
              if (a.kind == Arg::NamedPositive || is_optional(a.kind)) takes.append(a.name);
          }
          d["coupling"] = r.coupling ? pyb::object(pyb::str(to_string(*r.coupling))) : pyb::none();
          d["coupling_args"] = takes;
          out.append(d);
        }
        return out;
      },
      "The named joints, one dict per row of the engine's table: name (add_joint's kind), title,\n"
      "meaning, what it composes (hinge, guide, angle, twist, coupling), the limits it takes,\n"
      "what it needs, and a coupling's arguments (coupling_args: its ratio, radius or pitch,\n"
      "left, phase).");
  m.def(
      "components",
      [] {
        pyb::list out;
        for (const ComponentRow& r : components()) {
          pyb::dict d;
          d["keyword"] = r.keyword;
          d["meaning"] = r.meaning;
          d["guide"] = r.guide.has_value();
          d["coupling"] = r.coupling.has_value();
          pyb::list args;
          for (const ArgSpec& a : r.args) args.append(pyb::make_tuple(a.name, to_string(a.kind)));
          d["args"] = args;
          d["bounds"] = r.has_bounds ? pyb::object(pyb::make_tuple(r.defaults.min, r.defaults.max))
                                     : pyb::none();
          d["natural"] = r.has_bounds ? pyb::object(pyb::make_tuple(r.natural.min, r.natural.max))
                                      : pyb::none();
          out.append(d);
        }
        return out;
      },
      "The .dcl statements of a constraint block: keyword, meaning, its arguments (name, kind),\n"
      "default bounds and natural range (None without bounds).");
}

}  // namespace dispcon::py
