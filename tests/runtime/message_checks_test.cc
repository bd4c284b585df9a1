// Tests of the checks that run before LCM's generated decoders (runtime/message_checks.h) and of
// slammtt::Decode (runtime/lcm_io.h), for every message type with an array or a string.
#include "runtime/message_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/lcm_io.h"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "tests/runtime/allocation_tally.h"
#include "tests/runtime/message_samples.h"

namespace slammtt {
namespace {

using testing_samples::CountField;
using testing_samples::ReadInt32;
using testing_samples::Sample;
using testing_samples::SampledTypeNames;
using testing_samples::SampledTypes;
using testing_samples::WriteInt32;

int Size(const std::vector<uint8_t>& bytes) { return static_cast<int>(bytes.size()); }

template <class Msg>
bool Plausible(const std::vector<uint8_t>& bytes, int size) {
  return PlausibleEncoding(static_cast<const Msg*>(nullptr), bytes.data(), size);
}

template <class Msg>
class MessageChecksTest : public ::testing::Test {};

TYPED_TEST_SUITE(MessageChecksTest, SampledTypes, SampledTypeNames);

// The hand-computed layout of the checks and of the samples agrees with lcm-gen's encoder: a
// valid message passes the check, decodes, and encodes back to the same bytes.
TYPED_TEST(MessageChecksTest, ValidMessageRoundTripsByteForByte) {
  using Msg = TypeParam;
  const Msg sample = Sample<Msg>::Make();
  const std::vector<uint8_t> bytes = Encode(sample);
  EXPECT_TRUE(Plausible<Msg>(bytes, Size(bytes)));
  Msg decoded{};
  ASSERT_TRUE(Decode(bytes.data(), Size(bytes), &decoded));
  EXPECT_EQ(Encode(decoded), bytes);
  EXPECT_TRUE(Sample<Msg>::ArraysMatchCounts(decoded));
}

TYPED_TEST(MessageChecksTest, CountFieldsAreWhereTheLayoutSays) {
  using Msg = TypeParam;
  const Msg sample = Sample<Msg>::Make();
  const std::vector<uint8_t> bytes = Encode(sample);
  const std::vector<CountField> fields = Sample<Msg>::Counts(sample);
  ASSERT_FALSE(fields.empty());
  for (const CountField& field : fields) {
    ASSERT_LE(field.offset + 4, bytes.size()) << field.name;
    EXPECT_EQ(ReadInt32(bytes, field.offset), field.value) << field.name;
  }
}

// Every count and string length set to one more, one less, 0, -1, INT32_MIN and 0x7fffffff is
// rejected by the check itself, so the decoder never runs: Decode allocates nothing at all.
TYPED_TEST(MessageChecksTest, CorruptCountsAreRejectedWithoutAllocating) {
  using Msg = TypeParam;
  const Msg sample = Sample<Msg>::Make();
  const std::vector<uint8_t> valid = Encode(sample);
  for (const CountField& field : Sample<Msg>::Counts(sample)) {
    const int64_t v = field.value;
    for (int64_t corrupt : {v + 1, v - 1, int64_t{0}, int64_t{-1}, int64_t{INT32_MIN},
                            int64_t{INT32_MAX}}) {
      if (corrupt == v) continue;
      std::vector<uint8_t> bytes = valid;
      WriteInt32(&bytes, field.offset, static_cast<int32_t>(corrupt));
      EXPECT_FALSE(Plausible<Msg>(bytes, Size(bytes))) << field.name << " = " << corrupt;
      Msg decoded = sample;
      bool accepted = true;
      const AllocationTally tally =
          AllocationsDuring([&] { accepted = Decode(bytes.data(), Size(bytes), &decoded); });
      EXPECT_FALSE(accepted) << field.name << " = " << corrupt;
      EXPECT_EQ(tally.allocations, 0) << field.name << " = " << corrupt;
      EXPECT_EQ(Encode(decoded), valid) << "a rejected decode changed the message";
    }
  }
}

TYPED_TEST(MessageChecksTest, TruncationAtEveryByteAndTrailingBytesAreRejected) {
  using Msg = TypeParam;
  const Msg sample = Sample<Msg>::Make();
  std::vector<uint8_t> bytes = Encode(sample);
  const int size = Size(bytes);
  for (int cut = 0; cut < size; ++cut) {
    EXPECT_FALSE(Plausible<Msg>(bytes, cut)) << "cut at " << cut;
    Msg decoded{};
    bool accepted = true;
    const AllocationTally tally =
        AllocationsDuring([&] { accepted = Decode(bytes.data(), cut, &decoded); });
    EXPECT_FALSE(accepted) << "cut at " << cut;
    EXPECT_EQ(tally.allocations, 0) << "cut at " << cut;
  }
  bytes.push_back(0);
  Msg decoded{};
  EXPECT_FALSE(Plausible<Msg>(bytes, size + 1));
  EXPECT_FALSE(Decode(bytes.data(), size + 1, &decoded));
}

// A string whose last byte is not the NUL the LCM specification puts there is not a string.
TYPED_TEST(MessageChecksTest, StringWithoutItsNulIsRejected) {
  using Msg = TypeParam;
  const Msg sample = Sample<Msg>::Make();
  const std::vector<uint8_t> valid = Encode(sample);
  for (const CountField& field : Sample<Msg>::Counts(sample)) {
    if (field.name.rfind("num_", 0) == 0) continue;  // an array count, not a string
    std::vector<uint8_t> bytes = valid;
    bytes.at(field.offset + 4 + static_cast<size_t>(field.value) - 1) = 'x';
    EXPECT_FALSE(Plausible<Msg>(bytes, Size(bytes))) << field.name;
    Msg decoded{};
    EXPECT_FALSE(Decode(bytes.data(), Size(bytes), &decoded)) << field.name;
  }
}

// Random damage to a valid message (a few random bytes, a random count, a random length) never
// throws; what is rejected leaves the message as it was, and what is accepted has arrays as long
// as its counts. (Longer campaigns: tests/runtime/message_fuzz_test.cc, label fuzz.)
TYPED_TEST(MessageChecksTest, RandomBytesNeverThrow) {
  using Msg = TypeParam;
  const Msg sample = Sample<Msg>::Make();
  const std::vector<uint8_t> valid = Encode(sample);
  const std::vector<CountField> fields = Sample<Msg>::Counts(sample);
  std::mt19937_64 rng(20240611);
  int accepted = 0;
  for (int round = 0; round < 600; ++round) {
    std::vector<uint8_t> bytes = valid;
    switch (round % 3) {
      case 0:  // a few bytes anywhere after the fingerprint
        for (int k = 0; k < 1 + round % 4; ++k) {
          bytes[8 + rng() % (bytes.size() - 8)] = static_cast<uint8_t>(rng());
        }
        break;
      case 1:  // a random count or length
        WriteInt32(&bytes, fields[rng() % fields.size()].offset, static_cast<int32_t>(rng()));
        break;
      default:  // random bytes of a random size behind the right fingerprint
        bytes.resize(8 + rng() % (2 * valid.size()));
        for (size_t k = 8; k < bytes.size(); ++k) bytes[k] = static_cast<uint8_t>(rng());
        break;
    }
    Msg decoded = sample;
    bool ok = false;
    try {
      ok = Decode(bytes.data(), Size(bytes), &decoded);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "round " << round << " threw " << e.what();
    }
    if (ok) {
      ++accepted;
      EXPECT_TRUE(Sample<Msg>::ArraysMatchCounts(decoded)) << "round " << round;
    } else {
      EXPECT_EQ(Encode(decoded), valid) << "round " << round;
    }
  }
  // Flipped payload bytes of fixed fields keep a message whole: some rounds must be accepted,
  // or the test would not be exercising the accepting path at all.
  EXPECT_GT(accepted, 0);
}

bool IsNumber(const std::string& s) {
  return !s.empty() &&
         std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

// Which .lcm types have a string or a variable-length array, directly or through a nested type.
std::set<std::string> TypesWithVariableLength(const std::string& lcm_dir) {
  std::map<std::string, std::set<std::string>> nested;  // type -> struct types of its fields
  std::set<std::string> variable;
  const std::regex field(R"(^\s*([A-Za-z_][A-Za-z0-9_.]*)\s+[A-Za-z_]\w*\s*((\[[^\]]*\]\s*)*);)");
  const std::regex dimension(R"(\[\s*([^\]\s]+)\s*\])");
  const std::set<std::string> primitives = {"int8_t", "int16_t", "int32_t", "int64_t", "float",
                                            "double", "boolean", "byte", "string"};
  for (const auto& entry : std::filesystem::directory_iterator(lcm_dir)) {
    if (entry.path().extension() != ".lcm") continue;
    const std::string type = entry.path().stem().string();
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      line = line.substr(0, line.find("//"));
      std::smatch m;
      if (line.find("const ") != std::string::npos || !std::regex_search(line, m, field)) {
        continue;
      }
      const std::string field_type = m[1].str();
      if (field_type == "string") variable.insert(type);
      const std::string dims = m[2].str();
      for (auto it = std::sregex_iterator(dims.begin(), dims.end(), dimension);
           it != std::sregex_iterator(); ++it) {
        const std::string n = (*it)[1].str();
        if (!IsNumber(n)) variable.insert(type);
      }
      if (primitives.count(field_type) == 0) {
        nested[type].insert(field_type.substr(field_type.rfind('.') + 1));
      }
    }
  }
  for (bool grew = true; grew;) {
    grew = false;
    for (const auto& [type, members] : nested) {
      for (const std::string& member : members) {
        if (variable.count(member) != 0 && variable.insert(type).second) grew = true;
      }
    }
  }
  return variable;
}

// A new type with an array or a string needs a check in runtime/message_checks.h, an overload of
// PlausibleEncoding, a Sample in message_samples.h and a place in its SampledTypes.
TEST(MessageChecksCoverageTest, EveryTypeWithAnArrayOrAStringIsChecked) {
  const std::set<std::string> expected = {
      "laser_scan_t", "features_t",     "ground_truth_t", "tracks_t",          "map_t",
      "stage_timing_t", "lidar_status_t", "base_status_t", "estimator_status_t", "leg_labels_t",
      "laser_geometry_t", "smoother_input_t", "trajectory_t"};
  EXPECT_EQ(TypesWithVariableLength(std::string(SLAMMTT_SOURCE_DIR) + "/lcmtypes"), expected);
}

TEST(MessageChecksCoverageTest, FixedElementSizesAreLcmGensOwn) {
  EXPECT_EQ(slammtt_msgs::feature_t{}._getEncodedSizeNoHash(), encoded_bytes::kFeature);
  EXPECT_EQ(slammtt_msgs::line_feature_t{}._getEncodedSizeNoHash(), encoded_bytes::kLineFeature);
  EXPECT_EQ(slammtt_msgs::person_feature_t{}._getEncodedSizeNoHash(),
            encoded_bytes::kPersonFeature);
  EXPECT_EQ(slammtt_msgs::object_truth_t{}._getEncodedSizeNoHash(), encoded_bytes::kObjectTruth);
  EXPECT_EQ(slammtt_msgs::segment_truth_t{}._getEncodedSizeNoHash(),
            encoded_bytes::kSegmentTruth);
  EXPECT_EQ(slammtt_msgs::track_t{}._getEncodedSizeNoHash(), encoded_bytes::kTrack);
  EXPECT_EQ(slammtt_msgs::landmark_t{}._getEncodedSizeNoHash(), encoded_bytes::kLandmark);
  EXPECT_EQ(slammtt_msgs::line_landmark_t{}._getEncodedSizeNoHash(),
            encoded_bytes::kLineLandmark);
  slammtt_msgs::laser_scan_t scan = Sample<slammtt_msgs::laser_scan_t>::Make();
  const int with_beams = scan.getEncodedSize();
  scan.num_beams = 0;
  scan.angle_rad.clear();
  scan.range_m.clear();
  scan.intensity.clear();
  scan.valid.clear();
  EXPECT_EQ(with_beams - scan.getEncodedSize(), 5 * encoded_bytes::kBeam);
}

// Why the checks exist: LCM 1.3.1's generated decoder resizes to a negative count and throws.
// (Should an LCM upgrade fix this, the checks stay correct; this test then says so.)
TEST(DecodeTest, GeneratedDecoderOfLcm131ThrowsOnANegativeCount) {
  using Features = slammtt_msgs::features_t;
  std::vector<uint8_t> bytes = Encode(Sample<Features>::Make());
  WriteInt32(&bytes, Sample<Features>::Counts(Sample<Features>::Make())[0].offset, -1);
  Features raw{};
  EXPECT_THROW(raw.decode(bytes.data(), 0, Size(bytes)), std::length_error);
  Features checked{};
  EXPECT_FALSE(Decode(bytes.data(), Size(bytes), &checked));
}

// The generated decoder leaves an array alone when its count is 0; Decode starts afresh.
TEST(DecodeTest, ReusedMessageKeepsNoElementsOfThePreviousOne) {
  slammtt_msgs::laser_scan_t scan = Sample<slammtt_msgs::laser_scan_t>::Make();
  const std::vector<uint8_t> with_beams = Encode(scan);
  scan.num_beams = 0;
  scan.angle_rad.clear();
  scan.range_m.clear();
  scan.intensity.clear();
  scan.valid.clear();
  const std::vector<uint8_t> empty = Encode(scan);

  slammtt_msgs::laser_scan_t reused{};
  ASSERT_TRUE(Decode(with_beams.data(), Size(with_beams), &reused));
  ASSERT_EQ(reused.angle_rad.size(), 5u);
  ASSERT_TRUE(Decode(empty.data(), Size(empty), &reused));
  EXPECT_EQ(reused.num_beams, 0);
  EXPECT_TRUE(reused.angle_rad.empty());
  EXPECT_TRUE(reused.valid.empty());
}

TEST(DecodeTest, WrongTypeNullAndNegativeSizeAreRejected) {
  const std::vector<uint8_t> tracks = Encode(Sample<slammtt_msgs::tracks_t>::Make());
  slammtt_msgs::map_t map{};
  EXPECT_FALSE(Decode(tracks.data(), Size(tracks), &map));
  slammtt_msgs::tracks_t decoded{};
  EXPECT_FALSE(Decode(nullptr, 0, &decoded));
  EXPECT_FALSE(Decode(tracks.data(), -1, &decoded));
  EXPECT_FALSE(PlausibleTracks(nullptr, 16));
  EXPECT_FALSE(PlausibleTracks(tracks.data(), -1));

  // Fixed-size types go straight to the generated decoder, which bounds every read.
  slammtt_msgs::odometry_t odometry{};
  odometry.x_m = 1.25;
  const std::vector<uint8_t> odometry_bytes = Encode(odometry);
  slammtt_msgs::odometry_t decoded_odometry{};
  ASSERT_TRUE(Decode(odometry_bytes.data(), Size(odometry_bytes), &decoded_odometry));
  EXPECT_EQ(decoded_odometry.x_m, 1.25);
  for (int cut = 0; cut < Size(odometry_bytes); ++cut) {
    EXPECT_FALSE(Decode(odometry_bytes.data(), cut, &decoded_odometry)) << cut;
  }
  slammtt_msgs::pose_t pose{};
  EXPECT_FALSE(Decode(odometry_bytes.data(), Size(odometry_bytes), &pose));
  EXPECT_FALSE(Decode(nullptr, 0, &pose));
}

}  // namespace
}  // namespace slammtt
