// Simulated GPIO chips for the libgpiod backend's tests.
//
// Prefers gpio-sim (configfs, Linux 5.17+): create /sys/kernel/config/gpio-sim/<name> with
// one bank of lines (one of them named), set it live, and drive inputs by writing
// "pull-up"/"pull-down" to /sys/devices/platform/<dev_name>/<chip_name>/sim_gpioN/pull. When
// configfs lacks gpio-sim, `modprobe gpio-sim` is tried once. Falls back to a gpio-mockup chip
// that is already loaded (debugfs /sys/kernel/debug/gpio-mockup/<chip>/<offset>: write 0/1 to
// pull, read the value); its lines have no names. Without either, Create's error says why,
// for GTEST_SKIP.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "hal/common/error.hpp"

namespace flat2d::hal::gpio::testing {

class SimulatedChip {
 public:
  static Result<std::unique_ptr<SimulatedChip>> Create(unsigned num_lines, unsigned named_offset,
                                                       const std::string& line_name);
  ~SimulatedChip();
  SimulatedChip(const SimulatedChip&) = delete;
  SimulatedChip& operator=(const SimulatedChip&) = delete;

  const std::string& chip_name() const { return chip_name_; }  // "gpiochip3"
  const std::string& kind() const { return kind_; }            // "gpio-sim", "gpio-mockup"
  bool has_line_names() const { return kind_ == "gpio-sim"; }
  unsigned num_lines() const { return num_lines_; }

  // Pulls an input line up or down, which the chip reports as an edge.
  Status Pull(unsigned offset, bool high) const;
  // The line's value: what a consumer drives on an output, else the pull.
  Result<bool> Value(unsigned offset) const;

 private:
  SimulatedChip() = default;
  static Result<std::unique_ptr<SimulatedChip>> CreateSim(unsigned num_lines, unsigned named_offset,
                                                          const std::string& line_name);
  static Result<std::unique_ptr<SimulatedChip>> FindMockup(unsigned num_lines);
  std::filesystem::path LineFile(unsigned offset, const char* attribute) const;

  std::string kind_;
  std::string chip_name_;
  unsigned num_lines_ = 0;
  std::filesystem::path configfs_dir_;  // gpio-sim: torn down by the destructor
  std::filesystem::path named_line_dir_;
  std::filesystem::path lines_dir_;  // gpio-sim: the sysfs chip dir; mockup: the debugfs dir
};

}  // namespace flat2d::hal::gpio::testing
