// The model built from the blocks: each object added as its block ends, each constraint too when
// both its objects are known by then (the rest, and the includes, at the end), and the
// diagnostics put in order under the cap.
#include <algorithm>
#include <cstring>

#include "dispcon/io/dcl_parser.hpp"

namespace dispcon::dcl {

void Declarations::reserve(size_t names) {
  entries_.reserve(names);
  size_t size = 8;
  while (size < 2 * names) size *= 2;
  if (size <= slots_.size()) return;
  slots_.assign(size, 0);
  const size_t mask = size - 1;
  for (size_t k = 0; k < entries_.size(); ++k) {
    size_t i = hash(entries_[k].first) & mask;
    while (slots_[i]) i = (i + 1) & mask;
    slots_[i] = static_cast<uint32_t>(k + 1);
  }
}

// Eight bytes at a time, each word mixed in by a multiplication, the high bits folded down: the
// slots are picked by the low ones.
uint64_t Declarations::hash(std::string_view name) {
  constexpr uint64_t kMix = 0x9E3779B97F4A7C15;
  uint64_t h = name.size() * kMix;
  size_t i = 0;
  for (; i + 8 <= name.size(); i += 8) {
    uint64_t w;
    std::memcpy(&w, name.data() + i, 8);
    h = (h ^ w) * kMix;
    h ^= h >> 29;
  }
  uint64_t tail = 0;
  for (size_t k = 0; i < name.size(); ++i, k += 8)
    tail |= uint64_t{static_cast<unsigned char>(name[i])} << k;
  h = (h ^ tail) * kMix;
  return h ^ (h >> 32);
}

std::pair<Declared*, bool> Declarations::try_emplace(std::string_view name, const Declared& d) {
  uint32_t* slot = lookup(name);
  if (*slot) return {&entries_[*slot - 1].second, false};
  if (2 * (entries_.size() + 1) > slots_.size()) {
    reserve(2 * entries_.size() + 1);
    slot = lookup(name);
  }
  entries_.emplace_back(name, d);
  *slot = static_cast<uint32_t>(entries_.size());
  return {&entries_.back().second, true};
}

void LaterList::add(Place at, bool error, std::string message) {
  if ((error ? errors++ : warnings++) < kErrorCap)
    listed.push_back({at, error, std::move(message)});
}

void Parser::report(LaterList* later, Place at, bool is_error, std::string message) {
  if (later) {
    later->add(at, is_error, std::move(message));
  } else if (is_error) {
    error(at, message);
  } else {
    warning(at, message);
  }
}

void Parser::replay(const LaterList& later) {
  for (const Later& l : later.listed) report(nullptr, l.at, l.error, l.message);
  // Those past the cap were counted, not kept: none of them would be listed.
  const auto cap = static_cast<long long>(kErrorCap);
  errors_ += later.errors - std::min(later.errors, cap);
  warnings_ += later.warnings - std::min(later.warnings, cap);
}

void Parser::add_object(ObjectBlock& ob) {
  if (ob.name.empty() || ob.name == "world") return;
  const auto [declared, first] = declared_.try_emplace(ob.name, Declared{ob.at, std::nullopt});
  if (!first) {
    objects_later_.add(ob.at, true,
                       "duplicate object '" + std::string(ob.name) + "' (first declared at line " +
                           std::to_string(declared->at.line) + ")");
    return;
  }
  if (!ob.ok) return;
  ob.body.name = std::string(ob.name);
  try {
    declared->body = model_.add_body(std::move(ob.body));
  } catch (const ValueError& e) {
    objects_later_.add(place(ob.seen, e.field(), ob.at), true, e.what());
  } catch (const std::invalid_argument& e) {
    objects_later_.add(ob.at, true, e.what());
  }
}

std::optional<BodyId> Parser::body_of(std::string_view name) const {
  if (name == "world") return Model::kWorld;
  const Declared* declared = declared_.find(name);
  return declared ? declared->body : std::nullopt;
}

void Parser::add_constraint(ConstraintBlock& cb, LaterList* later) {
  Joint& j = cb.joint;
  bool ok = cb.ok;
  auto resolve = [&](std::string_view name, const char* keyword, BodyId& out) {
    if (name == "world") {
      out = Model::kWorld;
      return;
    }
    const Declared* declared = declared_.find(name);
    if (!declared) {
      std::string why = "no 'object " + std::string(name) + "' block declares it";
      for (const std::string& r : rigid_) {
        if (name.size() > r.size() && name.compare(0, r.size(), r) == 0 && name[r.size()] == '.')
          why = r + " is a rigid include: its objects are one, '" + r + "'";
      }
      report(later, place(cb.seen, keyword, cb.at), true,
             "unknown object '" + std::string(name) + "' (" + why + ")");
      ok = false;
      return;
    }
    if (declared->body) {
      out = *declared->body;
    } else {
      ok = false;  // its object block had an error, reported there
    }
  };
  if (!cb.has_object2) {
    report(later, cb.at, true, "constraint needs 'object2'");
    ok = false;
  } else {
    resolve(cb.object1, "object1", j.body1);
    resolve(cb.object2, "object2", j.body2);
  }
  if (ok) add_resolved(cb, later);
}

void Parser::add_resolved(ConstraintBlock& cb, LaterList* later) {
  Joint& j = cb.joint;
  const size_t warned = model_.warnings().size();
  try {
    model_.add_joint(std::move(j));
  } catch (const JointError& e) {
    const Place statement = place(cb.seen, e.keyword(), cb.at);
    report(later, e.arg().empty() ? statement : place(cb.seen, e.keyword(), statement, e.arg()),
           true, e.detail());
  } catch (const ValueError& e) {
    report(later, place(cb.seen, e.field(), cb.at), true, e.what());
  } catch (const std::invalid_argument& e) {
    report(later, cb.at, true, e.what());
  }
  for (size_t k = warned; k < model_.warnings().size(); ++k) {
    const ModelWarning& w = model_.warnings()[k];
    report(later, place(cb.seen, w.keyword, cb.at), false, w.message);
  }
}

ParseResult Parser::build() {
  ParseResult result;
  // In the order they have always been listed: the objects' problems, the includes', then the
  // constraints'.
  replay(objects_later_);
  for (IncludeBlock& ib : includes_) include_into(model_, ib, declared_);
  replay(constraints_later_);
  for (ConstraintBlock& cb : constraints_) add_constraint(cb, nullptr);
  // The lexer's errors first, then the parser's, up to kErrorCap together.
  const long long lexed = static_cast<long long>(lex_errors_.listed.size()) + lex_errors_.more;
  result.diagnostics.reserve(diagnostics_.size() + lex_errors_.listed.size() + 2);
  for (const LexError& e : lex_errors_.listed)
    result.diagnostics.push_back({file_, e.line, e.column, true, e.message});
  long long parsed = 0;  // the parser's errors so far
  for (Diagnostic& d : diagnostics_) {
    if (!d.error || lexed + parsed++ < kErrorCap) result.diagnostics.push_back(std::move(d));
  }
  errors_ += lexed;
  // One last line for what the cap left out, at the end of the file.
  const Place end = at(current_);
  if (errors_ > kErrorCap) {
    result.diagnostics.push_back({file_, end.line, end.column, true,
                                  std::to_string(errors_ - kErrorCap) +
                                      " more errors (only the first " + std::to_string(kErrorCap) +
                                      " are listed)"});
  }
  if (warnings_ > kErrorCap) {
    result.diagnostics.push_back({file_, end.line, end.column, false,
                                  std::to_string(warnings_ - kErrorCap) +
                                      " more warnings (only the first " +
                                      std::to_string(kErrorCap) + " are listed)"});
  }
  if (errors_ == 0) result.model = std::move(model_);
  return result;
}

}  // namespace dispcon::dcl
