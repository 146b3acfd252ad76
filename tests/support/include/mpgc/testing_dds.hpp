// Test helpers over DDS readers (tests that link mpgc_runtime).
#pragma once

#include <chrono>
#include <thread>

#include "mpgc/dds/dds.hpp"

namespace mpgc::testing {

// Takes samples until one satisfies `pred` (copied to `out`) or the time runs out.
template <class T, class Pred>
bool wait_for(dds::Reader<T>& r, T& out, Pred pred, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    for (auto& s : r.take())
      if (pred(s.value)) {
        out = s.value;
        return true;
      }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

}  // namespace mpgc::testing
