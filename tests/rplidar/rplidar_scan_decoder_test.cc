// Scan decoders against byte vectors computed by hand from the protocol document, and the
// resync behaviour on corrupt input.
#include "drivers/rplidar/rplidar_scan_decoder.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace slammtt {
namespace rplidar {
namespace {

using Bytes = std::vector<uint8_t>;

// A standard node from its fields, following the bit layout of the protocol document.
Bytes Node(uint16_t angle_q6, uint16_t distance_q2, uint8_t quality, bool start) {
  return {static_cast<uint8_t>((quality << 2) | (start ? 0x1 : 0x2)),
          static_cast<uint8_t>(((angle_q6 & 0x7F) << 1) | 0x1),
          static_cast<uint8_t>(angle_q6 >> 7), static_cast<uint8_t>(distance_q2 & 0xFF),
          static_cast<uint8_t>(distance_q2 >> 8)};
}

std::vector<ScanSample> FeedBytewise(StandardNodeDecoder& decoder, const Bytes& bytes) {
  std::vector<ScanSample> out;
  for (size_t i = 0; i < bytes.size(); ++i) decoder.Feed(&bytes[i], 1, 1000 + i, &out);
  return out;
}

TEST(StandardNodeTest, WorkedExampleOfTheProtocolNotes) {
  const Bytes node = {0xBD, 0x01, 0x2D, 0xA0, 0x0F};
  auto sample = ParseStandardNode(node.data());
  ASSERT_TRUE(sample);
  EXPECT_TRUE(sample->start_of_revolution);
  EXPECT_EQ(sample->quality, 47);
  EXPECT_EQ(sample->angle_q6, 5760);
  EXPECT_DOUBLE_EQ(sample->AngleDeg(), 90.0);
  EXPECT_DOUBLE_EQ(sample->DistanceMm(), 1000.0);
}

TEST(StandardNodeTest, SecondHandComputedNode) {
  // quality 10, S 0 -> 0x2A; angle 90.5 deg = q6 5792 = 45 * 128 + 32 -> 0x41, 0x2D;
  // 1500.25 mm = q2 6001 = 0x1771.
  const Bytes node = {0x2A, 0x41, 0x2D, 0x71, 0x17};
  auto sample = ParseStandardNode(node.data());
  ASSERT_TRUE(sample);
  EXPECT_FALSE(sample->start_of_revolution);
  EXPECT_EQ(sample->quality, 10);
  EXPECT_DOUBLE_EQ(sample->AngleDeg(), 90.5);
  EXPECT_DOUBLE_EQ(sample->DistanceMm(), 1500.25);
  EXPECT_EQ(Node(5792, 6001, 10, false), node);
}

TEST(StandardNodeTest, RejectsBrokenCheckBitsAndImpossibleAngles) {
  EXPECT_FALSE(ParseStandardNode(Bytes({0xBC, 0x01, 0x2D, 0xA0, 0x0F}).data()));  // S = !S = 0
  EXPECT_FALSE(ParseStandardNode(Bytes({0xBF, 0x01, 0x2D, 0xA0, 0x0F}).data()));  // S = !S = 1
  EXPECT_FALSE(ParseStandardNode(Bytes({0xBD, 0x00, 0x2D, 0xA0, 0x0F}).data()));  // C = 0
  EXPECT_FALSE(ParseStandardNode(Bytes({0xBD, 0x01, 0xB4, 0xA0, 0x0F}).data()));  // 360.0 deg
  EXPECT_TRUE(ParseStandardNode(Bytes({0xBD, 0xFF, 0xB3, 0xA0, 0x0F}).data()));   // 359.98 deg
}

// n nodes 1.5 degrees apart from `first_q6`, start flag where the angle wraps.
Bytes NodeStream(int n, uint16_t first_q6, std::vector<uint16_t>* angles) {
  Bytes stream;
  int previous = -1;
  for (int i = 0; i < n; ++i) {
    const uint16_t angle = static_cast<uint16_t>((first_q6 + i * 96) % kFullTurnQ6);
    const bool start = previous >= 0 && angle < previous;
    const Bytes node = Node(angle, static_cast<uint16_t>(4000 + 8 * i), 40, start);
    stream.insert(stream.end(), node.begin(), node.end());
    angles->push_back(angle);
    previous = angle;
  }
  return stream;
}

TEST(StandardNodeDecoderTest, CleanStreamInAnyChunkingLagsTwoNodes) {
  std::vector<uint16_t> angles;
  const Bytes stream = NodeStream(300, 22000, &angles);
  StandardNodeDecoder decoder;
  const std::vector<ScanSample> out = FeedBytewise(decoder, stream);
  ASSERT_EQ(out.size(), 298u);  // the last two nodes wait for their successors
  int starts = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].angle_q6, angles[i]);
    EXPECT_EQ(out[i].distance_q2, 4000 + 8 * i);
    EXPECT_EQ(out[i].source_offset, 5 * i);
    EXPECT_EQ(out[i].arrival_us, static_cast<int64_t>(1000 + 5 * i + 4));
    starts += out[i].start_of_revolution ? 1 : 0;
  }
  EXPECT_EQ(starts, 2);  // 343.75 deg + 299 * 1.5 deg crosses 0 twice
  EXPECT_EQ(decoder.counters().resyncs, 0);
  EXPECT_EQ(decoder.counters().skipped_bytes, 0);

  StandardNodeDecoder whole;
  std::vector<ScanSample> at_once;
  whole.Feed(stream.data(), stream.size(), 7, &at_once);
  ASSERT_EQ(at_once.size(), out.size());
  for (size_t i = 0; i < out.size(); ++i) EXPECT_EQ(at_once[i].angle_q6, out[i].angle_q6);
}

TEST(StandardNodeDecoderTest, GarbageIsSkippedWithOneResyncAndCostsThreeNodes) {
  std::vector<uint16_t> angles;
  Bytes stream = NodeStream(40, 0, &angles);
  const Bytes garbage = {0x00, 0x00, 0xFF, 0xFF, 0x00, 0x04, 0x08, 0xFC, 0x00, 0x00, 0x00};
  stream.insert(stream.begin() + 20 * 5, garbage.begin(), garbage.end());
  StandardNodeDecoder decoder;
  const std::vector<ScanSample> out = FeedBytewise(decoder, stream);
  // Nodes 0..17, then 21..37: 18 and 19 waited for successors and met garbage, 20 is the
  // seam after it, 38 and 39 wait.
  ASSERT_EQ(out.size(), 35u);
  for (size_t i = 0; i < out.size(); ++i) {
    const size_t node = i < 18 ? i : i + 3;
    EXPECT_EQ(out[i].angle_q6, angles[node]) << i;
  }
  EXPECT_EQ(decoder.counters().resyncs, 1);
  EXPECT_EQ(decoder.counters().skipped_bytes, static_cast<int64_t>(garbage.size()));
  EXPECT_EQ(decoder.counters().rejected_nodes, 3);
}

TEST(StandardNodeDecoderTest, DroppedByteNeverYieldsANodeThatWasNotSent) {
  std::vector<uint16_t> angles;
  const Bytes clean = NodeStream(60, 1000, &angles);
  for (size_t drop = 5 * 20; drop < 5 * 21; ++drop) {
    Bytes stream = clean;
    stream.erase(stream.begin() + static_cast<std::ptrdiff_t>(drop));
    StandardNodeDecoder decoder;
    const std::vector<ScanSample> out = FeedBytewise(decoder, stream);
    EXPECT_GE(out.size(), 50u) << "drop at " << drop;
    for (const ScanSample& sample : out) {
      const size_t index = (sample.angle_q6 + kFullTurnQ6 - 1000) % kFullTurnQ6 / 96;
      ASSERT_LT(index, angles.size());
      EXPECT_EQ(sample.angle_q6, angles[index]) << "drop at " << drop;
      EXPECT_EQ(sample.distance_q2, 4000 + 8 * index) << "drop at " << drop;
    }
    EXPECT_EQ(decoder.counters().resyncs, 1) << "drop at " << drop;
  }
}

TEST(StandardNodeDecoderTest, AngleJumpStartsANewRunThatMustBeConfirmed) {
  Bytes stream;
  std::vector<uint16_t> angles;
  for (int i = 0; i < 10; ++i) angles.push_back(static_cast<uint16_t>(64 * 10 + 96 * i));
  for (int i = 0; i < 10; ++i) angles.push_back(static_cast<uint16_t>(64 * 100 + 96 * i));
  for (uint16_t angle : angles) {
    const Bytes node = Node(angle, 4000, 30, false);
    stream.insert(stream.end(), node.begin(), node.end());
  }
  StandardNodeDecoder decoder;
  const std::vector<ScanSample> out = FeedBytewise(decoder, stream);
  // Nodes 8 and 9 (before the 75-degree jump) never got their successors, 10 is the seam of
  // the new run, 18 and 19 wait.
  ASSERT_EQ(out.size(), 15u);
  EXPECT_EQ(out[7].angle_q6, angles[7]);
  EXPECT_EQ(out[8].angle_q6, angles[11]);
  EXPECT_EQ(decoder.counters().rejected_nodes, 3);
}

// The capsules computed by hand in the test's comments (see rplidar.md, "Test vectors").
Bytes CapsuleA() {
  // start 10.0 deg = q6 640 = 0x0280; cabin 0: d1 1000 mm (q2 0x0FA0) with dtheta1 = 19
  // (0b01_0011: bits 5..4 = 1 in the distance field, 3 in the low nibble), d2 = 0, dtheta2 = 0;
  // cabins 1..14 zero; cabin 15: d1 2500 mm (0x2710) dtheta1 0, d2 12000 mm (0xBB80) with
  // dtheta2 = 63 (bits 5..4 = 3, low nibble 0xF in the high half of byte 4).
  // checksum = 80^02 ^ A1^0F^00^00^03 ^ 10^27^83^BB^F0 = 0xD0 -> A0 5D.
  Bytes capsule = {0xA0, 0x5D, 0x80, 0x02, 0xA1, 0x0F, 0x00, 0x00, 0x03};
  capsule.resize(4 + 15 * 5, 0x00);
  const Bytes last = {0x10, 0x27, 0x83, 0xBB, 0xF0};
  capsule.insert(capsule.end(), last.begin(), last.end());
  return capsule;
}

Bytes EmptyCapsule(uint16_t start_q6, bool start_flag) {
  const uint16_t word = static_cast<uint16_t>(start_q6 | (start_flag ? 0x8000 : 0));
  const uint8_t low = static_cast<uint8_t>(word & 0xFF);
  const uint8_t high = static_cast<uint8_t>(word >> 8);
  const uint8_t checksum = low ^ high;
  Bytes capsule = {static_cast<uint8_t>(0xA0 | (checksum & 0xF)),
                   static_cast<uint8_t>(0x50 | (checksum >> 4)), low, high};
  capsule.resize(84, 0x00);
  return capsule;
}

TEST(ExpressCapsuleDecoderTest, HandComputedCapsuleDecodesWhenTheNextArrives) {
  const Bytes a = CapsuleA();
  ASSERT_EQ(a.size(), 84u);
  // B: start 42.0 deg = q6 2688 = 0x0A80; checksum 80^0A = 8A -> AA 58.
  const Bytes b = EmptyCapsule(2688, false);
  EXPECT_EQ(b[0], 0xAA);
  EXPECT_EQ(b[1], 0x58);
  ExpressCapsuleDecoder decoder;
  std::vector<ScanSample> out;
  decoder.Feed(a.data(), a.size(), 111, &out);
  EXPECT_TRUE(out.empty()) << "a capsule is decoded only when the next has arrived";
  decoder.Feed(b.data(), b.size(), 222, &out);
  ASSERT_EQ(out.size(), 32u);
  // 32 degrees over 32 samples: base angle 10 + k degrees.
  EXPECT_EQ(out[0].angle_q6, 488);  // 10 - 19/8 = 7.625 deg
  EXPECT_EQ(out[0].distance_q2, 4000);
  EXPECT_EQ(out[0].quality, 47);
  EXPECT_EQ(out[1].angle_q6, 11 * 64);
  EXPECT_EQ(out[1].distance_q2, 0);
  EXPECT_EQ(out[1].quality, 0);
  EXPECT_EQ(out[17].angle_q6, 27 * 64);
  EXPECT_EQ(out[30].angle_q6, 40 * 64);
  EXPECT_EQ(out[30].distance_q2, 10000);
  EXPECT_EQ(out[31].angle_q6, 2120);  // 41 - 63/8 = 33.125 deg
  EXPECT_EQ(out[31].distance_q2, 48000);
  for (const ScanSample& sample : out) {
    EXPECT_EQ(sample.source_offset, 0u);
    EXPECT_EQ(sample.arrival_us, 111);
    EXPECT_FALSE(sample.start_of_revolution);
  }
  EXPECT_EQ(decoder.counters().checksum_errors, 0);
  EXPECT_EQ(decoder.counters().resyncs, 0);
}

TEST(ExpressCapsuleDecoderTest, RevolutionStartsWhereTheInterpolatedAngleWraps) {
  // 350 deg (q6 22400 = 0x5780, checksum D7 -> A7 5D), then 14 deg (q6 896, checksum 83).
  const Bytes c = EmptyCapsule(22400, false);
  EXPECT_EQ(c[0], 0xA7);
  EXPECT_EQ(c[1], 0x5D);
  const Bytes d = EmptyCapsule(896, false);
  ExpressCapsuleDecoder decoder;
  std::vector<ScanSample> out;
  decoder.Feed(c.data(), c.size(), 0, &out);
  decoder.Feed(d.data(), d.size(), 0, &out);
  ASSERT_EQ(out.size(), 32u);
  // 24 degrees / 32 = 0.75 deg per sample: sample 14 is at 360.5 -> 0.5 deg.
  for (size_t k = 0; k < out.size(); ++k) {
    EXPECT_EQ(out[k].start_of_revolution, k == 14) << k;
  }
  EXPECT_EQ(out[13].angle_q6, 22400 + 13 * 48);  // 359.75 deg
  EXPECT_EQ(out[14].angle_q6, 32);               // 0.5 deg
}

TEST(ExpressCapsuleDecoderTest, BadChecksumDropsTheCapsuleAndTheOneWaitingForIt) {
  Bytes stream = CapsuleA();
  Bytes bad = EmptyCapsule(2688, false);
  bad[50] = 0x11;  // one corrupt cabin byte
  stream.insert(stream.end(), bad.begin(), bad.end());
  for (uint16_t start : {4000, 6000, 8000}) {
    const Bytes good = EmptyCapsule(start, false);
    stream.insert(stream.end(), good.begin(), good.end());
  }
  ExpressCapsuleDecoder decoder;
  std::vector<ScanSample> out;
  for (uint8_t byte : stream) decoder.Feed(&byte, 1, 0, &out);
  // A has no valid successor; the bad capsule is skipped; 4000 and 6000 decode; 8000 waits.
  ASSERT_EQ(out.size(), 64u);
  EXPECT_EQ(out.front().angle_q6, 4000);
  EXPECT_EQ(out.front().source_offset, 168u);
  EXPECT_EQ(out[32].angle_q6, 6000);
  EXPECT_EQ(decoder.counters().checksum_errors, 1);
  EXPECT_EQ(decoder.counters().resyncs, 1);
  EXPECT_EQ(decoder.counters().skipped_bytes, 84);
  EXPECT_EQ(decoder.counters().dropped_capsules, 1);
}

// checksum_errors counts capsules that failed their checksum, not the false sync matches the
// decoder tries while it looks for the next capsule (a random window passes the two sync
// nibbles 1 time in 256). Before: 100 corrupt capsules among random cabins counted about 130.
TEST(ExpressCapsuleDecoderTest, ChecksumErrorsCountCorruptCapsulesOnly) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> byte(0, 255);
  Bytes stream;
  int corrupted = 0;
  for (int k = 0; k < 400; ++k) {
    Bytes capsule = EmptyCapsule(static_cast<uint16_t>((k * 704) % kFullTurnQ6), false);
    for (size_t i = 4; i < capsule.size(); ++i) capsule[i] = static_cast<uint8_t>(byte(random));
    uint8_t checksum = 0;
    for (size_t i = 2; i < capsule.size(); ++i) checksum ^= capsule[i];
    capsule[0] = static_cast<uint8_t>(0xA0 | (checksum & 0xF));
    capsule[1] = static_cast<uint8_t>(0x50 | (checksum >> 4));
    if (k % 4 == 1) {
      capsule[40] ^= 0x5A;  // as the emulator's bad-checksum fault
      ++corrupted;
    }
    stream.insert(stream.end(), capsule.begin(), capsule.end());
  }
  ExpressCapsuleDecoder decoder;
  std::vector<ScanSample> out;
  decoder.Feed(stream.data(), stream.size(), 0, &out);
  EXPECT_EQ(corrupted, 100);
  EXPECT_EQ(decoder.counters().checksum_errors, 100);
}

TEST(ExpressCapsuleDecoderTest, HalfCapsuleIsSkipped) {
  Bytes stream = CapsuleA();
  const Bytes half = EmptyCapsule(2688, false);
  stream.insert(stream.end(), half.begin(), half.begin() + 40);
  for (uint16_t start : {4000, 6000}) {
    const Bytes good = EmptyCapsule(start, false);
    stream.insert(stream.end(), good.begin(), good.end());
  }
  ExpressCapsuleDecoder decoder;
  std::vector<ScanSample> out;
  decoder.Feed(stream.data(), stream.size(), 0, &out);
  ASSERT_EQ(out.size(), 32u);
  EXPECT_EQ(out.front().angle_q6, 4000);
  EXPECT_EQ(decoder.counters().resyncs, 1);
  EXPECT_EQ(decoder.counters().skipped_bytes, 40);
}

TEST(ExpressCapsuleDecoderTest, StartFlagMidStreamResetsTheDecoder) {
  Bytes stream = CapsuleA();
  for (const Bytes& capsule : {EmptyCapsule(2688, true), EmptyCapsule(4000, false)}) {
    stream.insert(stream.end(), capsule.begin(), capsule.end());
  }
  ExpressCapsuleDecoder decoder;
  std::vector<ScanSample> out;
  decoder.Feed(stream.data(), stream.size(), 0, &out);
  ASSERT_EQ(out.size(), 32u);  // A is dropped; the restarted capsule decodes with its successor
  EXPECT_EQ(out.front().angle_q6, 2688);
  EXPECT_EQ(decoder.counters().dropped_capsules, 1);
}

TEST(ExpressCapsuleDecoderTest, CapsuleThatVanishedWholeIsNotBridged) {
  Bytes stream;
  for (uint16_t start : {1000, 3000, 7000, 9000, 11000}) {  // 5000 never arrived
    const Bytes capsule = EmptyCapsule(start, false);
    stream.insert(stream.end(), capsule.begin(), capsule.end());
  }
  ExpressCapsuleDecoder decoder;
  std::vector<ScanSample> out;
  decoder.Feed(stream.data(), stream.size(), 0, &out);
  // 1000 decodes with 3000; 3000 -> 7000 spans twice as much: 3000 is dropped, not stretched;
  // 7000 starts over and decodes with 9000, 9000 with 11000; 11000 waits.
  ASSERT_EQ(out.size(), 96u);
  EXPECT_EQ(out[0].angle_q6, 1000);
  EXPECT_EQ(out[31].angle_q6, 1000 + 31 * 2000 / 32);
  EXPECT_EQ(out[32].angle_q6, 7000);
  EXPECT_EQ(out[64].angle_q6, 9000);
  EXPECT_EQ(decoder.counters().dropped_capsules, 1);
  EXPECT_EQ(decoder.counters().resyncs, 1);
  EXPECT_EQ(decoder.counters().checksum_errors, 0);
}

ScanSample Sample(uint16_t angle_q6, bool start) {
  ScanSample sample;
  sample.angle_q6 = angle_q6;
  sample.start_of_revolution = start;
  return sample;
}

TEST(RevolutionAssemblerTest, CutsAtStartsAndDropsTheFirstPartialRevolution) {
  RevolutionAssembler assembler;
  std::vector<std::vector<ScanSample>> revolutions;
  const std::vector<ScanSample> samples = {Sample(300, false), Sample(400, false),
                                           Sample(10, true),   Sample(20, false),
                                           Sample(30, false),  Sample(5, true),
                                           Sample(15, false)};
  for (const ScanSample& sample : samples) {
    if (auto done = assembler.Add(sample)) revolutions.push_back(*done);
  }
  ASSERT_EQ(revolutions.size(), 1u);
  ASSERT_EQ(revolutions[0].size(), 3u);
  EXPECT_EQ(revolutions[0][0].angle_q6, 10);
  EXPECT_EQ(revolutions[0][2].angle_q6, 30);
  EXPECT_EQ(assembler.dropped_samples(), 2);
  assembler.Reset();  // link lost: the partial revolution (5, 15) goes
  EXPECT_EQ(assembler.dropped_samples(), 4);
  EXPECT_FALSE(assembler.Add(Sample(1, false)));
  EXPECT_EQ(assembler.dropped_samples(), 5);
}

// Issue 15 item 4: a fault that corrupts the node carrying the start-of-revolution bit. Before,
// the revolution ran on to the next S: one 720-degree scan (the emulator's runs gave 2 of 921).
// Now a revolution also ends where the angle wraps past 360 degrees.
TEST(RevolutionAssemblerTest, AStandardRevolutionWhoseStartBitWasLostEndsWhereTheAngleWraps) {
  std::vector<uint16_t> angles;
  Bytes stream = NodeStream(4 * 240 + 10, 0, &angles);  // 1.5 degrees a node: 240 a turn
  int starts = 0;
  for (size_t i = 1; i < angles.size(); ++i) {
    if (angles[i] >= angles[i - 1]) continue;
    if (++starts == 2) stream[5 * i] |= 0x3;  // S and !S both set: the node fails its check
  }
  StandardNodeDecoder decoder;
  RevolutionAssembler assembler;
  std::vector<ScanSample> samples;
  decoder.Feed(stream.data(), stream.size(), 0, &samples);
  std::vector<std::vector<ScanSample>> revolutions;
  for (const ScanSample& sample : samples) {
    if (auto done = assembler.Add(sample)) revolutions.push_back(*done);
  }
  ASSERT_EQ(revolutions.size(), 3u);
  for (const auto& revolution : revolutions) {
    EXPECT_LE(revolution.size(), 240u);
    EXPECT_GE(revolution.size(), 236u);  // the glitch costs a few nodes around it
    for (size_t k = 1; k < revolution.size(); ++k) {
      EXPECT_GT(revolution[k].angle_q6, revolution[k - 1].angle_q6) << "a second turn";
    }
  }
  EXPECT_EQ(assembler.starts_without_mark(), 1);
}

TEST(RevolutionAssemblerTest, AStartMarkJustAfterAWrapConfirmsTheStartItMade) {
  RevolutionAssembler assembler;
  std::vector<std::vector<ScanSample>> revolutions;
  auto add = [&](uint16_t angle, bool start) {
    if (auto done = assembler.Add(Sample(angle, start))) revolutions.push_back(*done);
  };
  add(100, true);
  for (uint16_t a = 1000; a < kFullTurnQ6; a += 1000) add(a, false);
  add(50, false);   // wrapped, no mark: a new revolution
  add(150, true);   // the mark one node late: the same start
  for (uint16_t a = 1000; a < kFullTurnQ6; a += 1000) add(a, false);
  add(60, true);
  ASSERT_EQ(revolutions.size(), 2u);
  EXPECT_EQ(revolutions[0].front().angle_q6, 100);
  EXPECT_EQ(revolutions[1].front().angle_q6, 50);
  EXPECT_EQ(revolutions[1][1].angle_q6, 150);
}

TEST(RevolutionAssemblerTest, RevolutionWithoutEndIsDroppedAndCounted) {
  RevolutionAssembler assembler(4);
  EXPECT_FALSE(assembler.Add(Sample(1, true)));
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(assembler.Add(Sample(2, false)));
  EXPECT_EQ(assembler.overlong(), 1);
  EXPECT_FALSE(assembler.Add(Sample(3, true)));  // nothing to finish: the long one was dropped
  EXPECT_FALSE(assembler.Add(Sample(4, false)));
  auto done = assembler.Add(Sample(5, true));
  ASSERT_TRUE(done);
  EXPECT_EQ(done->size(), 2u);
}

}  // namespace
}  // namespace rplidar
}  // namespace slammtt
