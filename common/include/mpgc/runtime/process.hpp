// Child processes, started one way: the scenario runner's launcher, the network lab's hosts and
// helpers, `mpgc compare`'s runs and plain commands (ip, podman) all go through these. No DDS.
//
//   pid_t pid = mpgc::rt::spawn_logged({"mpgc_launch", "launch.yaml"}, "out/launch.log");
//   int rc = mpgc::rt::wait_exit(pid);                   // exit status, 128 + signal if killed
//   int rc2 = mpgc::rt::run_command({"ip", "netns", "list"}, &text);
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace mpgc::rt {

// Starts argv[0] (searched in PATH when it has no '/') with argv, its stdout and stderr to `log`
// (created or truncated; "" : /dev/null). `own_group`: the child leads a new process group, so a
// signal to -pid reaches whatever it starts. Returns the pid, or -1 when fork fails or argv is
// empty. A program that cannot be executed exits 127 with the reason in `log`.
pid_t spawn_logged(const std::vector<std::string>& argv, const std::string& log, bool own_group = true);

// Waits for the child `pid`: its exit status, or 128 + the signal that ended it (as a shell
// reports), -1 when there is no such child.
int wait_exit(pid_t pid);

// Runs argv to its end, its stdout and stderr together into *out (if given): the exit status as
// wait_exit, -1 when it cannot be started.
int run_command(const std::vector<std::string>& argv, std::string* out = nullptr);

}  // namespace mpgc::rt
