// Test support: the real sample files, so the tests validate the samples themselves.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "dispcon/io/dcl_reader.hpp"

namespace dispcon::test_support {

inline Model sample(const std::string& name) {
  ParseResult r = load_dcl(std::string(DISPCON_SOURCE_DIR) + "/samples/" + name);
  EXPECT_TRUE(r.ok()) << r.messages();
  return r.ok() ? std::move(*r.model) : Model();
}

// A body's id by name; an unknown name fails the test (and gives the world) rather than crashing.
inline BodyId id(const Model& m, const std::string& name) {
  const auto b = m.find(name);
  EXPECT_TRUE(b) << "no body '" << name << "'";
  return b ? *b : Model::kWorld;
}

}  // namespace dispcon::test_support
