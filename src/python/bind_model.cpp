// Models: reading .dcl text, building in code with the file format's vocabulary, poses.
#include <fstream>

#include "bindings.hpp"
#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/io/dcl_writer.hpp"

namespace dispcon::py {

namespace {

Model parsed(ParseResult r) {
  if (!r.ok()) throw std::invalid_argument(r.messages());
  return std::move(*r.model);
}

// What a joint joins and where it was declared; read by attribute, or by key as a dict.
struct JointInfo {
  int index = 0, line = 0;
  std::string object1, object2, label;
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

}  // namespace

ModelClass bind_model(pyb::module_& m) {
  pyb::class_<JointInfo>(m, "JointInfo", "One joint: the bodies it joins and its .dcl line.")
      .def_readonly("index", &JointInfo::index)
      .def_readonly("object1", &JointInfo::object1)
      .def_readonly("object2", &JointInfo::object2)
      .def_readonly("line", &JointInfo::line)
      .def_readonly("label", &JointInfo::label)
      .def(
          "__getitem__",
          [](const JointInfo& j, const std::string& key) -> pyb::object {
            if (key == "index") return pyb::int_(j.index);
            if (key == "line") return pyb::int_(j.line);
            if (key == "object1") return pyb::str(j.object1);
            if (key == "object2") return pyb::str(j.object2);
            if (key == "label") return pyb::str(j.label);
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
             const pyb::object& hinge, const pyb::object& axial, const pyb::object& planar,
             const pyb::object& sphere, const pyb::object& circle, const pyb::object& cylinder,
             const pyb::object& polyline, const pyb::object& angle, const pyb::object& twist,
             std::optional<double> move, const pyb::object& time, const std::string& label) {
            Joint j;
            j.body1 = body_id(model, object1);
            j.body2 = body_id(model, object2);
            j.label = label;
            j.move = move;
            if (!hinge.is_none()) {
              const pyb::sequence h = items(hinge, 2, "hinge (P1, P2)");
              j.has_hinge = true;
              j.p1 = vec3(h[0], "hinge P1");
              j.p2 = vec3(h[1], "hinge P2");
            }
            int guides = 0;
            auto guide = [&](GuideKind kind) {
              ++guides;
              Guide g;
              g.kind = kind;
              return g;
            };
            if (!axial.is_none()) {
              const pyb::sequence s = items(axial, 1, "axial (u, min, max)");
              Guide g = guide(GuideKind::Axial);
              g.dir = vec3(s[0], "axial u");
              g.min = bound(s, 1, -kInf);
              g.max = bound(s, 2, kInf);
              j.guide = g;
            }
            if (!planar.is_none()) {
              const pyb::sequence s = items(planar, 1, "planar (n, min, max)");
              Guide g = guide(GuideKind::Planar);
              g.dir = vec3(s[0], "planar n");
              g.min = bound(s, 1, 0);
              g.max = bound(s, 2, kInf);
              j.guide = g;
            }
            if (!sphere.is_none()) {
              const pyb::sequence s = items(sphere, 0, "sphere (min, max)");
              Guide g = guide(GuideKind::Sphere);
              g.min = bound(s, 0, 0);
              g.max = bound(s, 1, kInf);
              j.guide = g;
            }
            if (!circle.is_none()) {
              const pyb::sequence s = items(circle, 2, "circle (n, r)");
              Guide g = guide(GuideKind::Circle);
              g.dir = vec3(s[0], "circle n");
              g.radius = number(s[1], "circle r");
              j.guide = g;
            }
            if (!cylinder.is_none()) {
              const pyb::sequence s = items(cylinder, 2, "cylinder (u, r, min, max)");
              Guide g = guide(GuideKind::Cylinder);
              g.dir = vec3(s[0], "cylinder u");
              g.radius = number(s[1], "cylinder r");
              g.min = bound(s, 2, -kInf);
              g.max = bound(s, 3, kInf);
              j.guide = g;
            }
            if (!polyline.is_none()) {
              const pyb::sequence s = items(polyline, 2, "polyline");
              Guide g = guide(GuideKind::Polyline);
              for (const pyb::handle p : s) g.points.push_back(vec3(p, "polyline point"));
              j.guide = g;
            }
            if (guides > 1) {
              throw std::invalid_argument("a joint has at most one translation guide");
            }
            if (!angle.is_none()) {
              const pyb::sequence s = items(angle, 2, "angle (a1, a2, min, max)");
              j.angle = AngleSpec{vec3(s[0], "angle a1"), vec3(s[1], "angle a2"), bound(s, 2, 0),
                                  bound(s, 3, kPi)};
            }
            if (!twist.is_none()) {
              const pyb::sequence s = items(twist, 2, "twist (b1, b2, min, max)");
              j.twist = TwistSpec{vec3(s[0], "twist b1"), vec3(s[1], "twist b2"), bound(s, 2, 0),
                                  bound(s, 3, 0)};
            }
            if (!time.is_none()) {
              const pyb::sequence s = items(time, 2, "time (t0, t1)");
              j.t0 = number(s[0], "time t0");
              j.t1 = number(s[1], "time t1");
            }
            return model.add_joint(j).value;
          },
          pyb::arg("object2"), pyb::arg("object1") = "world", pyb::arg("hinge") = pyb::none(),
          pyb::arg("axial") = pyb::none(), pyb::arg("planar") = pyb::none(),
          pyb::arg("sphere") = pyb::none(), pyb::arg("circle") = pyb::none(),
          pyb::arg("cylinder") = pyb::none(), pyb::arg("polyline") = pyb::none(),
          pyb::arg("angle") = pyb::none(), pyb::arg("twist") = pyb::none(),
          pyb::arg("move") = pyb::none(), pyb::arg("time") = pyb::none(), pyb::arg("label") = "",
          "Adds a joint (a constraint block) and returns its index.")
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
      .def("joint_count", &Model::joint_count)
      .def(
          "joint",
          [](const Model& model, int i) {
            if (i < 0 || i >= model.joint_count())
              throw std::invalid_argument("no joint " + std::to_string(i));
            const Joint& j = model.joint(JointId{i});
            return JointInfo{i, j.line, model.body(j.body1).name, model.body(j.body2).name,
                             j.label};
          },
          pyb::arg("index"),
          "The joint's index, object1, object2, line (0 if built in code), label.")
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
