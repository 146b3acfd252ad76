#include "mpgc/runtime/process.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace mpgc::rt {

namespace {
// In the child after fork: only async-signal-safe calls (no stdio, no allocation).
[[noreturn]] void exec_or_exit(char* const* argv) {
  execvp(argv[0], argv);
  dprintf(STDERR_FILENO, "cannot execute '%s': %s\n", argv[0], std::strerror(errno));
  _exit(127);
}

std::vector<char*> c_argv(const std::vector<std::string>& argv) {
  std::vector<char*> a;
  for (const auto& s : argv) a.push_back(const_cast<char*>(s.c_str()));
  a.push_back(nullptr);
  return a;
}
}  // namespace

pid_t spawn_logged(const std::vector<std::string>& argv, const std::string& log, bool own_group) {
  if (argv.empty()) return -1;
  std::vector<char*> a = c_argv(argv);  // before fork: no allocation in the child
  const char* path = log.empty() ? "/dev/null" : log.c_str();
  const pid_t pid = fork();
  if (pid == 0) {
    if (own_group) setpgid(0, 0);
    const int fd = open(path, O_CREAT | O_WRONLY | O_TRUNC | O_CLOEXEC, 0644);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
    }
    exec_or_exit(a.data());
  }
  if (pid > 0 && own_group) setpgid(pid, pid);  // also set here: no race with an early kill(-pid)
  return pid;
}

int wait_exit(pid_t pid) {
  int status = 0;
  pid_t w;
  while ((w = waitpid(pid, &status, 0)) < 0 && errno == EINTR) {
  }
  if (w != pid) return -1;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

int run_command(const std::vector<std::string>& argv, std::string* out) {
  if (argv.empty()) return -1;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) return -1;
  std::vector<char*> a = c_argv(argv);
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    return -1;
  }
  if (pid == 0) {
    dup2(fds[1], STDOUT_FILENO);
    dup2(fds[1], STDERR_FILENO);
    exec_or_exit(a.data());
  }
  close(fds[1]);
  char buf[1024];
  ssize_t n;
  while ((n = read(fds[0], buf, sizeof buf)) > 0 || (n < 0 && errno == EINTR))
    if (n > 0 && out) out->append(buf, static_cast<size_t>(n));
  close(fds[0]);
  return wait_exit(pid);
}

}  // namespace mpgc::rt
