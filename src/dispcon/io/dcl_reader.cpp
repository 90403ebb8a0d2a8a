// The description language reader's doors (format.md): text or a file in, a model or
// diagnostics out. The parser is dcl_parser.hpp's.
#include "dispcon/io/dcl_reader.hpp"

#include <algorithm>
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
  size_t n = std::fread(text.data(), 1, text.size(), in);
  // More than the size said (a pipe says none): read on into the string's own room, doubled as
  // it fills. (A 64 kB buffer on the stack cost the command a page fault or two of its stack.)
  char more;
  if (n == text.size() && std::fread(&more, 1, 1, in) == 1) {
    text.resize(n);
    text.push_back(more);
    ++n;
    do {
      text.resize(std::max<size_t>(2 * n, size_t{1} << 16));
      n += std::fread(text.data() + n, 1, text.size() - n, in);
    } while (n == text.size());
  }
  text.resize(n);
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
