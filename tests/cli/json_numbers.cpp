// JsonWriter's doubles against nlohmann's dump, digit for digit: the whole numbers it writes
// itself (every integer in [-2e6, 2e6], powers of ten and their neighbours up to 1e15, millions
// of random ones), and random doubles of every magnitude and bit pattern, which the writer
// converts with its own copy of nlohmann's Grisu2. Then its strings and keys, byte for byte as
// nlohmann's dump(2) escapes and lays them out: every length up to 40 with a byte that must be
// escaped (each control character, the quote, the backslash) at every place, among plain ASCII and
// multi-byte UTF-8 (the writer tests eight bytes at a time, with overlapping words at the ends).
// Exit 1 and the first differences when any differs.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "json_writer.hpp"

int main() {
  long tested = 0, differ = 0;
  auto test = [&](double v) {
    std::string out;
    dispcon::cli::JsonWriter(out).value(v);
    const std::string expected = nlohmann::json(v).dump();
    ++tested;
    if (out != expected && differ++ < 10)
      std::printf("%.17g: wrote %s, nlohmann %s\n", v, out.c_str(), expected.c_str());
  };
  for (long i = -2000000; i <= 2000000; ++i) test(static_cast<double>(i));
  test(-0.0);
  for (double p = 1; p < 1e16; p *= 10) {
    for (double d = -3; d <= 3; ++d) {
      test(p + d);
      test(-(9 * p + d));
    }
  }
  std::mt19937_64 random(14);
  for (int i = 0; i < 2000000; ++i) {
    const double magnitude = std::ldexp(static_cast<double>(random() >> 11), -int(random() % 64));
    test((random() & 1 ? -1 : 1) * std::trunc(magnitude));
    test((random() & 1 ? -1 : 1) * magnitude);
  }
  // Every bit pattern alike (every exponent, subnormals too: the writer's own Grisu2 takes the
  // branches nlohmann's takes), and the values a solve writes: cosines, sines and their products,
  // near 1 and near 0.
  for (int i = 0; i < 3000000; ++i) {
    const std::uint64_t bits = random();
    double v;
    std::memcpy(&v, &bits, sizeof v);
    if (std::isfinite(v)) test(v);
    const double angle = std::ldexp(static_cast<double>(random() >> 11), -53) * 7 - 3.5;
    test(std::cos(angle));
    test(std::sin(angle) * std::cos(3 * angle));
    test(std::ldexp(std::sin(angle), -int(random() % 40)));
  }
  for (std::uint64_t bits = 0; bits < 100000; ++bits) {  // the smallest subnormals
    double v;
    std::memcpy(&v, &bits, sizeof v);
    test(v);
  }
  for (int e = -1074; e <= 1023; ++e) {  // powers of two, where the lower bound is closer
    for (const double d : {-1.0, 0.0, 1.0}) {
      const double v = std::ldexp(1.0, e);
      test(v + d * std::ldexp(1.0, e - 52));
    }
  }
  std::printf("%ld doubles, %ld differ from nlohmann's\n", tested, differ);

  // One writer writing many numbers, as a document does: its memo of the texts of the numbers
  // last converted (by their bits) hits on every repeat, and loses entries to other numbers of the
  // same hash. Each array of numbers drawn from a pool with repeats (of both signs, the pools from
  // 3 to 3,000 numbers: the memo's 128 entries filled, and overwritten over and over) against
  // nlohmann's dump of the same array.
  long arrays = 0, arrays_differ = 0;
  for (const int pool_size : {3, 40, 128, 300, 3000}) {
    std::vector<double> pool;
    for (int i = 0; i < pool_size; ++i) {
      const double angle = std::ldexp(static_cast<double>(random() >> 11), -53) * 7 - 3.5;
      pool.push_back(i % 3 == 0 ? std::cos(angle) : std::ldexp(std::sin(angle), -int(i % 70)));
    }
    for (int round = 0; round < 20; ++round) {
      nlohmann::json expected = nlohmann::json::array();
      std::string out;
      {
        dispcon::cli::JsonWriter w(out);
        w.begin_array();
        for (int i = 0; i < 5000; ++i) {
          const double v = (random() & 1 ? -1 : 1) * pool[random() % pool.size()];
          w.value(v);
          expected.push_back(v);
        }
        w.end_array();
      }
      ++arrays;
      if (out != expected.dump(2) && arrays_differ++ < 10)
        std::printf("an array from a pool of %d numbers differs\n", pool_size);
    }
  }
  std::printf("%ld arrays of repeated numbers, %ld differ from nlohmann's\n", arrays,
              arrays_differ);

  // numbers(), an array written in one call, as begin_array(), value() of each and end_array()
  // write it: arrays of 0 to 5 numbers (zeros of both signs, whole numbers, NaN and infinities
  // among them) as an object's member and an array's item, at every depth from 0 to 20 (the
  // deeper ones past the short indents, where it falls back to those calls), against nlohmann.
  long nested = 0, nested_differ = 0;
  const double specials[] = {0.0, -0.0,    1.0, -3.0,     1e15,
                             0.1, -2.5e-7, NAN, INFINITY, 0.7648421872844884};
  for (int depth = 0; depth <= 20; ++depth) {
    for (size_t n = 0; n <= 5; ++n) {
      for (const bool member : {false, true}) {
        std::vector<double> v;
        for (size_t i = 0; i < n; ++i) {
          v.push_back(random() % 3 ? specials[random() % 10]
                                   : std::ldexp(static_cast<double>(random() >> 11), -60));
        }
        nlohmann::json leaf = nlohmann::json::array();
        for (const double x : v) leaf.push_back(x);
        std::string out;
        {
          dispcon::cli::JsonWriter w(out);
          for (int d = 0; d < depth; ++d) w.begin_array();
          w.value(1);  // an item before in the innermost array: the array's item has a comma
          if (member) {
            w.begin_object();
            w.literal_key("a");  // the report's own keys' way
            w.value(2);
            w.key("b");
          }
          w.numbers(v.data(), v.size());
          if (member) w.end_object();
          for (int d = 0; d < depth; ++d) w.end_array();
        }
        nlohmann::json doc = member ? nlohmann::json{{"a", 2}, {"b", leaf}} : leaf;
        for (int d = 0; d < depth; ++d) {
          doc = d == 0 ? nlohmann::json::array({1, doc}) : nlohmann::json::array({doc});
        }
        // At depth 0 the writer's document is the number 1 and the array after it: not one JSON
        // value, so it is compared with the two dumped one after the other.
        const std::string expected = depth == 0 ? "1" + doc.dump(2) : doc.dump(2);
        ++nested;
        if (out != expected && nested_differ++ < 10)
          std::printf("numbers() of %zu at depth %d differs:\n%s\n%s\n", n, depth, out.c_str(),
                      expected.c_str());
      }
    }
  }
  std::printf("%ld arrays written by numbers(), %ld differ from nlohmann's\n", nested,
              nested_differ);

  long strings = 0, strings_differ = 0;
  auto test_string = [&](const std::string& s) {
    std::string value, key;
    dispcon::cli::JsonWriter(value).value(s);
    {
      dispcon::cli::JsonWriter w(key);
      w.begin_object();
      w.key(s);
      w.value(1);
      w.end_object();
    }
    const nlohmann::json object = {{s, 1}};
    ++strings;
    if ((value != nlohmann::json(s).dump() || key != object.dump(2)) && strings_differ++ < 10)
      std::printf("string of %zu bytes: wrote %s and %s\n", s.size(), value.c_str(), key.c_str());
  };
  std::string special;  // every byte that must be escaped
  for (int c = 0; c < 0x20; ++c) special += static_cast<char>(c);
  special += "\"\\";
  // Plain ASCII, and two-byte UTF-8 characters (a special byte goes between two of them).
  const std::string fillers[] = {"abcdefghijklmnopqrstuvwxyz0123456789ABCD", "\xc3\xa9"};
  for (size_t length = 0; length <= 40; ++length) {
    for (const std::string& filler : fillers) {
      const size_t step = filler.size() == 2 ? 2 : 1;
      std::string plain;
      while (plain.size() < length) plain += filler;
      plain.resize(length - length % step);
      test_string(plain);
      for (size_t at = 0; at <= plain.size(); at += step) {
        for (const char c : special) {
          std::string s = plain;
          s.insert(at, 1, c);
          test_string(s);
        }
      }
    }
  }
  std::printf("%ld strings, %ld differ from nlohmann's\n", strings, strings_differ);
  return differ || arrays_differ || nested_differ || strings_differ ? 1 : 0;
}
