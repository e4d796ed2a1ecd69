#include "tests/hal/gpio/gpio_sim.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>

namespace flat2d::hal::gpio::testing {
namespace fs = std::filesystem;
namespace {

const fs::path kConfigfsRoot = "/sys/kernel/config/gpio-sim";
const fs::path kMockupRoot = "/sys/kernel/debug/gpio-mockup";

Status WriteFile(const fs::path& path, const std::string& text) {
  std::ofstream file(path);
  file << text;
  file.flush();
  if (!file) return MakeError("cannot write '" + text + "' to " + path.string());
  return {};
}

Result<std::string> ReadFile(const fs::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  if (!file) return MakeError("cannot read " + path.string());
  std::string value = text.str();
  while (!value.empty() && (value.back() == '\n' || value.back() == ' ')) value.pop_back();
  return value;
}

// Why gpio-sim is not usable, or empty when it is (possibly after loading it).
std::string GpioSimUnavailableReason() {
  std::error_code ec;
  if (fs::exists(kConfigfsRoot, ec)) return {};
  const int status = std::system("modprobe gpio-sim >/dev/null 2>&1");
  if (fs::exists(kConfigfsRoot, ec)) return {};
  const int exit_code = status >= 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (exit_code == 0) {
    return "modprobe gpio-sim succeeded but " + kConfigfsRoot.string() +
           " is missing (configfs not mounted at /sys/kernel/config?)";
  }
  return kConfigfsRoot.string() + " missing and modprobe gpio-sim failed (" +
         (exit_code == 127 ? std::string("modprobe not found, ") : std::string()) + "exit status " +
         std::to_string(exit_code) + ")";
}

}  // namespace

Result<std::unique_ptr<SimulatedChip>> SimulatedChip::Create(unsigned num_lines,
                                                             unsigned named_offset,
                                                             const std::string& line_name) {
  const std::string sim_reason = GpioSimUnavailableReason();
  if (sim_reason.empty()) return CreateSim(num_lines, named_offset, line_name);
  auto mockup = FindMockup(num_lines);
  if (mockup.ok()) return mockup;
  return MakeError("no gpio-sim: " + sim_reason + "; no gpio-mockup: " + mockup.error().message);
}

Result<std::unique_ptr<SimulatedChip>> SimulatedChip::CreateSim(unsigned num_lines,
                                                                unsigned named_offset,
                                                                const std::string& line_name) {
  std::unique_ptr<SimulatedChip> chip(new SimulatedChip());
  chip->kind_ = "gpio-sim";
  chip->num_lines_ = num_lines;
  const fs::path device = kConfigfsRoot / ("flat2d-test-" + std::to_string(getpid()));
  const fs::path bank = device / "gpio-bank0";
  const fs::path line = bank / ("line" + std::to_string(named_offset));
  std::error_code ec;
  if (!fs::create_directory(device, ec) || ec) {
    return MakeError("gpio-sim: cannot create " + device.string() + ": " + ec.message());
  }
  chip->configfs_dir_ = device;  // from here on the destructor tears down what exists
  if (!fs::create_directory(bank, ec) || ec) {
    return MakeError("gpio-sim: cannot create " + bank.string() + ": " + ec.message());
  }
  if (Status s = WriteFile(bank / "num_lines", std::to_string(num_lines)); !s.ok()) {
    return s.error();
  }
  if (!fs::create_directory(line, ec) || ec) {
    return MakeError("gpio-sim: cannot create " + line.string() + ": " + ec.message());
  }
  chip->named_line_dir_ = line;
  if (Status s = WriteFile(line / "name", line_name); !s.ok()) return s.error();
  if (Status s = WriteFile(device / "live", "1"); !s.ok()) return s.error();
  auto chip_name = ReadFile(bank / "chip_name");
  auto dev_name = ReadFile(device / "dev_name");
  if (!chip_name.ok()) return chip_name.error();
  if (!dev_name.ok()) return dev_name.error();
  chip->chip_name_ = *chip_name;
  chip->lines_dir_ = fs::path("/sys/devices/platform") / *dev_name / *chip_name;
  if (!fs::exists(chip->LineFile(0, "pull"), ec)) {
    return MakeError("gpio-sim: " + chip->LineFile(0, "pull").string() + " missing");
  }
  return chip;
}

Result<std::unique_ptr<SimulatedChip>> SimulatedChip::FindMockup(unsigned num_lines) {
  std::error_code ec;
  if (!fs::is_directory(kMockupRoot, ec)) {
    return MakeError(kMockupRoot.string() +
                     " missing (load gpio-mockup gpio_mockup_ranges=-1,8; mount debugfs)");
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(kMockupRoot, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("gpiochip", 0) != 0) continue;
    if (!fs::exists(entry.path() / std::to_string(num_lines - 1), ec)) continue;
    std::unique_ptr<SimulatedChip> chip(new SimulatedChip());
    chip->kind_ = "gpio-mockup";
    chip->chip_name_ = name;
    chip->num_lines_ = num_lines;
    chip->lines_dir_ = entry.path();
    // The module outlives every test run: start each from lines pulled down, as gpio-sim does.
    for (unsigned offset = 0; offset < num_lines; ++offset) {
      if (Status s = chip->Pull(offset, false); !s.ok()) return s.error();
    }
    return chip;
  }
  return MakeError(kMockupRoot.string() + " has no chip with " + std::to_string(num_lines) +
                   " lines");
}

SimulatedChip::~SimulatedChip() {
  if (configfs_dir_.empty()) return;
  std::error_code ec;
  (void)WriteFile(configfs_dir_ / "live", "0");
  if (!named_line_dir_.empty()) fs::remove(named_line_dir_, ec);
  fs::remove(configfs_dir_ / "gpio-bank0", ec);
  fs::remove(configfs_dir_, ec);
}

fs::path SimulatedChip::LineFile(unsigned offset, const char* attribute) const {
  if (kind_ == "gpio-mockup") return lines_dir_ / std::to_string(offset);
  return lines_dir_ / ("sim_gpio" + std::to_string(offset)) / attribute;
}

Status SimulatedChip::Pull(unsigned offset, bool high) const {
  if (kind_ == "gpio-mockup") return WriteFile(LineFile(offset, ""), high ? "1" : "0");
  return WriteFile(LineFile(offset, "pull"), high ? "pull-up" : "pull-down");
}

Result<bool> SimulatedChip::Value(unsigned offset) const {
  auto text = ReadFile(LineFile(offset, "value"));
  if (!text.ok()) return text.error();
  return *text == "1";
}

}  // namespace flat2d::hal::gpio::testing
