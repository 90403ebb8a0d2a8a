// The description language (.dcl, format.md): reading into a Model.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dispcon/model/model.hpp"

namespace dispcon {

struct Diagnostic {
  std::string file;
  int line = 0;       // 1-based
  int column = 0;     // 1-based
  bool error = true;  // false: warning
  std::string message;

  // "FILE:LINE:COL: error: MESSAGE" (or "warning:")
  std::string format() const;
};

struct ParseResult {
  std::optional<Model> model;  // absent when any error was found
  std::vector<Diagnostic> diagnostics;
  bool ok() const { return model.has_value(); }
  // Every diagnostic formatted, one per line.
  std::string messages() const;
};

// Never throws on bad text; every problem becomes a diagnostic naming its place.
ParseResult parse_dcl(std::string_view text, const std::string& filename = "<string>");
// Reads the file; an unreadable file is a diagnostic at line 0.
ParseResult load_dcl(const std::string& path);

}  // namespace dispcon
