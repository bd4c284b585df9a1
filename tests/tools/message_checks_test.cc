#include "tools/replay/message_checks.h"

#include <gtest/gtest.h>

#include <vector>

namespace slammtt {
namespace {

// Overwrites the big-endian int32 at `offset`.
void SetInt32(std::vector<uint8_t>* bytes, size_t offset, int32_t value) {
  for (int k = 0; k < 4; ++k) {
    (*bytes)[offset + k] = static_cast<uint8_t>(static_cast<uint32_t>(value) >> (24 - 8 * k));
  }
}

slammtt_msgs::tracks_t ThreeTracks() {
  slammtt_msgs::tracks_t msg{};
  msg.utime = 42;
  msg.tracks.resize(3);
  for (int k = 0; k < 3; ++k) msg.tracks[k].id = k;
  msg.num_tracks = 3;
  return msg;
}

TEST(MessageChecksTest, AcceptsWholeMessagesAndRejectsImpossibleLengths) {
  std::vector<uint8_t> bytes = Encode(ThreeTracks());
  const int size = static_cast<int>(bytes.size());
  EXPECT_TRUE(PlausibleTracks(bytes.data(), size));
  slammtt_msgs::tracks_t decoded{};
  ASSERT_TRUE(DecodeChecked(bytes.data(), size, &decoded));
  EXPECT_EQ(decoded.tracks[2].id, 2);

  SetInt32(&bytes, 16, 4);  // one track more than the bytes hold
  EXPECT_FALSE(PlausibleTracks(bytes.data(), size));
  EXPECT_FALSE(DecodeChecked(bytes.data(), size, &decoded));
  SetInt32(&bytes, 16, -1);  // LCM's decoder would throw std::length_error
  EXPECT_FALSE(DecodeChecked(bytes.data(), size, &decoded));
  SetInt32(&bytes, 16, 0x7fffffff);  // ... or allocate hundreds of gigabytes
  EXPECT_FALSE(DecodeChecked(bytes.data(), size, &decoded));
  SetInt32(&bytes, 16, 3);
  EXPECT_FALSE(DecodeChecked(bytes.data(), size - 1, &decoded));  // truncated
  EXPECT_FALSE(DecodeChecked(bytes.data(), 10, &decoded));
  EXPECT_FALSE(DecodeChecked(nullptr, 0, &decoded));
}

TEST(MessageChecksTest, GroundTruthAndMapLengths) {
  slammtt_msgs::ground_truth_t gt{};
  gt.objects.resize(2);
  gt.num_objects = 2;
  std::vector<uint8_t> bytes = Encode(gt);
  EXPECT_TRUE(PlausibleGroundTruth(bytes.data(), static_cast<int>(bytes.size())));
  SetInt32(&bytes, 56, 3);
  EXPECT_FALSE(PlausibleGroundTruth(bytes.data(), static_cast<int>(bytes.size())));

  slammtt_msgs::map_t map{};
  map.landmarks.resize(5);
  map.num_landmarks = 5;
  bytes = Encode(map);
  EXPECT_TRUE(PlausibleMap(bytes.data(), static_cast<int>(bytes.size())));
  SetInt32(&bytes, 16, 6);
  EXPECT_FALSE(PlausibleMap(bytes.data(), static_cast<int>(bytes.size())));
}

TEST(MessageChecksTest, StageTimingWalksItsStrings) {
  slammtt_msgs::stage_timing_t msg{};
  msg.stage = "estimator";
  msg.total_ns = 5;
  msg.substage = {"predict", "gating"};
  msg.substage_ns = {1, 2};
  msg.num_substages = 2;
  msg.counter_name = {"hypotheses"};
  msg.counter_value = {7};
  msg.num_counters = 1;
  std::vector<uint8_t> bytes = Encode(msg);
  const int size = static_cast<int>(bytes.size());
  slammtt_msgs::stage_timing_t decoded{};
  ASSERT_TRUE(DecodeChecked(bytes.data(), size, &decoded));
  EXPECT_EQ(decoded.substage[1], "gating");
  // num_substages sits after the fingerprint, utime, the stage string and total_ns.
  const size_t substages_at = 8 + 8 + 4 + msg.stage.size() + 1 + 8;
  SetInt32(&bytes, substages_at, 1000);
  EXPECT_FALSE(DecodeChecked(bytes.data(), size, &decoded));
  bytes = Encode(msg);
  SetInt32(&bytes, 16, 100000);  // the stage string's length
  EXPECT_FALSE(DecodeChecked(bytes.data(), size, &decoded));
  bytes = Encode(msg);
  const size_t counters_at = size - (4 + 11 + 8) - 4;  // before "hypotheses" and its value
  SetInt32(&bytes, counters_at, 2);
  EXPECT_FALSE(DecodeChecked(bytes.data(), size, &decoded));
}

}  // namespace
}  // namespace slammtt
