// The second pass: names resolved, the model built from the blocks that parsed cleanly, and the
// diagnostics put in order under the cap.
#include "dispcon/io/dcl_parser.hpp"

namespace dispcon::dcl {

ParseResult Parser::build() {
  ParseResult result;
  Model model;
  model.reserve(objects_.size() + 1, constraints_.size());
  Declarations declared;
  declared.reserve(objects_.size());
  for (ObjectBlock& ob : objects_) {
    if (ob.name.empty() || ob.name == "world") continue;
    const auto [it, first] = declared.try_emplace(ob.name, Declared{ob.at, std::nullopt});
    if (!first) {
      error(ob.at, "duplicate object '" + std::string(ob.name) + "' (first declared at line " +
                       std::to_string(it->second.at.line) + ")");
      continue;
    }
    if (!ob.ok) continue;
    ob.body.name = std::string(ob.name);
    try {
      it->second.body = model.add_body(std::move(ob.body));
    } catch (const ValueError& e) {
      error(place(ob.seen, e.field(), ob.at), e.what());
    } catch (const std::invalid_argument& e) {
      error(ob.at, e.what());
    }
  }
  for (IncludeBlock& ib : includes_) include_into(model, ib, declared);
  for (ConstraintBlock& cb : constraints_) {
    Joint& j = cb.joint;
    bool ok = cb.ok;
    auto resolve = [&](std::string_view name, const char* keyword, BodyId& out) {
      if (name == "world") {
        out = Model::kWorld;
        return;
      }
      const auto it = declared.find(name);
      if (it == declared.end()) {
        std::string why = "no 'object " + std::string(name) + "' block declares it";
        for (const std::string& r : rigid_) {
          if (name.size() > r.size() && name.compare(0, r.size(), r) == 0 && name[r.size()] == '.')
            why = r + " is a rigid include: its objects are one, '" + r + "'";
        }
        error(place(cb.seen, keyword, cb.at),
              "unknown object '" + std::string(name) + "' (" + why + ")");
        ok = false;
        return;
      }
      if (it->second.body) {
        out = *it->second.body;
      } else {
        ok = false;  // its object block had an error, reported there
      }
    };
    if (!cb.has_object2) {
      error(cb.at, "constraint needs 'object2'");
      ok = false;
    } else {
      resolve(cb.object1, "object1", j.body1);
      resolve(cb.object2, "object2", j.body2);
    }
    if (!ok) continue;
    const size_t warned = model.warnings().size();
    try {
      model.add_joint(std::move(j));
    } catch (const JointError& e) {
      const Place statement = place(cb.seen, e.keyword(), cb.at);
      error(e.arg().empty() ? statement : place(cb.seen, e.keyword(), statement, e.arg()),
            e.detail());
    } catch (const ValueError& e) {
      error(place(cb.seen, e.field(), cb.at), e.what());
    } catch (const std::invalid_argument& e) {
      error(cb.at, e.what());
    }
    for (size_t k = warned; k < model.warnings().size(); ++k) {
      const ModelWarning& w = model.warnings()[k];
      warning(place(cb.seen, w.keyword, cb.at), w.message);
    }
  }
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
  if (errors_ == 0) result.model = std::move(model);
  return result;
}

}  // namespace dispcon::dcl
