// Models: reading .dcl text, building in code with the file format's vocabulary, poses.
#include <fstream>

#include "bindings.hpp"
#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/io/dcl_writer.hpp"
#include "dispcon/model/joint_kinds.hpp"

namespace dispcon::py {

namespace {

// Errors raise ValueError with every line; warnings (bounds clamped) go to Python's warnings
// module, each as the command line prints it.
Model parsed(ParseResult r) {
  if (!r.ok()) throw std::invalid_argument(r.messages());
  for (const Diagnostic& d : r.diagnostics)
    if (!d.error) warn(d.format());
  return std::move(*r.model);
}

// What a joint joins and where it was declared; read by attribute, or by key as a dict.
struct JointInfo {
  int index = 0, line = 0;
  std::string object1, object2, label, kind;
  // A coupling's phase as the model holds it now (it follows the turns); None for other joints.
  std::optional<double> phase;
};

// A live view of one body of a model: read only, changed through the model's checked setters.
struct BodyView {
  Model* model;
  BodyId id;
  const Body& get() const { return model->body(id); }
};

double number(const pyb::handle& h, const char* what) {
  try {
    if (!h.is_none()) return h.cast<double>();
  } catch (const pyb::cast_error&) {
  }
  throw std::invalid_argument(std::string(what) + " must be a number");
}

// (a, b, ...) as a sequence of at least `need` items.
pyb::sequence items(const pyb::object& o, size_t need, const char* what) {
  if (!pyb::isinstance<pyb::sequence>(o) || pyb::len(o) < need) {
    throw std::invalid_argument(std::string(what) + " needs at least " + std::to_string(need) +
                                " items");
  }
  return o.cast<pyb::sequence>();
}

// Optional item k of a sequence, or the default when absent or None.
double bound(const pyb::sequence& s, size_t k, double fallback) {
  if (pyb::len(s) <= k || s[k].is_none()) return fallback;
  return number(s[k], "a bound");
}

std::optional<Range> range(const pyb::handle& h, const char* what) {
  if (h.is_none()) return std::nullopt;
  const pyb::sequence s = items(pyb::reinterpret_borrow<pyb::object>(h), 2, what);
  return Range{number(s[0], what), number(s[1], what)};
}

// A joint from a row of joint_kinds(): its anchors and the limits it takes, by keyword.
Joint joint_of_kind(const Model& model, const std::string& kind, const std::string& object1,
                    const std::string& object2, const pyb::kwargs& kw) {
  const JointKindRow* row = find_joint_kind(kind);
  if (!row) {
    std::string known;
    for (const JointKindRow& r : joint_kinds())
      known += (known.empty() ? "" : ", ") + std::string(r.name);
    throw std::invalid_argument("unknown joint kind '" + kind + "' (expected " + known + ")");
  }
  Anchor at1, at2;
  JointLimits limits;
  std::vector<Vec3> curve;
  CouplingValues coupling;
  // A coupling kind also takes its row's value (ratio, radius or pitch), `left` and `phase`.
  std::vector<ArgSpec> coupling_args;
  if (row->coupling) {
    for (const ArgSpec& a : component(*row->coupling).args)
      if (a.kind == Arg::NamedPositive || is_optional(a.kind)) coupling_args.push_back(a);
  }
  auto coupling_arg = [&](const std::string& key) -> const ArgSpec* {
    for (const ArgSpec& a : coupling_args)
      if (key == a.name) return &a;
    return nullptr;
  };
  for (const auto& item : kw) {
    const std::string key = pyb::str(item.first);
    const pyb::handle v = item.second;
    if (key == "point1") {
      at1.point = vec3(v, "point1");
    } else if (key == "point2") {
      at2.point = vec3(v, "point2");
    } else if (key == "axis1") {
      at1.axis = vec3(v, "axis1");
    } else if (key == "axis2") {
      at2.axis = vec3(v, "axis2");
    } else if (key == "across1") {
      at1.across = vec3(v, "across1");
    } else if (key == "across2") {
      at2.across = vec3(v, "across2");
    } else if (key == "curve") {
      for (const pyb::handle p : items(pyb::reinterpret_borrow<pyb::object>(v), 2, "curve"))
        curve.push_back(vec3(p, "curve point"));
    } else if (key == "turn") {
      limits.turn = range(v, "turn (min, max)");
    } else if (key == "travel") {
      limits.travel = range(v, "travel (min, max)");
    } else if (key == "angle") {
      limits.angle = range(v, "angle (min, max)");
    } else if (key == "distance") {
      limits.distance = range(v, "distance (min, max)");
    } else if (key == "cone") {
      if (!v.is_none()) limits.cone = number(v, "cone");
    } else if (const ArgSpec* a = coupling_arg(key)) {
      if (v.is_none()) continue;
      if (a->kind == Arg::Flag) {
        if (!pyb::isinstance<pyb::bool_>(v))
          throw std::invalid_argument(key + " must be True or False");
        coupling.left = v.cast<bool>();
      } else if (a->kind == Arg::NamedOption) {
        coupling.phase = number(v, a->name.data());
      } else {
        coupling.value = number(v, a->name.data());
      }
    } else {
      std::string extra;
      for (const ArgSpec& a : coupling_args) extra += ", " + std::string(a.name);
      throw std::invalid_argument("add_joint(kind='" + kind +
                                  "') takes point1, point2, axis1, axis2, across1, across2, "
                                  "curve, turn, travel, cone, angle, distance" +
                                  extra + "; not '" + key + "'");
    }
  }
  return make_joint(row->kind, body_id(model, object1), at1, body_id(model, object2), at2, limits,
                    curve, coupling);
}

// A joint from the .dcl statements, each a tuple in the order the statement is written (the
// arguments of its row of components(), then min and max).
Joint joint_of_components(const pyb::kwargs& kw) {
  Joint j;
  const ComponentRow* guide = nullptr;
  for (const auto& item : kw) {
    const std::string key = pyb::str(item.first);
    const ComponentRow* row = find_component(key);
    if (!row) {
      std::string known;
      for (const ComponentRow& r : components()) known += std::string(r.keyword) + ", ";
      throw std::invalid_argument("add_joint takes kind=..., or the statements " + known +
                                  "move, time, label; not '" + key + "'");
    }
    if (item.second.is_none()) continue;
    if (row->guide && guide)
      throw std::invalid_argument(std::string("a joint has at most one translation guide: '") +
                                  key + "' with '" + std::string(guide->keyword) + "'");
    if (row->guide) guide = row;
    const pyb::object o = pyb::reinterpret_borrow<pyb::object>(item.second);
    ComponentValues v;
    v.bounds = row->defaults;
    // polyline=[p, q, ...] is its list of points; every other statement is a tuple, its
    // optional items (a screw's left, a coupling's phase) last and None when not given.
    const bool list_only = row->args.size() == 1 && row->args[0].kind == Arg::Points;
    size_t required = 0;
    for (const ArgSpec& a : row->args) required += !is_optional(a.kind);
    const pyb::sequence s = items(o, list_only ? 2 : required, key.c_str());
    size_t k = 0;
    for (const ArgSpec& a : row->args) {
      const std::string what = key + " " + std::string(a.name);
      const bool given = k < pyb::len(s) && !s[k].is_none();
      switch (a.kind) {
        case Arg::Point:
        case Arg::Direction:
          v.vectors.push_back(vec3(s[k++], what.c_str()));
          break;
        case Arg::PositiveLength:
        case Arg::NonNegativeLength:
        case Arg::NamedPositive:
          v.scalars.push_back(number(s[k++], what.c_str()));
          break;
        case Arg::Points:
          for (const pyb::handle p : s) v.points.push_back(vec3(p, what.c_str()));
          k = pyb::len(s);
          break;
        case Arg::Flag:
          if (given && !pyb::isinstance<pyb::bool_>(s[k]))
            throw std::invalid_argument(what + " must be True or False");
          v.flags.push_back(given && s[k].cast<bool>());
          ++k;
          break;
        case Arg::NamedOption:
          v.options.push_back(given ? std::optional(number(s[k], what.c_str())) : std::nullopt);
          ++k;
          break;
      }
    }
    if (row->has_bounds) {
      v.bounds.min = bound(s, k, row->defaults.min);
      v.bounds.max = bound(s, k + 1, row->defaults.max);
    }
    set_component(j, row->id, v);
  }
  return j;
}

}  // namespace

ModelClass bind_model(pyb::module_& m) {
  pyb::class_<JointInfo>(m, "JointInfo", "One joint: the bodies it joins and its .dcl line.")
      .def_readonly("index", &JointInfo::index)
      .def_readonly("object1", &JointInfo::object1)
      .def_readonly("object2", &JointInfo::object2)
      .def_readonly("line", &JointInfo::line)
      .def_readonly("label", &JointInfo::label)
      .def_readonly("kind", &JointInfo::kind, "its row of joint_kinds(), or 'constraint'")
      .def_readonly("phase", &JointInfo::phase,
                    "a coupling's phase now (radians for gear and belt, length for rack and "
                    "screw; it follows the turns as the model moves), None for other joints")
      .def(
          "__getitem__",
          [](const JointInfo& j, const std::string& key) -> pyb::object {
            if (key == "index") return pyb::int_(j.index);
            if (key == "line") return pyb::int_(j.line);
            if (key == "object1") return pyb::str(j.object1);
            if (key == "object2") return pyb::str(j.object2);
            if (key == "label") return pyb::str(j.label);
            if (key == "kind") return pyb::str(j.kind);
            if (key == "phase") return j.phase ? pyb::object(pyb::float_(*j.phase)) : pyb::none();
            throw pyb::key_error(key);
          },
          pyb::arg("key"))
      .def("__repr__", [](const JointInfo& j) {
        return "<dispcon.JointInfo " + std::to_string(j.index) + ": " + j.object1 + " -> " +
               j.object2 + ">";
      });
  pyb::class_<BodyView>(m, "Body", "A live view of one body of a model.")
      .def_property_readonly("name", [](const BodyView& b) { return b.get().name; })
      .def_property_readonly(
          "position", [](const BodyView& b) { return b.get().pose.x; },
          "world position of the local origin")
      .def_property_readonly(
          "rotation", [](const BodyView& b) { return b.get().pose.rotation(); },
          "3x3 rotation, local -> world")
      .def_property_readonly("quaternion",
                             [](const BodyView& b) {
                               Quat q = b.get().pose.q;
                               if (q.w() < 0) q.coeffs() = -q.coeffs();
                               return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
                             })
      .def_property_readonly("rotation_vector",
                             [](const BodyView& b) { return b.get().pose.rotation_vector(); })
      .def_property_readonly("center", [](const BodyView& b) { return b.get().center; })
      .def_property(
          "fixed", [](const BodyView& b) { return b.get().fixed; },
          [](BodyView& b, bool v) { b.model->set_fixed(b.id, v); })
      .def_property(
          "mass", [](const BodyView& b) { return b.get().mass; },
          [](BodyView& b, std::optional<double> v) { b.model->set_mass(b.id, v); })
      .def_property(
          "rotate", [](const BodyView& b) { return b.get().rotate; },
          [](BodyView& b, std::optional<double> v) { b.model->set_rotate(b.id, v); },
          "the no-physics ability to rotate (None: derived from the constrained points)")
      .def("__repr__", [](const BodyView& b) { return "<dispcon.Body '" + b.get().name + "'>"; });

  ModelClass model(m, "Model", "Bodies and joints (constraint blocks). Body 'world' is fixed.");
  model.def(pyb::init<>())
      .def(
          "add_body",
          [](Model& model, const std::string& name, const pyb::object& position,
             const pyb::object& rotation, const pyb::object& center, bool fixed,
             std::optional<double> rotate, std::optional<double> mass, const pyb::object& inertia) {
            Body b;
            b.name = name;
            b.pose.x = vec3(position, "position");
            b.pose.q = rotation_from(rotation);
            b.center = vec3(center, "center");
            b.fixed = fixed;
            b.rotate = rotate;
            b.mass = mass;
            if (!inertia.is_none()) {
              const pyb::array_t<double> a = pyb::array_t<double>::ensure(inertia);
              if (a && a.ndim() == 2) {
                if (a.shape(0) != 3 || a.shape(1) != 3)
                  throw std::invalid_argument("inertia: a matrix must be 3x3");
                b.inertia = inertia.cast<Mat3>();
              } else {
                const pyb::sequence s = items(inertia, 3, "inertia");
                Mat3 J = Mat3::Zero();
                J(0, 0) = number(s[0], "inertia");
                J(1, 1) = number(s[1], "inertia");
                J(2, 2) = number(s[2], "inertia");
                if (pyb::len(s) >= 6) {
                  J(0, 1) = J(1, 0) = number(s[3], "inertia");
                  J(0, 2) = J(2, 0) = number(s[4], "inertia");
                  J(1, 2) = J(2, 1) = number(s[5], "inertia");
                }
                b.inertia = J;
              }
            }
            model.add_body(b);
            return name;
          },
          pyb::arg("name"), pyb::arg("position") = pyb::make_tuple(0, 0, 0),
          pyb::arg("rotation") = pyb::make_tuple(0, 0, 0),
          pyb::arg("center") = pyb::make_tuple(0, 0, 0), pyb::arg("fixed") = false,
          pyb::arg("rotate") = pyb::none(), pyb::arg("mass") = pyb::none(),
          pyb::arg("inertia") = pyb::none(),
          "Adds a body; rotation is a rotation vector (axis * angle) or a 3x3 matrix.")
      .def(
          "add_joint",
          [](Model& model, const std::string& object2, const std::string& object1,
             const std::optional<std::string>& kind, std::optional<double> move,
             const pyb::object& time, const std::string& label, const pyb::kwargs& parts) {
            Joint j = kind ? joint_of_kind(model, *kind, object1, object2, parts)
                           : joint_of_components(parts);
            j.body1 = body_id(model, object1);
            j.body2 = body_id(model, object2);
            j.label = label;
            j.move = move;
            if (!time.is_none()) {
              const pyb::sequence s = items(time, 2, "time (t0, t1)");
              j.t0 = number(s[0], "time t0");
              j.t1 = number(s[1], "time t1");
            }
            const size_t warned = model.warnings().size();
            const JointId id = model.add_joint(j);
            for (size_t k = warned; k < model.warnings().size(); ++k)
              warn("joint " + std::to_string(id.value) + ": " + model.warnings()[k].message);
            return id.value;
          },
          pyb::arg("object2"), pyb::arg("object1") = "world", pyb::arg("kind") = pyb::none(),
          pyb::arg("move") = pyb::none(), pyb::arg("time") = pyb::none(), pyb::arg("label") = "",
          "Adds a joint and returns its index. Either a kind (dispcon.joint_kinds()) with\n"
          "point1, point2, axis1, axis2, across1, across2, curve and its limits (turn, travel,\n"
          "cone, angle, distance) or, for a coupling (gear, belt, rack, screw), its ratio,\n"
          "radius or pitch, left and phase; or the .dcl statements (hinge, axial, planar, sphere,\n"
          "circle, cylinder, polyline, angle, twist, gear, belt, rack, screw). A bound clamped\n"
          "into its range warns (dispcon.ModelWarning).")
      .def("body_names",
           [](const Model& model) {
             std::vector<std::string> out;
             for (int i = 1; i < model.body_count(); ++i) out.push_back(model.body(BodyId{i}).name);
             return out;
           })
      .def(
          "body",
          [](Model& model, const std::string& name) {
            const BodyId id = body_id(model, name);
            return BodyView{&model, id};
          },
          pyb::arg("name"), pyb::keep_alive<0, 1>())
      .def(
          "set_pose",
          [](Model& model, const std::string& name, const pyb::object& position,
             const pyb::object& rotation) {
            const BodyId id = body_id(model, name);
            Pose p = model.body(id).pose;
            if (!position.is_none()) p.x = vec3(position, "position");
            if (!rotation.is_none()) p.q = rotation_from(rotation);
            model.set_pose(id, p);
          },
          pyb::arg("name"), pyb::arg("position") = pyb::none(), pyb::arg("rotation") = pyb::none(),
          "Places a body: position, and rotation as a rotation vector or a 3x3 matrix.")
      // Every pose in one call: a live drag reads a hundred bodies a frame, and a call per
      // body and per value (body(n).position, .quaternion) cost more than the solve.
      .def(
          "poses",
          [](const Model& model) {
            const auto n = static_cast<pyb::ssize_t>(model.body_count() - 1);
            pyb::array_t<double> out({n, pyb::ssize_t{7}});
            auto a = out.mutable_unchecked<2>();
            for (pyb::ssize_t i = 0; i < n; ++i) {
              const Pose& p = model.body(BodyId{static_cast<int>(i) + 1}).pose;
              const double row[7] = {p.x.x(), p.x.y(), p.x.z(), p.q.w(), p.q.x(), p.q.y(), p.q.z()};
              for (pyb::ssize_t k = 0; k < 7; ++k) a(i, k) = row[k];
            }
            return out;
          },
          "Every body's pose as one array, a row per body in body_names() order: x, y, z and "
          "the quaternion w, x, y, z as the model holds it (q and -q are the same turn).")
      .def(
          "set_poses",
          [](Model& model,
             const pyb::array_t<double, pyb::array::c_style | pyb::array::forcecast>& poses) {
            const auto n = static_cast<pyb::ssize_t>(model.body_count() - 1);
            if (poses.ndim() != 2 || poses.shape(0) != n || poses.shape(1) != 7)
              throw std::invalid_argument("set_poses: an array of " + std::to_string(n) +
                                          " rows (one per body) of 7 numbers expected");
            auto a = poses.unchecked<2>();
            std::vector<Pose> all = model.poses();
            for (pyb::ssize_t i = 0; i < n; ++i) {
              if (model.body(BodyId{static_cast<int>(i) + 1}).fixed) continue;
              Pose& p = all[static_cast<size_t>(i) + 1];
              p.x = Vec3(a(i, 0), a(i, 1), a(i, 2));
              p.q = Quat(a(i, 3), a(i, 4), a(i, 5), a(i, 6));
            }
            model.set_poses(all);  // checked there, the couplings' turns counted
          },
          pyb::arg("poses"),
          "Places every body from an array as poses() gives (a fixed body keeps its pose).")
      .def("joint_count", &Model::joint_count)
      .def(
          "joint",
          [](const Model& model, int i) {
            if (i < 0 || i >= model.joint_count())
              throw std::invalid_argument("no joint " + std::to_string(i));
            const Joint& j = model.joint(JointId{i});
            return JointInfo{i,
                             j.line,
                             model.body(j.body1).name,
                             model.body(j.body2).name,
                             j.label,
                             kind_name(j),
                             j.coupling ? j.coupling->phase : std::nullopt};
          },
          pyb::arg("index"),
          "The joint's index, object1, object2, line (0 if built in code), label, kind, phase.")
      .def("to_dcl", &write_dcl, "The model as .dcl text.")
      .def(
          "save",
          [](const Model& model, const std::string& path) {
            std::ofstream out(path, std::ios::binary);
            out << write_dcl(model);
            out.flush();  // a full disk shows only when the buffer goes out
            if (out) out.close();
            if (!out) throw std::invalid_argument(path + ": cannot write the file");
          },
          pyb::arg("path"));

  m.def(
      "loads",
      [](const std::string& text, const std::string& filename) {
        return parsed(parse_dcl(text, filename));
      },
      pyb::arg("text"), pyb::arg("filename") = "<string>",
      "Reads .dcl text; ValueError with 'FILE:LINE:COL: error: ...' lines on bad input.");
  m.def(
      "load", [](const std::string& path) { return parsed(load_dcl(path)); }, pyb::arg("path"),
      "Reads a .dcl file; ValueError with 'FILE:LINE:COL: error: ...' lines on bad input.");
  return model;
}

}  // namespace dispcon::py
