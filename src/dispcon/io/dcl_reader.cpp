// The description language reader's doors (format.md): text or a file in, a model or
// diagnostics out. The parser is dcl_parser.hpp's.
#include "dispcon/io/dcl_reader.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "dispcon/io/dcl_parser.hpp"

namespace dispcon {

std::string Diagnostic::format() const {
  std::ostringstream out;
  out << file;
  if (line > 0) out << ":" << line << ":" << column;  // line 0: the file as a whole
  out << ": " << (error ? "error" : "warning") << ": " << message;
  return out.str();
}

std::string ParseResult::messages() const {
  std::string out;
  for (const Diagnostic& d : diagnostics) out += d.format() + "\n";
  return out;
}

namespace dcl {

// In one go: sized from the file when it says its size, in chunks otherwise (a pipe).
bool read_file(const std::string& path, std::string& text) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    text = "is a directory, not a .dcl file";
    return false;
  }
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (!in) {
    text = std::string("cannot open the file (") + std::strerror(errno) + ")";
    return false;
  }
  text.clear();
  if (std::fseek(in, 0, SEEK_END) == 0) {
    const long size = std::ftell(in);
    if (size > 0) text.resize(static_cast<size_t>(size));
    std::rewind(in);
  }
  text.resize(std::fread(text.data(), 1, text.size(), in));
  char chunk[1 << 16];
  for (size_t n; (n = std::fread(chunk, 1, sizeof chunk, in)) > 0;) text.append(chunk, n);
  std::fclose(in);
  return true;
}

}  // namespace dcl

ParseResult parse_dcl(std::string_view text, const std::string& filename) {
  // A file's own includes of itself are cycles too (its canonical path made at the first include).
  dcl::IncludeStack stack(filename);
  return dcl::parse_text(text, filename, stack);
}

ParseResult load_dcl(const std::string& path) {
  ParseResult r;
  std::string text;
  if (!dcl::read_file(path, text)) {
    r.diagnostics.push_back({path, 0, 0, true, text});
    return r;
  }
  return parse_dcl(text, path);
}

}  // namespace dispcon
