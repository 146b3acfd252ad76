// A component's parameters as its declare() makes them, with overrides applied, for the tests of
// the components' node logic (node.hpp).
//
//   const auto p = mpgc::testing::declared<sim::NodeParams>(sim::declare, {"time.step=0.2"});
#pragma once

#include <string>
#include <vector>

#include "mpgc/runtime/params.hpp"

namespace mpgc::testing {

// `declare(ps, p)` declares p's parameters into ps; each override is "name=value".
template <class P, class Declare>
P declared(Declare declare, const std::vector<std::string>& overrides = {}) {
  P p;
  rt::ParamSet ps;
  declare(ps, p);
  for (const auto& o : overrides) ps.set_override(o);
  ps.validate_and_apply();
  return p;
}

}  // namespace mpgc::testing
