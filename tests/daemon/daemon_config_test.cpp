// flat2dd's configuration (daemon/config/daemon_config.hpp): the shipped file parses; bad
// files stop start-up naming file, line and field; defaults and relative paths are filled.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "daemon/config/daemon_config.hpp"

namespace flat2d::daemon {
namespace {

const std::filesystem::path kShipped =
    std::filesystem::path(FLAT2D_SOURCE_DIR) / "packaging/config/flat2dd/flat2dd.textproto";

class ConfigFile : public ::testing::Test {
 protected:
  std::filesystem::path Write(const std::string& text) {
    const std::filesystem::path path = dir_ / "flat2dd.textproto";
    std::ofstream(path) << text;
    return path;
  }
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("flat2d_config_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

constexpr const char* kSources = R"(
lidar { pcap { path: "drive/lidar.pcap" } }
can { candump { path: "drive/can.log" } }
)";
constexpr const char* kFiles = R"(
dbc: "drive/vehicle.dbc"
odometry_config: "odometry.textproto"
grid_config: "/usr/share/flat2d/grid.textproto"
localizer_config: "localizer.textproto"
map: "map.f2m"
)";
const std::string kMinimal = std::string(kSources) + kFiles;

TEST_F(ConfigFile, TheShippedConfigurationIsValid) {
  auto config = LoadDaemonConfig(kShipped);
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_TRUE(config->lidar().has_udp());
  EXPECT_EQ(config->lidar().udp().port(), 2368u);
  EXPECT_EQ(config->can().socketcan().interface(), "can0");
  EXPECT_EQ(config->api().unix_socket(), "/run/flat2d/api.sock");
  EXPECT_EQ(config->api().unix_mode(), 0660u);
  EXPECT_EQ(config->map(), "/var/lib/flat2d/map.f2m");
  EXPECT_EQ(config->dbc(), (kShipped.parent_path() / "vehicle.dbc").lexically_normal().string());
  EXPECT_FALSE(config->has_initial_pose());
}

TEST_F(ConfigFile, FillsDefaultsAndResolvesRelativePaths) {
  auto config = LoadDaemonConfig(Write(kMinimal));
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_EQ(config->lidar().pcap().path(), (dir_ / "drive/lidar.pcap").string());
  EXPECT_EQ(config->grid_config(), "/usr/share/flat2d/grid.textproto");
  EXPECT_DOUBLE_EQ(config->lidar().pcap().rate(), 1.0);
  EXPECT_EQ(config->lidar().ring_datagrams(), 4096u);
  EXPECT_EQ(config->api().unix_socket(), "/run/flat2d/api.sock");
  EXPECT_EQ(config->api().max_clients(), 64u);
  EXPECT_EQ(config->api().max_message_bytes(), 4096u);
  EXPECT_DOUBLE_EQ(config->persistence().warm_start_sigma_m(), 2.0);
  EXPECT_DOUBLE_EQ(config->watchdog_stall_s(), 2.0);
}

TEST_F(ConfigFile, AnUnknownFieldNamesFileAndLine) {
  const auto path = Write(kMinimal + "api { unix_sockett: \"/tmp/x\" }\n");
  auto config = LoadDaemonConfig(path);
  ASSERT_FALSE(config.ok());
  EXPECT_NE(config.error().message.find(path.string() + ":10:"), std::string::npos) << config.error().message;
  EXPECT_NE(config.error().message.find("unix_sockett"), std::string::npos) << config.error().message;
}

TEST_F(ConfigFile, InvalidValuesNameTheField) {
  const std::pair<std::string, std::string> cases[] = {
      {"api { tcp_address: \"localhost\" tcp_port: 80 }", "api.tcp_address"},
      {"api { tcp_address: \"127.0.0.1\" }", "api.tcp_port"},
      {"api { max_message_bytes: 10 }", "api.max_message_bytes"},
      {"api { unix_mode: 4095 }", "api.unix_mode"},
      {"api { max_subscribe_hz: -1 }", "api.max_subscribe_hz"},
      {"lidar { pcap { path: \"x.pcap\" rate: -2 } }", "lidar.pcap.rate"},
      {"lidar { udp { bind_address: \"300.1.1.1\" } }", "lidar.udp.bind_address"},
      {"lidar { pcap { path: \"x.pcap\" } ring_datagrams: 100000 }", "lidar.ring_datagrams"},
      {"can { socketcan { } }", "can.socketcan.interface"},
      {"initial_pose { x: 1 sigma_m: -1 }", "initial_pose"},
      {"persistence { period_s: -1 }", "persistence.period_s"},
      {"gpio { pose_valid { line { offset: 17 } } }", "gpio.pose_valid.line.chip"},
      {"gpio { pps { line { offset: 4 } } }", "gpio.pps.line.chip"},
      {"gpio { pps { line { chip: \"gpiochip0\" } window_pulses: 2 } }", "gpio.pps"},
      {"gpio { pps { line { chip: \"gpiochip0\" } lock_pulses: 40 } }", "gpio.pps"},
      {"gpio { pose_valid { line { chip: \"gpiochip0\" name: \"PPS\" } } "
       "pps { line { chip: \"gpiochip0\" name: \"PPS\" } } }", "gpio"},
  };
  for (const auto& [extra, field] : cases) {
    // A case that sets a source replaces the minimal one (a message field may appear once).
    std::string text = kFiles;
    if (extra.rfind("lidar", 0) == 0) text += "can { candump { path: \"drive/can.log\" } }\n";
    else if (extra.rfind("can", 0) == 0) text += "lidar { pcap { path: \"drive/lidar.pcap\" } }\n";
    else text += kSources;
    auto config = LoadDaemonConfig(Write(text + extra + "\n"));
    ASSERT_FALSE(config.ok()) << extra;
    EXPECT_NE(config.error().message.find(field + ":"), std::string::npos) << extra << " -> " << config.error().message;
  }
}

TEST_F(ConfigFile, GpioLinesTakeTheirDocumentedDefaults) {
  auto config = LoadDaemonConfig(Write(kMinimal + "gpio { pose_valid { line { chip: \"gpiochip0\" offset: 17 } } "
                                                  "pps { line { chip: \"gpiochip0\" name: \"GNSS_PPS\" } } }\n"));
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_EQ(config->gpio().pose_valid().min_on_ms(), 500u);
  EXPECT_EQ(config->gpio().pose_valid().min_off_ms(), 1000u);
  EXPECT_EQ(config->gpio().pps().window_pulses(), 32u);
  EXPECT_EQ(config->gpio().pps().lock_pulses(), 8u);
  EXPECT_FALSE(config->gpio().pps().falling_edge());
}

TEST_F(ConfigFile, MissingSourcesAndFilesAreNamed) {
  auto no_lidar = LoadDaemonConfig(Write("can { candump { path: \"c.log\" } }\n"));
  ASSERT_FALSE(no_lidar.ok());
  EXPECT_NE(no_lidar.error().message.find("lidar: set udp or pcap"), std::string::npos) << no_lidar.error().message;
  auto no_map = LoadDaemonConfig(Write("lidar { pcap { path: \"l.pcap\" } }\ncan { candump { path: \"c.log\" } }\n"
                                       "dbc: \"v.dbc\"\nodometry_config: \"o\"\ngrid_config: \"g\"\nlocalizer_config: \"l\"\n"));
  ASSERT_FALSE(no_map.ok());
  EXPECT_NE(no_map.error().message.find("map: required"), std::string::npos) << no_map.error().message;
}

TEST_F(ConfigFile, LoadingInputsNamesTheFileThatIsMissing) {
  auto inputs = LoadDaemonInputs(Write(kMinimal));
  ASSERT_FALSE(inputs.ok());
  EXPECT_NE(inputs.error().message.find("vehicle.dbc"), std::string::npos) << inputs.error().message;
}

}  // namespace
}  // namespace flat2d::daemon
