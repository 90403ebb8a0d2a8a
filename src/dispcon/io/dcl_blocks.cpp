// `object` and `constraint` blocks: each statement as format.md and the components' table say.
#include <Eigen/Cholesky>
#include <cstdint>
#include <stdexcept>

#include "dispcon/io/dcl_parser.hpp"

namespace dispcon::dcl {

void Parser::object_block() {
  const Token kw = next();
  ObjectBlock ob;
  ob.at = at(kw);
  ob.body.line = kw.line;
  ob.seen = statements();
  const long long errors_before = errors_;
  try {
    ob.name = name("an object name");
    if (ob.name == "world") {
      error(ob.at, "'world' is reserved for the fixed world frame");
    }
    semicolon("the object name");
  } catch (const StatementError&) {
    recover();
  }
  Vec3 rotation = Vec3::Zero();
  while (!block_end(true, ob.name, ob.at)) {
    const Token t = next();
    try {
      const std::string_view k = keyword(t, "object", ob.name, ob.seen);
      Body& b = ob.body;
      if (k == "position") {
        b.pose.x = vec3("position");
      } else if (k == "rotation") {
        rotation = vec3("rotation");
      } else if (k == "fixed") {
        b.fixed = true;
      } else if (k == "rotate") {
        const double v = number("rotate");
        if (!(v > 0)) error(at(t), "rotate must be positive, found " + format_number(v));
        b.rotate = v;
      } else if (k == "mass") {
        const double v = number("mass");
        if (!(v > 0)) error(at(t), "mass must be positive, found " + format_number(v));
        b.mass = v;
      } else if (k == "inertia") {
        double v[6] = {0, 0, 0, 0, 0, 0};
        for (int i = 0; i < 3; ++i) v[i] = number("inertia");
        if (peek().kind == Token::Number) {
          for (int i = 3; i < 6; ++i) v[i] = number("inertia (Ixy Ixz Iyz)");
        }
        Mat3 J;
        J << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
        Eigen::LLT<Mat3> llt(J);
        if (llt.info() != Eigen::Success) {
          error(at(t), "inertia is not positive definite");
        }
        b.inertia = J;
      } else if (k == "center") {
        b.center = vec3("center");
      } else if (k == "velocity") {
        b.velocity = vec3("velocity");
      } else if (k == "spin") {
        b.spin = vec3("spin");
      } else if (k == "force") {
        b.force = vec3("force");
      } else if (k == "torque") {
        b.torque = vec3("torque");
      } else {
        error(at(t), "unknown object statement '" + std::string(k) +
                         "' (expected position, rotation, fixed, rotate, mass, inertia, center, "
                         "velocity, spin, force, torque or end)");
        throw StatementError{};
      }
      semicolon(k, true);
    } catch (const StatementError&) {
      recover();
    }
  }
  try {
    ob.body.pose.q = rotation_from_vector(rotation, "rotation");
  } catch (const ValueError& e) {
    error(place(ob.seen, e.field(), ob.at), object_label(ob.name) + ": " + e.what());
  }
  ob.ok = errors_ == errors_before;
  add_object(ob);
  statements_.resize(ob.seen.begin);  // its places were needed only for the model's refusals
}

void Parser::component_statement(const ComponentRow& row, std::string_view k, ConstraintBlock& cb) {
  ComponentValues v;
  for (const ArgSpec& a : row.args) {
    const What what(k, " ", a.name);
    mark(cb.seen, k, a.name, at(peek()));
    switch (a.kind) {
      case Arg::Point:
      case Arg::Direction:
        v.vectors.push_back(vec3(what));
        break;
      case Arg::PositiveLength:
      case Arg::NonNegativeLength:
        v.scalars.push_back(number(what));
        break;
      case Arg::NamedPositive: {
        const Token& w = peek();
        if (w.kind != Token::Word || w.text != a.name) {
          error(at(w), "expected '" + std::string(a.name) + "' in " + std::string(k) + ", found " +
                           quote(w));
          throw StatementError{};
        }
        skip();
        mark(cb.seen, k, a.name, at(peek()));
        v.scalars.push_back(number(what));
        break;
      }
      case Arg::Points: {
        const Place first = at(peek());
        std::vector<double> x;
        while (peek().kind == Token::Number) x.push_back(number(what));
        if (x.size() % 3 != 0) {
          error(first, std::string(k) + " needs three coordinates per point, found " +
                           std::to_string(x.size()) + " numbers");
          throw StatementError{};
        }
        for (size_t i = 0; i < x.size(); i += 3) v.points.emplace_back(x[i], x[i + 1], x[i + 2]);
        break;
      }
      case Arg::Flag:
        v.flags.push_back(false);
        break;
      case Arg::NamedOption:
        v.options.emplace_back();
        break;
    }
  }
  if (row.has_bounds) {
    v.bounds = row.defaults;
    bounds(k, v.bounds.min, v.bounds.max);
  } else {
    options(row, k, v, cb);
  }
  set_component(cb.joint, row, v);
  if (row.guide) cb.guide = k;
  if (row.coupling) cb.coupling = k;
}

void Parser::options(const ComponentRow& row, std::string_view k, ComponentValues& v,
                     ConstraintBlock& cb) {
  // Which arguments were given, a bit each (a row has a handful).
  std::uint64_t given = 0;
  const auto was_given = [&given](size_t i) { return ((given >> i) & 1) != 0; };
  if (row.args.size() > 64) throw std::logic_error("a row of components() has over 64 arguments");
  while (peek().kind == Token::Word) {
    size_t i = 0, flag = 0, option = 0;
    for (; i < row.args.size(); ++i) {
      const ArgSpec& a = row.args[i];
      if (is_optional(a.kind) && !was_given(i) && peek().text == a.name) break;
      flag += a.kind == Arg::Flag;
      option += a.kind == Arg::NamedOption;
    }
    if (i == row.args.size()) break;
    given |= std::uint64_t{1} << i;
    const ArgSpec& a = row.args[i];
    skip();
    mark(cb.seen, k, a.name, at(peek()));
    if (a.kind == Arg::Flag) {
      v.flags[flag] = true;
    } else {
      v.options[option] = number(What(k, " ", a.name));
    }
  }
  if (peek().kind != Token::Semicolon) {
    std::string expected;  // "'left', 'phase' or "
    for (size_t i = 0; i < row.args.size(); ++i)
      if (is_optional(row.args[i].kind) && !was_given(i))
        expected += "'" + std::string(row.args[i].name) + "', ";
    if (expected.empty()) semicolon(k);  // "expected ';' after hinge"
    expected.replace(expected.size() - 2, 2, " or ");
    error(at(peek()),
          "expected " + expected + "';' in " + std::string(k) + ", found " + quote(peek()));
    throw StatementError{};
  }
  skip();
}

void Parser::constraint_block() {
  const Token kw = next();
  ConstraintBlock cb;
  cb.at = at(kw);
  cb.joint.line = kw.line;
  cb.seen = statements();
  Joint& j = cb.joint;
  const long long errors_before = errors_;
  while (!block_end(false, {}, cb.at)) {
    const Token t = next();
    try {
      const std::string_view k = keyword(t, "constraint", {}, cb.seen);
      // object1 and object2 first: no component is named so, and every block has them.
      if (k == "object1") {
        cb.object1 = name("an object name");
        semicolon("object1");
      } else if (k == "object2") {
        cb.object2 = name("an object name");
        cb.has_object2 = true;
        semicolon("object2");
      } else if (const ComponentRow* row = find_component(k)) {
        if (row->guide && !cb.guide.empty()) {
          error(at(t), "a constraint has at most one translation guide: '" + std::string(k) +
                           "' after '" + std::string(cb.guide) + "' at line " +
                           std::to_string(place(cb.seen, cb.guide, cb.at).line));
          throw StatementError{};
        }
        if (row->coupling && !cb.coupling.empty()) {
          error(at(t), "a constraint has at most one coupling: '" + std::string(k) + "' after '" +
                           std::string(cb.coupling) + "' at line " +
                           std::to_string(place(cb.seen, cb.coupling, cb.at).line));
          throw StatementError{};
        }
        component_statement(*row, k, cb);
      } else if (k == "move") {
        j.move = number("move");
        semicolon("move");
      } else if (k == "time") {
        j.t0 = number("time t0", true);
        j.t1 = number("time t1", true);
        semicolon("time");
      } else if (k == "label") {
        if (peek().kind != Token::String) {
          if (peek().kind != Token::Bad)
            error(at(peek()),
                  "expected a string in double quotes for label, found " + quote(peek()));
          throw StatementError{};
        }
        j.label = std::string(next().text);
        semicolon("label");
      } else {
        std::string known;
        for (const ComponentRow& r : components()) known += std::string(r.keyword) + ", ";
        error(at(t), "unknown constraint statement '" + std::string(k) +
                         "' (expected object1, object2, " + known + "move, time, label or end)");
        throw StatementError{};
      }
    } catch (const StatementError&) {
      recover();
    }
  }
  cb.ok = errors_ == errors_before;
  // Added now when nothing before it waits and both its objects are bodies already; a
  // constraint that names an object declared later, or whose object was refused, waits for the
  // end, and every constraint after it, so that the joints keep the file's order.
  const std::optional<BodyId> body1 = in_place_ ? body_of(cb.object1) : std::nullopt;
  const std::optional<BodyId> body2 = body1 && cb.has_object2 ? body_of(cb.object2) : std::nullopt;
  if (body2) {
    j.body1 = *body1;
    j.body2 = *body2;
    if (cb.ok) add_resolved(cb, &constraints_later_);
    statements_.resize(cb.seen.begin);
  } else {
    in_place_ = false;
    constraints_.push_back(std::move(cb));
  }
}

}  // namespace dispcon::dcl
