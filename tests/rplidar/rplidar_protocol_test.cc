// Requests and single replies against byte vectors computed by hand from the protocol document
// (checksum = XOR of every byte before it; little-endian fields).
#include "drivers/rplidar/rplidar_protocol.h"

#include <gtest/gtest.h>

#include <vector>

namespace slammtt {
namespace rplidar {
namespace {

using Bytes = std::vector<uint8_t>;

TEST(RplidarRequestTest, CommandsWithoutPayloadAreTwoBytes) {
  EXPECT_EQ(StopRequest(), Bytes({0xA5, 0x25}));
  EXPECT_EQ(ResetRequest(), Bytes({0xA5, 0x40}));
  EXPECT_EQ(ScanRequest(), Bytes({0xA5, 0x20}));
  EXPECT_EQ(ForceScanRequest(), Bytes({0xA5, 0x21}));
  EXPECT_EQ(GetInfoRequest(), Bytes({0xA5, 0x50}));
  EXPECT_EQ(GetHealthRequest(), Bytes({0xA5, 0x52}));
  EXPECT_EQ(GetSampleRateRequest(), Bytes({0xA5, 0x59}));
}

TEST(RplidarRequestTest, PayloadRequestsCarrySizeAndXorChecksum) {
  // A5 ^ 82 ^ 05 ^ 00 x5 = 0x22
  EXPECT_EQ(ExpressScanRequest(), Bytes({0xA5, 0x82, 0x05, 0, 0, 0, 0, 0, 0x22}));
  // PWM 660 = 0x0294: A5 ^ F0 ^ 02 ^ 94 ^ 02 = 0xC1
  EXPECT_EQ(SetMotorPwmRequest(660), Bytes({0xA5, 0xF0, 0x02, 0x94, 0x02, 0xC1}));
  EXPECT_EQ(SetMotorPwmRequest(0), Bytes({0xA5, 0xF0, 0x02, 0x00, 0x00, 0x57}));
  // A5 ^ FF ^ 04 = 0x5E
  EXPECT_EQ(GetAccBoardFlagRequest(), Bytes({0xA5, 0xFF, 0x04, 0, 0, 0, 0, 0x5E}));
}

TEST(RplidarDescriptorTest, ParsesSingleAndMultipleReplies) {
  const Bytes health = {0xA5, 0x5A, 0x03, 0x00, 0x00, 0x00, 0x06};
  auto descriptor = ParseDescriptor(health.data());
  ASSERT_TRUE(descriptor);
  EXPECT_EQ(descriptor->length, 3u);
  EXPECT_EQ(descriptor->mode, SendMode::kSingle);
  EXPECT_EQ(descriptor->data_type, kAnswerDeviceHealth);

  const Bytes scan = {0xA5, 0x5A, 0x05, 0x00, 0x00, 0x40, 0x81};
  descriptor = ParseDescriptor(scan.data());
  ASSERT_TRUE(descriptor);
  EXPECT_EQ(descriptor->length, 5u);
  EXPECT_EQ(descriptor->mode, SendMode::kMultiple);
  EXPECT_EQ(descriptor->data_type, kAnswerMeasurement);

  const Bytes express = {0xA5, 0x5A, 0x54, 0x00, 0x00, 0x40, 0x82};
  descriptor = ParseDescriptor(express.data());
  ASSERT_TRUE(descriptor);
  EXPECT_EQ(descriptor->length, 84u);
  EXPECT_EQ(descriptor->data_type, kAnswerMeasurementCapsuled);
}

TEST(RplidarDescriptorTest, EncodesWhatItParses) {
  EXPECT_EQ(EncodeDescriptor(DescriptorFor(kAnswerMeasurement)),
            Bytes({0xA5, 0x5A, 0x05, 0x00, 0x00, 0x40, 0x81}));
  EXPECT_EQ(EncodeDescriptor(DescriptorFor(kAnswerMeasurementCapsuled)),
            Bytes({0xA5, 0x5A, 0x54, 0x00, 0x00, 0x40, 0x82}));
  EXPECT_EQ(EncodeDescriptor(DescriptorFor(kAnswerDeviceInfo)),
            Bytes({0xA5, 0x5A, 0x14, 0x00, 0x00, 0x00, 0x04}));
  EXPECT_EQ(EncodeDescriptor(DescriptorFor(kAnswerSampleRate)),
            Bytes({0xA5, 0x5A, 0x04, 0x00, 0x00, 0x00, 0x15}));
  EXPECT_EQ(EncodeDescriptor(DescriptorFor(kAnswerAccBoardFlag)),
            Bytes({0xA5, 0x5A, 0x04, 0x00, 0x00, 0x00, 0xFF}));
}

TEST(RplidarDescriptorTest, RejectsBadSyncAndReservedMode) {
  const Bytes bad_sync = {0xA5, 0x5B, 0x03, 0x00, 0x00, 0x00, 0x06};
  EXPECT_FALSE(ParseDescriptor(bad_sync.data()));
  const Bytes bad_mode = {0xA5, 0x5A, 0x03, 0x00, 0x00, 0x80, 0x06};
  EXPECT_FALSE(ParseDescriptor(bad_mode.data()));
}

TEST(RplidarReplyTest, HealthGoodAndErrorWithCode) {
  const Bytes good = {0x00, 0x00, 0x00};
  auto health = ParseDeviceHealth(good.data(), good.size());
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, HealthStatus::kGood);
  EXPECT_EQ(health->error_code, 0);
  const Bytes error = {0x02, 0x02, 0x01};  // error, code 0x0102
  health = ParseDeviceHealth(error.data(), error.size());
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, HealthStatus::kError);
  EXPECT_EQ(health->error_code, 0x0102);
  EXPECT_EQ(EncodeDeviceHealth(*health), error);
  const Bytes unknown = {0x03, 0x00, 0x00};
  EXPECT_FALSE(ParseDeviceHealth(unknown.data(), unknown.size()));
  EXPECT_FALSE(ParseDeviceHealth(error.data(), 2));
}

TEST(RplidarReplyTest, DeviceInfoFieldsAndSerialNumber) {
  const Bytes data = {0x28, 0x1D, 0x01, 0x07, 0x00, 0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77,
                      0x88, 0x99, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 0xFF};
  auto info = ParseDeviceInfo(data.data(), data.size());
  ASSERT_TRUE(info);
  EXPECT_EQ(info->model, 0x28);
  EXPECT_EQ(info->firmware_major, 1);
  EXPECT_EQ(info->firmware_minor, 29);
  EXPECT_EQ(info->hardware, 7);
  EXPECT_EQ(info->SerialNumberHex(), "00112233445566778899AABBCCDDEEFF");
  EXPECT_EQ(EncodeDeviceInfo(*info), data);
  EXPECT_FALSE(ParseDeviceInfo(data.data(), 19));
}

TEST(RplidarReplyTest, SampleRateAndAccessoryBoardFlag) {
  const Bytes rate = {0xF4, 0x01, 0xFA, 0x00};
  auto parsed = ParseSampleRate(rate.data(), rate.size());
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->standard_us, 500);
  EXPECT_EQ(parsed->express_us, 250);
  EXPECT_EQ(EncodeSampleRate(*parsed), rate);
  const Bytes flag = {0x01, 0x00, 0x00, 0x00};
  EXPECT_EQ(ParseAccBoardFlag(flag.data(), flag.size()), std::optional<uint32_t>(1));
  EXPECT_EQ(EncodeAccBoardFlag(1), flag);
}

TEST(RplidarRequestParserTest, SplitsRequestsSkipsNoiseAndChecksChecksums) {
  RequestParser parser;
  std::vector<Request> requests;
  Bytes stream = {0x00, 0x13};  // noise before the first sync
  for (const Bytes& request : {StopRequest(), GetHealthRequest(), SetMotorPwmRequest(660),
                               ExpressScanRequest()}) {
    stream.insert(stream.end(), request.begin(), request.end());
  }
  Bytes corrupt = SetMotorPwmRequest(500);
  corrupt.back() ^= 0x01;
  stream.insert(stream.end(), corrupt.begin(), corrupt.end());
  const Bytes last = GetInfoRequest();
  stream.insert(stream.end(), last.begin(), last.end());
  // One byte at a time: the parser must not depend on chunking.
  for (uint8_t byte : stream) parser.Feed(&byte, 1, &requests);
  ASSERT_EQ(requests.size(), 5u);
  EXPECT_EQ(requests[0].command, kStop);
  EXPECT_EQ(requests[1].command, kGetHealth);
  EXPECT_EQ(requests[2].command, kSetMotorPwm);
  EXPECT_EQ(requests[2].payload, Bytes({0x94, 0x02}));
  EXPECT_EQ(requests[3].command, kExpressScan);
  EXPECT_EQ(requests[3].payload, Bytes({0, 0, 0, 0, 0}));
  EXPECT_EQ(requests[4].command, kGetInfo);
  EXPECT_EQ(parser.skipped_bytes(), 2);
  EXPECT_EQ(parser.bad_checksums(), 1);
}

}  // namespace
}  // namespace rplidar
}  // namespace slammtt
