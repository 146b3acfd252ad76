// The simulator's journal: the command applied at every step, appended as the world advances, so
// that a simulator killed mid-run resumes where it was. The world is deterministic given its
// configuration and its commands (targets, sensor noise and all), so replaying the journal
// rebuilds the exact state, bit for bit, without a snapshot format for every model.
//
//   StepLog log(path);                           // opens or creates; reads what a previous run wrote
//   cmd = replay(world, log.take_commands(), cmd);  // the world where the killed simulator left it
//   log.append(cmd); world.step(cmd);            // every step from then on
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "mpgc/ship_simulator/ship_model.hpp"

namespace mpgc::ship_simulator {

class World;

class StepLog {
 public:
  // Opens `path` for appending (created when missing) and reads the commands already in it; a
  // record torn by a kill is dropped. Throws std::runtime_error naming the file on an I/O error or
  // a record that does not belong there (non-finite values, a step out of sequence).
  explicit StepLog(const std::string& path);
  ~StepLog();
  StepLog(const StepLog&) = delete;
  StepLog& operator=(const StepLog&) = delete;

  // The commands read at opening (once; the journal keeps no history in memory after that).
  std::vector<ShipCommand> take_commands() { return std::move(commands_); }
  uint64_t steps() const { return steps_; }
  // Appends the command of the step the world is about to take (one write, no fsync: a process
  // crash loses nothing, a power cut is not what this is for).
  void append(const ShipCommand& cmd);

 private:
  std::string path_;
  int fd_ = -1;
  std::vector<ShipCommand> commands_;
  uint64_t steps_ = 0;
};

// Steps a freshly built world through `commands`, sensing before every step as the simulator
// does, so that its sensors' random streams advance as they did. Returns the last command (the one
// the world holds until a new order), or `fallback` when there is none.
ShipCommand replay(World& world, const std::vector<ShipCommand>& commands, const ShipCommand& fallback);

}  // namespace mpgc::ship_simulator
