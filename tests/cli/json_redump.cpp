// The JSON document on standard input as nlohmann::json writes it (dump(2)): what the command
// line printed before it wrote its documents as streams. test_cli.JsonLayout checks that every
// document the command line prints comes back unchanged.
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

int main() {
  const std::string in((std::istreambuf_iterator<char>(std::cin)),
                       std::istreambuf_iterator<char>());
  std::cout << nlohmann::json::parse(in).dump(2) << "\n";
  return 0;
}
