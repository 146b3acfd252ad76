// Helpers for tests: unique DDS domains for concurrently running tests, paths to data and binaries.
#pragma once

#include <string>
#include <sys/types.h>
#include <vector>

namespace mpgc::testing {

// A DDS domain id (1..200) no other running test process holds: an flock on
// /tmp/mpgc-test-domain-<id>.lock, held until the process exits (notes pitfall 7).
int unique_domain();

// $MPGC_SHARED_DATA (../shared/data beside the repository) joined with `rel`.
std::string shared_data(const std::string& rel);
// $MPGC_BIN_DIR: the build's bin/ folder with every executable.
std::string bin_dir();
std::string source_dir();

// A shell command's exit code (-1: killed or not run) and its stdout and stderr together.
struct CommandResult {
  int code = -1;
  std::string output;
};
CommandResult shell(const std::string& command);

// A whole file ("" when it cannot be read).
std::string read_file(const std::string& path);

// Starts args[0] with args (posix_spawn, this environment); -1 when it cannot.
pid_t spawn(const std::vector<std::string>& args);
// The child's exit code; -2 when a signal ended it; -1 (after SIGKILL) when it outlived timeout_s.
int wait_child(pid_t pid, double timeout_s);

// A child process (a component under test): SIGTERM on destruction, SIGKILL after 5 s.
class Process {
 public:
  explicit Process(std::vector<std::string> args);  // args[0]: the executable
  ~Process();
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;
  bool running() const;

 private:
  pid_t pid_ = -1;
};

}  // namespace mpgc::testing
