// Randomly damaged encodings of every message type with an array or a string go through
// slammtt::Decode: it never throws, a rejected message is left untouched, an accepted one has
// arrays as long as its counts, and the heap it uses stays within a small multiple of the
// message's own size whatever the bytes claim. Seeded: the same cases on every run.
// 4000 cases per type by default; SLAMMTT_LONG_TESTS=1 runs 400000 per type.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "runtime/lcm_io.h"
#include "tests/runtime/allocation_tally.h"
#include "tests/runtime/message_samples.h"

namespace slammtt {
namespace {

using testing_samples::CountField;
using testing_samples::Sample;
using testing_samples::SampledTypeNames;
using testing_samples::SampledTypes;
using testing_samples::WriteInt32;

int CasesPerType() {
  const char* long_tests = std::getenv("SLAMMTT_LONG_TESTS");
  return long_tests != nullptr && std::string(long_tests) == "1" ? 400000 : 4000;
}

// A count or length an attacker or a bit error would produce: near the true value, small,
// negative, or anything.
int32_t DamagedCount(int32_t value, std::mt19937_64* rng) {
  switch ((*rng)() % 4) {
    case 0:
      return value + static_cast<int32_t>((*rng)() % 9) - 4;
    case 1:
      return static_cast<int32_t>((*rng)() % 64);
    case 2:
      return -static_cast<int32_t>((*rng)() % 0x7fffffff) - 1;
    default:
      return static_cast<int32_t>((*rng)());
  }
}

std::vector<uint8_t> Damaged(const std::vector<uint8_t>& valid,
                             const std::vector<CountField>& fields, std::mt19937_64* rng) {
  std::vector<uint8_t> bytes = valid;
  auto& r = *rng;
  switch (r() % 5) {
    case 0:  // a few bytes anywhere, the fingerprint included now and then
      for (int k = 0, n = 1 + static_cast<int>(r() % 6); k < n; ++k) {
        bytes[r() % bytes.size()] = static_cast<uint8_t>(r());
      }
      break;
    case 1:  // one or two counts or lengths
      for (int k = 0, n = 1 + static_cast<int>(r() % 2); k < n; ++k) {
        const CountField& field = fields[r() % fields.size()];
        WriteInt32(&bytes, field.offset, DamagedCount(field.value, rng));
      }
      break;
    case 2:  // cut, and perhaps followed by garbage
      bytes.resize(r() % bytes.size());
      for (int k = 0, n = static_cast<int>(r() % 16); k < n; ++k) {
        bytes.push_back(static_cast<uint8_t>(r()));
      }
      break;
    case 3: {  // a stretch of the message repeated (a duplicated datagram fragment)
      const size_t from = r() % bytes.size();
      const size_t length = 1 + r() % (bytes.size() - from);
      const auto begin = bytes.begin() + static_cast<std::ptrdiff_t>(from);
      const std::vector<uint8_t> stretch(begin, begin + static_cast<std::ptrdiff_t>(length));
      bytes.insert(begin, stretch.begin(), stretch.end());
      break;
    }
    default:  // noise of a random size behind the right fingerprint
      bytes.resize(8 + r() % (2 * valid.size()));
      for (size_t k = 8; k < bytes.size(); ++k) bytes[k] = static_cast<uint8_t>(r());
      break;
  }
  return bytes;
}

template <class Msg>
class MessageFuzzTest : public ::testing::Test {};

TYPED_TEST_SUITE(MessageFuzzTest, SampledTypes, SampledTypeNames);

TYPED_TEST(MessageFuzzTest, DamagedMessagesAreRejectedOrWholeNeverThrown) {
  using Msg = TypeParam;
  const Msg sample = Sample<Msg>::Make();
  const std::vector<uint8_t> valid = Encode(sample);
  const std::vector<CountField> fields = Sample<Msg>::Counts(sample);
  std::mt19937_64 rng(0x51a7c0de);
  const int cases = CasesPerType();
  int accepted = 0;
  int failures = 0;
  for (int c = 0; c < cases && failures < 10; ++c) {
    const std::vector<uint8_t> bytes = Damaged(valid, fields, &rng);
    const int size = static_cast<int>(bytes.size());
    Msg decoded = sample;
    bool ok = false;
    AllocationTally tally;
    try {
      tally = AllocationsDuring([&] { ok = Decode(bytes.data(), size, &decoded); });
    } catch (const std::exception& e) {
      ADD_FAILURE() << "case " << c << " threw " << e.what();
      ++failures;
      continue;
    }
    // Strings of the decoded message take at most 32 bytes of std::string each plus their
    // characters, and take at least 5 encoded bytes: 8 times the message bounds every type.
    const int64_t heap_bound = 8 * static_cast<int64_t>(size) + 4096;
    if (tally.bytes > heap_bound) {
      ADD_FAILURE() << "case " << c << ": " << tally.bytes << " heap bytes for " << size;
      ++failures;
    }
    if (ok) {
      ++accepted;
      if (!Sample<Msg>::ArraysMatchCounts(decoded)) {
        ADD_FAILURE() << "case " << c << ": arrays differ from their counts";
        ++failures;
      }
    } else if (Encode(decoded) != valid) {
      ADD_FAILURE() << "case " << c << ": a rejected decode changed the message";
      ++failures;
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(accepted, 0);  // the accepting path was exercised too
  this->RecordProperty("accepted", accepted);
  this->RecordProperty("cases", cases);
}

}  // namespace
}  // namespace slammtt
