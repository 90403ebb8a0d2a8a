#include "report.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iomanip>
#include <string>

namespace dispcon::cli {

namespace {

void write_numbers(JsonWriter& w, std::initializer_list<double> values) {
  w.numbers(values.begin(), values.size());
}

// A body's pose (and its dof when given), members in key order.
void write_pose(JsonWriter& w, const Pose& pose, const int* dof) {
  const Mat3 R = pose.rotation();
  Quat q = pose.q.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  w.begin_object();
  if (dof) {
    w.literal_key("dof");
    w.value(*dof);
  }
  w.literal_key("position");
  write_numbers(w, {pose.x.x(), pose.x.y(), pose.x.z()});
  w.literal_key("quaternion");
  write_numbers(w, {q.w(), q.x(), q.y(), q.z()});
  w.literal_key("rotation");
  w.begin_array();
  for (int i = 0; i < 3; ++i) write_numbers(w, {R(i, 0), R(i, 1), R(i, 2)});
  w.end_array();
  w.end_object();
}

// printf's "%<width>.6f" of a finite value, by std::to_chars: the same characters (both round the
// binary value's exact decimal expansion to nearest, ties to even; compared on 29 million values,
// dyadic ties and -0 among them), without printf's multiple-precision path, most of the time of
// the 100,000-link chain's listing.
char* fixed6(char* at, double v, int width) {
  char digits[48];
  const std::to_chars_result r =
      std::to_chars(digits, digits + sizeof digits, v, std::chars_format::fixed, 6);
  const auto n = static_cast<int>(r.ptr - digits);
  for (int k = n; k < width; ++k) *at++ = ' ';
  std::memcpy(at, digits, static_cast<size_t>(n));
  return at + n;
}

}  // namespace

void write_object(JsonWriter& w, std::vector<Member> members) {
  std::sort(members.begin(), members.end(),
            [](const Member& a, const Member& b) { return a.key < b.key; });
  w.begin_object();
  for (const Member& m : members) {
    w.key(m.key);
    m.write(w);
  }
  w.end_object();
}

void write_bodies(JsonWriter& w, const Model& model, const std::vector<Pose>& poses,
                  const std::vector<int>* dof) {
  // By name, as a sorted map has them: each name's first 16 bytes as two numbers whose order is
  // the bytes' (missing bytes 0), the whole names compared only where those are equal. The
  // strings compared at each step of the sort (a call to memcmp, through the model's bodies) were
  // a million instructions for the 400 four-bars' 1,200 names, 2 % of the command.
  struct Named {
    std::uint64_t first, second;  // bytes 0-7 and 8-15, the earlier byte the higher
    int body;
  };
  std::vector<Named> order;
  order.reserve(static_cast<size_t>(model.body_count()));
  for (int i = 1; i < model.body_count(); ++i) {
    const std::string& name = model.body(BodyId{i}).name;
    std::uint64_t key[2] = {0, 0};
    for (size_t k = 0; k < 16; ++k) {
      const auto byte = k < name.size() ? static_cast<unsigned char>(name[k]) : 0u;
      key[k / 8] = key[k / 8] << 8 | byte;
    }
    order.push_back({key[0], key[1], i});
  }
  std::sort(order.begin(), order.end(), [&](const Named& a, const Named& b) {
    if (a.first != b.first) return a.first < b.first;
    if (a.second != b.second) return a.second < b.second;
    return model.body(BodyId{a.body}).name < model.body(BodyId{b.body}).name;
  });
  w.begin_object();
  for (const Named& n : order) {
    const int i = n.body;
    w.key(model.body(BodyId{i}).name);
    write_pose(w, poses[static_cast<size_t>(i)], dof ? &(*dof)[static_cast<size_t>(i)] : nullptr);
  }
  w.end_object();
}

void write_constraints(JsonWriter& w, const Model& model,
                       const std::vector<ConstraintReport>& reports) {
  w.begin_array();
  for (const ConstraintReport& c : reports) {
    const Joint& j = model.joint(c.joint);
    w.begin_object();
    w.literal_key("active");
    w.value(c.active);
    w.literal_key("at_limit");
    w.value(c.at_limit);
    w.literal_key("index");
    w.value(c.joint.value);
    w.literal_key("line");
    w.value(c.line);
    w.literal_key("object1");
    w.value(model.body(j.body1).name);
    w.literal_key("object2");
    w.value(model.body(j.body2).name);
    w.literal_key("residual");
    w.value(c.residual);
    w.literal_key("satisfied");
    w.value(c.satisfied);
    w.end_object();
  }
  w.end_array();
}

void write_joint_list(JsonWriter& w, const std::vector<JointId>& ids) {
  w.begin_array();
  for (const JointId j : ids) w.value(j.value);
  w.end_array();
}

void write_strings(JsonWriter& w, const std::vector<std::string>& strings) {
  w.begin_array();
  for (const std::string& s : strings) w.value(s);
  w.end_array();
}

std::vector<Member> solve_members(const Model& model, const SolveResult& r,
                                  const std::vector<int>* body_dof) {
  return {{"converged", [&](JsonWriter& w) { w.value(r.converged); }},
          {"status", [&](JsonWriter& w) { w.value(to_string(r.status)); }},
          {"iterations", [&](JsonWriter& w) { w.value(r.iterations); }},
          {"seed_iterations", [&](JsonWriter& w) { w.value(r.seed_iterations); }},
          {"newton_iterations", [&](JsonWriter& w) { w.value(r.polish_iterations); }},
          {"max_residual", [&](JsonWriter& w) { w.value(r.max_residual); }},
          {"message", [&](JsonWriter& w) { w.value(r.message); }},
          {"bodies", [&, body_dof](JsonWriter& w) { write_bodies(w, model, r.poses, body_dof); }},
          {"constraints", [&](JsonWriter& w) { write_constraints(w, model, r.constraints); }}};
}

void print_json(const std::function<void(JsonWriter&)>& write) {
  std::string out;
  {
    JsonWriter w(out, stdout);
    write(w);
  }  // its last piece is in `out`
  out += '\n';
  std::fwrite(out.data(), 1, out.size(), stdout);
}

void csv_rows(std::ostream& out, const std::string& first, const Model& model,
              const std::vector<Pose>& poses) {
  char buf[512];
  for (int i = 1; i < model.body_count(); ++i) {
    const Pose& p = poses[static_cast<size_t>(i)];
    Quat q = p.q.normalized();
    if (q.w() < 0) q.coeffs() = -q.coeffs();
    std::snprintf(buf, sizeof buf, ",%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", p.x.x(), p.x.y(),
                  p.x.z(), q.w(), q.x(), q.y(), q.z());
    out << first << "," << model.body(BodyId{i}).name << buf << "\n";
  }
}

void print_poses(std::ostream& out, const Model& model, const std::vector<Pose>& poses) {
  out << "  " << std::left << std::setw(16) << "body" << std::setw(40) << "position"
      << "rotation vector\n";
  // Lines gathered in a buffer written out a piece at a time (the stream's formatting a line cost
  // as much as its numbers).
  std::string lines;
  constexpr size_t kPiece = size_t{1} << 16;
  lines.reserve(kPiece + 256);
  char buf[160];
  // Fixed point for the sizes of mechanisms; beyond a million, exponent form (1e+150 is not
  // written with 150 digits).
  auto fixed = [](const Vec3& v) { return (v.cwiseAbs().maxCoeff() < 1e6); };
  for (int i = 1; i < model.body_count(); ++i) {
    const Pose& p = poses[static_cast<size_t>(i)];
    const Vec3 r = p.rotation_vector();
    if (fixed(p.x) && r.allFinite()) {
      char* at = buf;
      for (int k = 0; k < 3; ++k) {
        if (k) *at++ = ' ';
        at = fixed6(at, p.x[k], 11);
      }
      std::memset(at, ' ', 6);
      at += 6;
      for (int k = 0; k < 3; ++k) {
        *at++ = ' ';
        at = fixed6(at, r[k], 10);
      }
      *at = '\0';
    } else {
      std::snprintf(buf, sizeof buf,
                    fixed(p.x) ? "%11.6f %11.6f %11.6f       %10.6f %10.6f %10.6f"
                               : "%11.5g %11.5g %11.5g       %10.6f %10.6f %10.6f",
                    p.x.x(), p.x.y(), p.x.z(), r.x(), r.y(), r.z());
    }
    const std::string& name = model.body(BodyId{i}).name;
    lines += "  ";
    lines += name;
    if (name.size() < 16) lines.append(16 - name.size(), ' ');
    lines += buf;
    lines += '\n';
    if (lines.size() >= kPiece) {
      out.write(lines.data(), static_cast<std::streamsize>(lines.size()));
      lines.clear();
    }
  }
  out.write(lines.data(), static_cast<std::streamsize>(lines.size()));
}

void print_solve(std::ostream& out, const Model& model, const SolveResult& r) {
  out << r.message << "\n";
  if (!r.converged) {
    out << "violated constraints:\n";
    for (const ConstraintReport& c : r.constraints) {
      if (c.satisfied) continue;
      const Joint& j = model.joint(c.joint);
      out << "  #" << c.joint.value << " (line " << c.line << ") " << model.body(j.body1).name
          << " / " << model.body(j.body2).name << ": residual " << c.residual << "\n";
    }
  }
}

}  // namespace dispcon::cli
