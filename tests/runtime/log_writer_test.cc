#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "runtime/lcm_io.h"
#include "slammtt_msgs/velocity_command_t.hpp"

namespace slammtt {
namespace {

std::string TempPath(const std::string& name) {
  return testing::TempDir() + "/" + name + "_" + std::to_string(getpid()) + ".lcm";
}

bool Exists(const std::string& path) { return access(path.c_str(), F_OK) == 0; }

// Files in the directory of `path` whose names start with the name of `path`.
std::vector<std::string> FilesStartingWith(const std::string& path) {
  const std::filesystem::path p(path);
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(p.parent_path())) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(p.filename().string(), 0) == 0) names.push_back(name);
  }
  return names;
}

TEST(LogWriterTest, CommittedLogReadsBackInOrder) {
  const std::string path = TempPath("committed");
  {
    LogWriter writer(path);
    slammtt_msgs::velocity_command_t cmd{};
    for (int i = 0; i < 3; ++i) {
      cmd.utime = 1000 * i;
      cmd.linear_mps = 0.1 * i;
      writer.WriteMessage(cmd.utime, "VELOCITY_COMMAND", cmd);
    }
    EXPECT_FALSE(Exists(path));  // not in place before Commit()
    EXPECT_EQ(FilesStartingWith(path).size(), 1u);  // the partial file
    writer.Commit();
  }
  ASSERT_TRUE(Exists(path));
  EXPECT_EQ(FilesStartingWith(path),
            std::vector<std::string>{std::filesystem::path(path).filename().string()});
  LogReader reader(path);
  for (int i = 0; i < 3; ++i) {
    auto event = reader.Next();
    ASSERT_TRUE(event.has_value());
    EXPECT_EQ(event->channel, "VELOCITY_COMMAND");
    EXPECT_EQ(event->timestamp_us, 1000 * i);
    slammtt_msgs::velocity_command_t cmd;
    ASSERT_TRUE(Decode(event->data.data(), static_cast<int>(event->data.size()), &cmd));
    EXPECT_DOUBLE_EQ(cmd.linear_mps, 0.1 * i);
  }
  EXPECT_FALSE(reader.Next().has_value());
  std::remove(path.c_str());
}

TEST(LogWriterTest, UncommittedLogLeavesNothingBehind) {
  const std::string path = TempPath("abandoned");
  {
    LogWriter writer(path);
    const char bytes[4] = {1, 2, 3, 4};
    writer.Write(1, "X", bytes, 4);
  }
  EXPECT_TRUE(FilesStartingWith(path).empty());
}

TEST(LogWriterTest, UnwritableDirectoryIsAnError) {
  EXPECT_THROW(LogWriter("/nonexistent-dir/x.lcm"), std::runtime_error);
  EXPECT_THROW(LogReader("/nonexistent-dir/x.lcm"), std::runtime_error);
}

TEST(DecodeTest, RejectsTruncatedBytes) {
  slammtt_msgs::velocity_command_t cmd{};
  cmd.utime = 5;
  std::vector<uint8_t> bytes = Encode(cmd);
  slammtt_msgs::velocity_command_t out;
  EXPECT_TRUE(Decode(bytes.data(), static_cast<int>(bytes.size()), &out));
  EXPECT_FALSE(Decode(bytes.data(), static_cast<int>(bytes.size()) - 1, &out));
  bytes[0] ^= 0xff;  // fingerprint no longer matches
  EXPECT_FALSE(Decode(bytes.data(), static_cast<int>(bytes.size()), &out));
}

}  // namespace
}  // namespace slammtt
