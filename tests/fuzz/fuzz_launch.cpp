// Launch files (deploy/launch/*.yaml) through mpgc::launch::parse, and the command lines of an
// accepted file's components. Expected rejection: std::runtime_error naming file, line and field.
#include "fuzz.hpp"
#include "launch_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return mpgc::fuzz::expect<std::runtime_error>([&] {
    const auto lf = mpgc::launch::parse(mpgc::fuzz::text(data, size), "fuzz.yaml", "/nonexistent/base", "/nonexistent/bin");
    for (const auto& c : lf.components) {
      (void)c.argv();
      (void)c.command_line();
    }
  });
}
