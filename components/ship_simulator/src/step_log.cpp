#include "mpgc/ship_simulator/step_log.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "mpgc/ship_simulator/world.hpp"

namespace mpgc::ship_simulator {

namespace {
// One record: the step index it applies to and the command, native doubles (the journal never
// leaves the machine that wrote it).
struct Record {
  uint64_t step;
  double rudder;
  double rpm;
};
static_assert(sizeof(Record) == 24, "journal record layout");
}  // namespace

StepLog::StepLog(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error("step journal " + path + ": " + std::strerror(errno));
  Record r{};
  for (;;) {
    const ssize_t n = ::read(fd_, &r, sizeof r);
    if (n == 0) break;
    if (n < 0) throw std::runtime_error("step journal " + path + ": " + std::strerror(errno));
    if (n != static_cast<ssize_t>(sizeof r)) break;  // torn by a kill: the step never happened
    if (r.step != commands_.size() || !std::isfinite(r.rudder) || !std::isfinite(r.rpm))
      throw std::runtime_error("step journal " + path + ": record " + std::to_string(commands_.size()) +
                               " is not this run's (step " + std::to_string(r.step) + ")");
    commands_.push_back({r.rudder, r.rpm});
  }
  steps_ = commands_.size();
  // Drop a torn tail so the next record lands on a record boundary.
  const off_t good = static_cast<off_t>(commands_.size() * sizeof(Record));
  if (::ftruncate(fd_, good) != 0 || ::lseek(fd_, good, SEEK_SET) != good)
    throw std::runtime_error("step journal " + path + ": " + std::strerror(errno));
}

StepLog::~StepLog() {
  if (fd_ >= 0) ::close(fd_);
}

void StepLog::append(const ShipCommand& cmd) {
  const Record r{steps_, cmd.rudder, cmd.rpm};
  if (::write(fd_, &r, sizeof r) != static_cast<ssize_t>(sizeof r))
    throw std::runtime_error("step journal " + path_ + ": " + std::strerror(errno));
  ++steps_;
}

ShipCommand replay(World& world, const std::vector<ShipCommand>& commands, const ShipCommand& fallback) {
  for (const auto& c : commands) {
    world.sense();
    world.step(c);
  }
  return commands.empty() ? fallback : commands.back();
}

}  // namespace mpgc::ship_simulator
