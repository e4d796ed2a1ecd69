#include "hal/velodyne/model_identifier.hpp"

#include <gtest/gtest.h>

#include "tests/testing/velodyne_packet_builder.hpp"

namespace flat2d::hal::velodyne {
namespace {

using flat2d::testing::DataPacketBuilder;

// Feeds `count` packets whose device timestamps advance by `step_us`.
ModelIdentifier Observe(std::uint8_t mode, std::uint8_t product, std::uint32_t step_us,
                        std::optional<Model> configured = std::nullopt, int count = 4) {
  ModelIdentifier identifier(configured);
  for (int i = 0; i < count; ++i) {
    DataPacketBuilder packet(mode, product);
    packet.Timestamp(3'599'999'000u + static_cast<std::uint32_t>(i) * step_us);  // crosses the hour
    if (3'599'999'000u + static_cast<std::uint64_t>(i) * step_us >= 3'600'000'000u) {
      packet.Timestamp(static_cast<std::uint32_t>(3'599'999'000u + static_cast<std::uint64_t>(i) * step_us -
                                                  3'600'000'000u));
    }
    identifier.Observe(packet.bytes());
  }
  return identifier;
}

TEST(ModelIdentifier, AgreeingProductIdAndTiming) {
  const auto id = Observe(0x37, 0x22, 1327).Decide();
  ASSERT_TRUE(id.ok()) << id.error().message;
  EXPECT_EQ(id->model, Model::kVlp16);
  EXPECT_EQ(id->decided_by, "product id");
  EXPECT_TRUE(id->disagreements.empty());
  ASSERT_TRUE(id->packet_period_us.has_value());
  EXPECT_EQ(*id->packet_period_us, 1327.0);
}

TEST(ModelIdentifier, TimingOverridesAWrongProductId) {
  // Early VLP-16 firmware reports the HDL-32E id; its packets come every 1327 us.
  const auto id = Observe(0x37, 0x21, 1327).Decide();
  ASSERT_TRUE(id.ok());
  EXPECT_EQ(id->model, Model::kVlp16);
  EXPECT_EQ(id->decided_by, "packet timing");
  ASSERT_EQ(id->disagreements.size(), 1u);
  EXPECT_NE(id->disagreements[0].find("0x21 names HDL-32E"), std::string::npos);
}

TEST(ModelIdentifier, DualReturnHalvesThePeriod) {
  EXPECT_EQ(Observe(0x39, 0x21, 276).Decide()->model, Model::kHdl32e);
  EXPECT_TRUE(Observe(0x39, 0x21, 276).Decide()->disagreements.empty());
  EXPECT_EQ(Observe(0x37, 0x28, 664).Decide()->model, Model::kVlp32c);
  // A VLP-16 in dual mode has the VLP-32C's single-return period: the id decides.
  EXPECT_EQ(Observe(0x39, 0x22, 664).Decide()->model, Model::kVlp16);
}

TEST(ModelIdentifier, PacketLossDoesNotHideThePeriod) {
  ModelIdentifier identifier;
  for (std::uint32_t t : {0u, 1327u * 3, 1327u * 4, 1327u * 9}) {
    identifier.Observe(DataPacketBuilder(0x37, 0x21).Timestamp(t).bytes());
  }
  EXPECT_EQ(identifier.Decide()->model, Model::kVlp16);
}

TEST(ModelIdentifier, ConfigurationWinsAndDisagreementsAreReported) {
  const auto id = Observe(0x37, 0x22, 1327, Model::kHdl32e).Decide();
  ASSERT_TRUE(id.ok());
  EXPECT_EQ(id->model, Model::kHdl32e);
  EXPECT_EQ(id->decided_by, "configuration");
  EXPECT_EQ(id->disagreements.size(), 2u);  // the id and the timing both say VLP-16
}

TEST(ModelIdentifier, UnsupportedModelIsNamed) {
  ModelIdentifier identifier;
  DataPacketBuilder vls128(0x37, 0xA1);
  vls128.BlockFlag(1, 0xFF, 0xDD);
  identifier.Observe(vls128.bytes());
  const auto id = identifier.Decide();
  ASSERT_FALSE(id.ok());
  EXPECT_NE(id.error().message.find("VLS-128"), std::string::npos) << id.error().message;
  EXPECT_NE(id.error().message.find("0xa1"), std::string::npos) << id.error().message;

  ModelIdentifier unknown;
  unknown.Observe(DataPacketBuilder(0x37, 0x5A).bytes());
  EXPECT_NE(unknown.Decide().error().message.find("unknown (0x5a)"), std::string::npos);
}

TEST(ModelIdentifier, OneCorruptedPacketDoesNotDecide) {
  ModelIdentifier identifier;
  for (std::uint32_t i = 0; i < 4; ++i) {
    DataPacketBuilder packet(0x37, i == 1 ? 0x99 : 0x22);
    if (i == 2) packet.BlockFlag(5, 0x12, 0x34);
    identifier.Observe(packet.Timestamp(i * 1327).bytes());
  }
  const auto id = identifier.Decide();
  ASSERT_TRUE(id.ok()) << id.error().message;
  EXPECT_EQ(id->model, Model::kVlp16);
  EXPECT_EQ(id->product_id, 0x22);
}

TEST(ModelIdentifier, NothingObservedIsAnError) {
  ModelIdentifier identifier;
  std::array<std::uint8_t, 100> short_payload{};
  identifier.Observe(short_payload);
  EXPECT_FALSE(identifier.Decide().ok());
}

}  // namespace
}  // namespace flat2d::hal::velodyne
