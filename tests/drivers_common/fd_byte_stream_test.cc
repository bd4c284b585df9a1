#include "drivers/common/fd_byte_stream.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <memory>
#include <numeric>
#include <vector>

#include "byte_stream_test_util.h"

namespace slammtt {
namespace {

struct Pair {
  std::unique_ptr<FdByteStream> a;
  std::unique_ptr<FdByteStream> b;
};

Pair MakePair() {
  int fds[2];
  EXPECT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, fds), 0);
  return {std::make_unique<FdByteStream>(fds[0], "a"), std::make_unique<FdByteStream>(fds[1], "b")};
}

TEST(FdByteStreamTest, CarriesEveryByteValueBothWays) {
  Pair pair = MakePair();
  std::vector<uint8_t> all(256);
  std::iota(all.begin(), all.end(), 0);
  pair.a->Write(all.data(), all.size());
  EXPECT_EQ(ReadExactly(*pair.b, 256), all);
  pair.b->Write(all.data(), all.size());
  EXPECT_EQ(ReadExactly(*pair.a, 256), all);
}

TEST(FdByteStreamTest, ReadTimesOutWithZero) {
  Pair pair = MakePair();
  uint8_t buffer[8];
  EXPECT_EQ(pair.a->Read(buffer, sizeof buffer, 10), 0u);
  EXPECT_EQ(pair.a->Read(buffer, sizeof buffer, 0), 0u);
}

TEST(FdByteStreamTest, ClosedPeerIsALinkErrorNamingTheEndpoint) {
  Pair pair = MakePair();
  pair.b.reset();
  uint8_t buffer[8];
  try {
    pair.a->Read(buffer, sizeof buffer, 100);
    FAIL() << "no LinkError";
  } catch (const LinkError& e) {
    EXPECT_NE(std::string(e.what()).find("a: "), std::string::npos) << e.what();
  }
  const uint8_t byte = 1;
  EXPECT_THROW(pair.a->Write(&byte, 1, 100), LinkError);
}

TEST(FdByteStreamTest, BytesSentBeforeTheCloseAreStillDelivered) {
  Pair pair = MakePair();
  const uint8_t bytes[3] = {1, 2, 3};
  pair.b->Write(bytes, 3);
  pair.b.reset();
  EXPECT_EQ(ReadExactly(*pair.a, 3), std::vector<uint8_t>({1, 2, 3}));
  uint8_t buffer[8];
  EXPECT_THROW(pair.a->Read(buffer, sizeof buffer, 100), LinkError);
}

TEST(FdByteStreamTest, FlushInputDropsWhatArrived) {
  Pair pair = MakePair();
  const uint8_t bytes[4] = {9, 9, 9, 9};
  pair.b->Write(bytes, 4);
  // A unix socket delivers into the peer's buffer before write() returns.
  pair.a->FlushInput();
  uint8_t buffer[8];
  EXPECT_EQ(pair.a->Read(buffer, sizeof buffer, 10), 0u);
  const uint8_t fresh = 7;
  pair.b->Write(&fresh, 1);
  EXPECT_EQ(ReadExactly(*pair.a, 1), std::vector<uint8_t>({7}));
}

TEST(FdByteStreamTest, PollDescriptorIsReadyExactlyWhenReadHasSomethingToSay) {
  Pair pair = MakePair();
  const int fd = pair.a->PollDescriptor();
  ASSERT_GE(fd, 0);
  EXPECT_FALSE(PollsReady(fd, 0));
  const uint8_t bytes[2] = {4, 2};
  pair.b->Write(bytes, 2);
  EXPECT_TRUE(PollsReady(fd, 1000));
  uint8_t buffer[8];
  EXPECT_EQ(pair.a->Read(buffer, sizeof buffer, 0), 2u);  // no wait: poll() said so
  EXPECT_FALSE(PollsReady(fd, 0));
  pair.b.reset();  // the peer goes away: ready again, and Read() fails at once
  EXPECT_TRUE(PollsReady(fd, 1000));
  EXPECT_THROW(pair.a->Read(buffer, sizeof buffer, 0), LinkError);
}

TEST(FdByteStreamTest, AByteStreamWithoutADescriptorSaysSo) {
  // The interface's default, for test doubles: owners then wait in Read() instead.
  class NoDescriptor : public ByteStream {
   public:
    void Write(const uint8_t*, size_t, int) override {}
    size_t Read(uint8_t*, size_t, int) override { return 0; }
    void FlushInput() override {}
    void SetDtr(bool) override {}
    std::string Describe() const override { return "none"; }
  };
  EXPECT_EQ(NoDescriptor().PollDescriptor(), -1);
}

TEST(FdByteStreamTest, WriteAvailableNeverBlocksAndWriteTimesOutWhenNobodyReads) {
  Pair pair = MakePair();
  std::vector<uint8_t> block(1 << 16, 0x55);
  size_t accepted_total = 0;
  size_t accepted = 0;
  int rounds = 0;
  do {
    accepted = pair.a->WriteAvailable(block.data(), block.size());
    accepted_total += accepted;
    ++rounds;
  } while (accepted == block.size() && rounds < 1000);
  EXPECT_LT(accepted, block.size()) << "the socket buffer never filled";
  EXPECT_GT(accepted_total, 0u);
  EXPECT_EQ(pair.a->WriteAvailable(block.data(), block.size()), 0u);
  try {
    pair.a->Write(block.data(), block.size(), 20);
    FAIL() << "no LinkError";
  } catch (const LinkError& e) {
    EXPECT_NE(std::string(e.what()).find("timed out"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace slammtt
