// JSON written as it goes, with no document built first: the command line's output of a large
// model (a body, a constraint, a frame at a time) costs what printing it costs.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace dispcon::cli {

// Appends to a string the layout nlohmann::json::dump(2) gives the same values, byte for byte,
// which is what the documents have always been: two-space indents, `"key": value`, `[]` and
// `{}` when empty, doubles as nlohmann writes them (shortest round-trip digits, `.0` on whole
// numbers, null for NaN and infinities), strings escaped as JSON requires. Keys are written in
// the order given (the documents give them sorted: see write_object in report.hpp).
class JsonWriter {
 public:
  // What is written is kept in the writer's own buffer and appended to `out` in pieces, the last
  // when the writer is destroyed. With a `sink`, each full piece (64 kB) goes out to it instead:
  // a long document never sits whole in memory (the last piece still goes to `out`).
  explicit JsonWriter(std::string& out, std::FILE* sink = nullptr) : out_(out), sink_(sink) {}
  ~JsonWriter() { out_.append(buffer_, size_); }
  JsonWriter(const JsonWriter&) = delete;
  JsonWriter& operator=(const JsonWriter&) = delete;

  void begin_object();
  void end_object();
  void begin_array();
  void end_array();
  // The key of the member whose value comes next.
  void key(std::string_view k);
  // The same for a key written in the code as a string literal holding nothing to escape
  // ("position", "residual"): not searched for bytes to escape (12,000 keys of the 400
  // four-bars' document, 0.6 M instructions).
  // Inline, its copies of a size known where it is called (no call to memcpy a key).
  template <size_t N>
  void literal_key(const char (&k)[N]) {
    item();
    char* const out = room(N + 3);  // `"key": ` in one piece
    out[0] = '"';
    std::memcpy(out + 1, k, N - 1);
    std::memcpy(out + N, "\": ", 3);
    size_ += N + 3;
    after_key_ = true;
  }

  void value(double v);
  // An array of n numbers: begin_array(), value() of each, end_array(), in fewer steps (the 400
  // four-bars' document is 19,200 numbers in 7,200 arrays of three or four).
  void numbers(const double* v, size_t n);
  void value(int v);
  void value(bool v);
  void value(std::string_view s);
  void value(const char* s) { value(std::string_view(s)); }
  void value(const std::string& s) { value(std::string_view(s)); }

 private:
  static constexpr size_t kBuffer = size_t{1} << 16;

  // A new line and up to 30 spaces of indent (a document of 400 four-bars has some 48,000 new
  // lines, nearly all indented less).
  static constexpr size_t kShortLine = 32;
  static constexpr char kShortLineText[kShortLine + 1] = "\n                               ";
  static_assert(kShortLineText[kShortLine - 1] == ' ' && kShortLineText[kShortLine] == 0);

  // Room for `n` more bytes (n at most kBuffer) at the end of the buffer, which goes out first
  // when it has not that much left; the caller writes there and adds what it wrote to size_.
  char* room(size_t n) {
    if (size_ + n > kBuffer) flush();
    return buffer_ + size_;
  }
  void put(char c) {
    *room(1) = c;
    ++size_;
  }
  void put(const char* s, size_t n);
  void flush();

  // The comma, new line and indent before an array's item or an object's key; nothing before a
  // member's value (on its key's line), told here inline.
  void item() {
    if (after_key_) {
      after_key_ = false;
      return;
    }
    next_item();
  }
  void next_item();                    // item() but for a member's value
  void plain_key(std::string_view k);  // key() of a key with nothing to escape
  // A new line and the indent of the open containers. The short ones in a copy of fixed size,
  // a few moves instead of a call: the spaces copied beyond the indent lie past size_, where
  // the next bytes are written.
  void new_line() {
    const size_t indent = 2 * items_.size();
    if (indent + 1 >= kShortLine) return long_line(indent);
    std::memcpy(room(kShortLine), kShortLineText, kShortLine);
    size_ += indent + 1;
  }
  void long_line(size_t indent);
  void open(char bracket);
  void close(char bracket);
  void string(std::string_view s);
  // The text of a number at `out` (64 bytes of room), through the memo; returns its end.
  char* number_text(char* out, double v);

  // The text of the last numbers converted, by their bits (a direct-mapped table, an entry per
  // hash of the bits): a document repeats many of its numbers (the same part's rotations, the
  // same residuals in a model of like mechanisms), and a repeat is a copy of at most 24 bytes, not
  // a conversion (about 400 instructions). The longest text is 23 bytes (d.dddddddddddddddde-308).
  struct Memo {
    std::uint64_t bits;  // 0: empty (0.0 is a whole number, never converted here)
    char text[23];
    std::uint8_t size;
  };
  static_assert(sizeof(Memo) == 32);
  static constexpr int kMemoBits = 7;

  std::string& out_;
  std::FILE* sink_;
  std::vector<int> items_;  // per open container, its items so far
  bool after_key_ = false;
  size_t size_ = 0;  // bytes in buffer_
  // On the heap, not in the writer: a writer on the stack made the stack's first touch of 16
  // pages, each a page fault (17-20 us of CPU on the development VM), where the command's heap is
  // on huge pages already touched (main.cpp).
  std::unique_ptr<char[]> own_{new char[kBuffer]};
  char* const buffer_ = own_.get();
  std::unique_ptr<Memo[]> memo_{new Memo[size_t{1} << kMemoBits]()};  // empty: zeroed
};

}  // namespace dispcon::cli
