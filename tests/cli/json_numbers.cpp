// JsonWriter's doubles against nlohmann's dump, digit for digit: the whole numbers it writes
// itself (every integer in [-2e6, 2e6], powers of ten and their neighbours up to 1e15, millions
// of random ones), and random doubles of every magnitude, which go through nlohmann's own
// conversion. Exit 1 and the first differences when any differs.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

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
  std::printf("%ld doubles, %ld differ from nlohmann's\n", tested, differ);
  return differ ? 1 : 0;
}
