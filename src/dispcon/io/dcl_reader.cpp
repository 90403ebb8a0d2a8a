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

// In one go: sized from the file when it says its size, in chunks otherwise (a pipe). The room is
// not zeroed first: a std::string's resize wrote the file's every byte as zero (a memset of 255
// kB for the 400 four-bars, 2 % of the read's instructions) before the read wrote them again.
bool read_file(const std::string& path, FileText& text, std::string& why) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    why = "is a directory, not a .dcl file";
    return false;
  }
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (!in) {
    why = std::string("cannot open the file (") + std::strerror(errno) + ")";
    return false;
  }
  size_t room = 0;
  if (std::fseek(in, 0, SEEK_END) == 0) {
    const long size = std::ftell(in);
    if (size > 0) room = static_cast<size_t>(size);
    std::rewind(in);
  }
  text.reserve(room);
  size_t n = std::fread(text.data_.get(), 1, room, in);
  // More than the size said (a pipe says none): read on, the room doubled as it fills. (A 64 kB
  // buffer on the stack cost the command a page fault or two of its stack.)
  char more;
  if (n == room && std::fread(&more, 1, 1, in) == 1) {
    do {
      text.size_ = n;
      text.reserve(std::max<size_t>(2 * (n + 1), size_t{1} << 16));
      text.data_[n++] = more;
      n += std::fread(text.data_.get() + n, 1, text.room_ - n, in);
    } while (n == text.room_ && std::fread(&more, 1, 1, in) == 1);
  }
  text.size_ = n;
  std::fclose(in);
  return true;
}

void FileText::reserve(size_t room) {
  if (room <= room_) return;
  std::unique_ptr<char[]> bigger(new char[room]);  // not zeroed
  if (size_) std::memcpy(bigger.get(), data_.get(), size_);
  data_ = std::move(bigger);
  room_ = room;
}

}  // namespace dcl

ParseResult parse_dcl(std::string_view text, const std::string& filename) {
  // A file's own includes of itself are cycles too (its canonical path made at the first include).
  dcl::IncludeStack stack(filename);
  return dcl::parse_text(text, filename, stack);
}

ParseResult load_dcl(const std::string& path) {
  ParseResult r;
  dcl::FileText text;
  std::string why;
  if (!dcl::read_file(path, text, why)) {
    r.diagnostics.push_back({path, 0, 0, true, why});
    return r;
  }
  return parse_dcl(text.view(), path);
}

}  // namespace dispcon
