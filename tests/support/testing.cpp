#include "mpgc/testing.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

namespace mpgc::testing {

int unique_domain() {
  static int domain = [] {
    for (int id = 1 + getpid() % 200, n = 0; n < 200; ++n, id = id % 200 + 1) {
      const std::string path = "/tmp/mpgc-test-domain-" + std::to_string(id) + ".lock";
      const int fd = open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0666);
      if (fd < 0) continue;
      if (flock(fd, LOCK_EX | LOCK_NB) == 0) return id;  // fd stays open: lock held until exit
      close(fd);
    }
    throw std::runtime_error("no free DDS test domain in 1..200");
  }();
  return domain;
}

static std::string env_or(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? v : fallback;
}

std::string shared_data(const std::string& rel) { return env_or("MPGC_SHARED_DATA", "../shared/data") + "/" + rel; }
std::string bin_dir() { return env_or("MPGC_BIN_DIR", "."); }
std::string source_dir() { return env_or("MPGC_SOURCE_DIR", "."); }

}  // namespace mpgc::testing
