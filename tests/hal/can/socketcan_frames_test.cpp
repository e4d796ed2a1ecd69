// SocketCAN without a socket: filter construction, raw frame conversion, error classes.
#include "hal/can/socketcan_frames.hpp"

#include <gtest/gtest.h>
#include <linux/can/error.h>

#include <vector>

namespace flat2d::hal::can {
namespace {

// What the kernel's can_rcv_filter does with one filter (Documentation/networking/can.rst).
bool Matches(const can_filter& filter, canid_t received) {
  return (received & filter.can_mask) == (filter.can_id & filter.can_mask);
}

bool AnyMatches(const std::vector<can_filter>& filters, canid_t received) {
  for (const can_filter& filter : filters) {
    if (Matches(filter, received)) return true;
  }
  return false;
}

TEST(CanFilters, StandardAndExtendedIdsAreDistinctAndRemoteFramesExcluded) {
  const std::vector<CanIdSpec> ids = {{0x0AA, false}, {0x1D0, false}, {0x18FEF100, true}};
  const Result<std::vector<can_filter>> filters = BuildCanFilters(ids);
  ASSERT_TRUE(filters.ok()) << filters.error().message;
  ASSERT_EQ(filters->size(), 3u);
  EXPECT_EQ((*filters)[0].can_id, 0x0AAu);
  EXPECT_EQ((*filters)[0].can_mask, CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG);
  EXPECT_EQ((*filters)[2].can_id, 0x18FEF100u | CAN_EFF_FLAG);
  EXPECT_EQ((*filters)[2].can_mask, CAN_EFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG);

  EXPECT_TRUE(AnyMatches(*filters, 0x0AA));
  EXPECT_TRUE(AnyMatches(*filters, 0x1D0));
  EXPECT_TRUE(AnyMatches(*filters, 0x18FEF100 | CAN_EFF_FLAG));
  EXPECT_FALSE(AnyMatches(*filters, 0x0AB));
  EXPECT_FALSE(AnyMatches(*filters, 0x0AA | CAN_EFF_FLAG));      // extended 0xAA
  EXPECT_FALSE(AnyMatches(*filters, 0x0AA | CAN_RTR_FLAG));      // remote request
  EXPECT_FALSE(AnyMatches(*filters, 0x18FEF100));                // its low bits as standard
  EXPECT_FALSE(AnyMatches(*filters, 0x18FEF101 | CAN_EFF_FLAG));
  EXPECT_FALSE(AnyMatches(*filters, 0x4AA));                     // same low 8 bits
}

TEST(CanFilters, DuplicatesMergeAndNoIdsMeanNoFilters) {
  const std::vector<CanIdSpec> ids = {{0x25, false}, {0x24, false}, {0x25, false}, {0x25, true}};
  const Result<std::vector<can_filter>> filters = BuildCanFilters(ids);
  ASSERT_TRUE(filters.ok());
  ASSERT_EQ(filters->size(), 3u);
  EXPECT_EQ((*filters)[0].can_id, 0x24u);
  EXPECT_EQ((*filters)[1].can_id, 0x25u);
  EXPECT_EQ((*filters)[2].can_id, 0x25u | CAN_EFF_FLAG);
  const Result<std::vector<can_filter>> none = BuildCanFilters({});
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none->empty());
}

TEST(CanFilters, IdsBeyondTheirWidthAndTooManyIdsAreErrors) {
  const std::vector<CanIdSpec> standard = {{0x800, false}};
  const Result<std::vector<can_filter>> wide = BuildCanFilters(standard);
  ASSERT_FALSE(wide.ok());
  EXPECT_NE(wide.error().message.find("0x800 is above 0x7FF"), std::string::npos);
  const std::vector<CanIdSpec> extended = {{0x20000000, true}};
  ASSERT_FALSE(BuildCanFilters(extended).ok());
  std::vector<CanIdSpec> many;
  for (std::uint32_t id = 0; id < 600; ++id) many.push_back({id, false});
  const Result<std::vector<can_filter>> too_many = BuildCanFilters(many);
  ASSERT_FALSE(too_many.ok());
  EXPECT_NE(too_many.error().message.find("at most 512"), std::string::npos);
}

TEST(RawFrames, ClassicStandardExtendedAndRemote) {
  can_frame raw{};
  raw.can_id = 0x1D0;
  raw.len = 3;
  raw.data[0] = 0x11;
  raw.data[2] = 0x33;
  CanFrame frame;
  ASSERT_EQ(ConvertRawFrame(raw, 42, frame), RawFrameKind::kData);
  EXPECT_EQ(frame.time_ns, 42);
  EXPECT_EQ(frame.id, 0x1D0u);
  EXPECT_FALSE(frame.extended || frame.remote || frame.fd || frame.error);
  EXPECT_EQ(std::vector<std::uint8_t>(frame.payload().begin(), frame.payload().end()),
            (std::vector<std::uint8_t>{0x11, 0x00, 0x33}));

  raw.can_id = 0x18FEF100 | CAN_EFF_FLAG | CAN_RTR_FLAG;
  raw.len = 8;
  ASSERT_EQ(ConvertRawFrame(raw, 0, frame), RawFrameKind::kData);
  EXPECT_TRUE(frame.extended && frame.remote);
  EXPECT_EQ(frame.id, 0x18FEF100u);
  EXPECT_EQ(frame.length, 8);
  EXPECT_TRUE(frame.payload().empty());
  EXPECT_EQ(frame.data[0], 0);  // a request's data bytes are not copied

  raw.can_id = 0x123;
  raw.len = 9;  // impossible for classic CAN
  EXPECT_EQ(ConvertRawFrame(raw, 0, frame), RawFrameKind::kInvalid);
}

TEST(RawFrames, CanFdKeepsFlagsAndRejectsBadSizes) {
  canfd_frame raw{};
  raw.can_id = 0x123;
  raw.len = 12;
  raw.flags = CANFD_BRS | CANFD_FDF;
  raw.data[11] = 0xAB;
  CanFrame frame;
  ASSERT_EQ(ConvertRawFrame(raw, CANFD_MTU, 7, frame), RawFrameKind::kData);
  EXPECT_TRUE(frame.fd);
  EXPECT_FALSE(frame.remote);
  EXPECT_EQ(frame.fd_flags, CANFD_BRS | CANFD_FDF);
  EXPECT_EQ(frame.length, 12);
  EXPECT_EQ(frame.data[11], 0xAB);
  raw.len = 13;
  EXPECT_EQ(ConvertRawFrame(raw, CANFD_MTU, 7, frame), RawFrameKind::kInvalid);
  raw.len = 12;
  EXPECT_EQ(ConvertRawFrame(raw, CANFD_MTU - 1, 7, frame), RawFrameKind::kInvalid);
  EXPECT_EQ(ConvertRawFrame(raw, 0, 7, frame), RawFrameKind::kInvalid);
  // A classic frame read into the FD buffer (CAN_MTU bytes) is classic.
  raw.len = 2;
  ASSERT_EQ(ConvertRawFrame(raw, CAN_MTU, 7, frame), RawFrameKind::kData);
  EXPECT_FALSE(frame.fd);
  EXPECT_EQ(frame.fd_flags, 0);
}

TEST(RawFrames, ErrorFramesAreClassified) {
  can_frame raw{};
  raw.can_id = CAN_ERR_FLAG | CAN_ERR_CRTL | CAN_ERR_BUSOFF;
  raw.len = CAN_ERR_DLC;
  raw.data[1] = CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_RX_OVERFLOW;
  CanFrame frame;
  ASSERT_EQ(ConvertRawFrame(raw, 0, frame), RawFrameKind::kError);
  EXPECT_TRUE(frame.error);
  EXPECT_EQ(frame.id, CAN_ERR_CRTL | CAN_ERR_BUSOFF);
  const CanErrorFrameInfo info = ClassifyErrorFrame(frame);
  EXPECT_TRUE(info.controller_problem && info.bus_off && info.error_passive && info.rx_overflow);
  EXPECT_FALSE(info.error_warning || info.tx_overflow || info.no_ack || info.protocol_violation);

  CanErrorCounts counts;
  CountErrorFrame(info, counts);
  raw.can_id = CAN_ERR_FLAG | CAN_ERR_ACK | CAN_ERR_PROT;
  raw.data[1] = CAN_ERR_CRTL_TX_WARNING;  // ignored: the controller class is not set
  ASSERT_EQ(ConvertRawFrame(raw, 0, frame), RawFrameKind::kError);
  CountErrorFrame(ClassifyErrorFrame(frame), counts);
  EXPECT_EQ(counts.frames, 2u);
  EXPECT_EQ(counts.bus_off, 1u);
  EXPECT_EQ(counts.error_passive, 1u);
  EXPECT_EQ(counts.controller_overflow, 1u);
  EXPECT_EQ(counts.error_warning, 0u);
  EXPECT_EQ(counts.no_ack, 1u);
  EXPECT_EQ(counts.protocol_violation, 1u);
  EXPECT_EQ(counts.other, 0u);
}

}  // namespace
}  // namespace flat2d::hal::can
