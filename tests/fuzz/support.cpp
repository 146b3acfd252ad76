// The scratch directory of tests/fuzz/fuzz.hpp: one per process, removed at exit.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "fuzz.hpp"

namespace mpgc::fuzz {
namespace {

// Never destroyed: the atexit cleanup runs after static destructors would have (ASan found the
// use after free of a static string at exit, fuzz_dnv under libFuzzer).
std::string& scratch_dir() {
  static std::string& dir = *new std::string([] {
    const char* t = std::getenv("TMPDIR");
    std::string tmpl = std::string(t && *t ? t : "/tmp") + "/mpgc-fuzz-XXXXXX";
    if (::mkdtemp(tmpl.data()) == nullptr) throw std::logic_error("fuzz: cannot make a scratch directory in " + tmpl);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch_dir(), ec);
    });
    return tmpl;
  }());
  return dir;
}

}  // namespace

std::string scratch_file(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = scratch_dir() + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) throw std::logic_error("fuzz: cannot write " + path);
  if (size > 0 && std::fwrite(data, 1, size, f) != size) throw std::logic_error("fuzz: short write to " + path);
  std::fclose(f);
  return path;
}

}  // namespace mpgc::fuzz
