#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "runtime/lcm_io.h"
#include "runtime/log_reader.h"
#include "slammtt_msgs/velocity_command_t.hpp"

namespace slammtt {
namespace {

std::string TempPath(const std::string& name) {
  return testing::TempDir() + "/" + name + "_" + std::to_string(getpid()) + ".lcm";
}

bool Exists(const std::string& path) { return access(path.c_str(), F_OK) == 0; }

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

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
    // An unnamed file (O_TMPFILE), or one exclusively created partial file.
    EXPECT_EQ(FilesStartingWith(path).size(), writer.partial_path().empty() ? 0u : 1u);
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

// The log's bytes are those LCM's own writer gives (lcm::LogFile, what lcm-logger uses).
TEST(LogWriterTest, WritesTheBytesLcmsOwnWriterWrites) {
  const std::string ours = TempPath("ours");
  const std::string lcms = TempPath("lcms");
  {
    LogWriter writer(ours);
    lcm::LogFile reference(lcms, "w");
    ASSERT_TRUE(reference.good());
    const std::vector<std::pair<std::string, std::vector<uint8_t>>> events = {
        {"ODOMETRY", {1, 2, 3}}, {"X", {}}, {std::string(63, 'C'), std::vector<uint8_t>(70000, 7)}};
    int64_t t = -5;
    for (const auto& [channel, data] : events) {
      writer.Write(t, channel, data.data(), static_cast<int>(data.size()));
      lcm::LogEvent event;
      event.eventnum = 0;
      event.timestamp = t;
      event.channel = channel;
      event.datalen = static_cast<int32_t>(data.size());
      event.data = const_cast<uint8_t*>(data.data());
      ASSERT_EQ(reference.writeEvent(&event), 0);
      t += 1700000000000000;
    }
    writer.Commit();
  }
  const std::string bytes_ours = ReadAll(ours);
  const std::string bytes_lcms = ReadAll(lcms);
  EXPECT_EQ(bytes_ours.size(), 3u * 28 + 8 + 1 + 63 + 3 + 70000);
  EXPECT_TRUE(bytes_ours == bytes_lcms);
  std::remove(ours.c_str());
  std::remove(lcms.c_str());
}

// Before: LogWriter wrote "<path>.partial.<pid>" with fopen("w"): a link planted at that name
// was followed and its target overwritten (a whole replay's output went into it). Now nothing
// planted beside the output, nor at the output's own name, is written through.
TEST(LogWriterTest, PlantedLinksAreNeverWrittenThrough) {
  const std::string directory = testing::TempDir() + "/planted_" + std::to_string(getpid());
  std::filesystem::create_directories(directory);
  const std::string victim = directory + "/victim";
  std::ofstream(victim) << "precious\n";
  const std::string path = directory + "/out.lcm";
  ASSERT_EQ(symlink(victim.c_str(), (path + ".partial." + std::to_string(getpid())).c_str()), 0);
  for (int n = 0; n < 4; ++n) {
    const std::string link =
        path + ".partial." + std::to_string(getpid()) + "." + std::to_string(n);
    ASSERT_EQ(symlink(victim.c_str(), link.c_str()), 0);
  }
  std::filesystem::create_symlink(victim, path);  // the output's own name, too
  {
    LogWriter writer(path);
    const char bytes[4] = {1, 2, 3, 4};
    writer.Write(1, "X", bytes, 4);
    writer.Commit();
  }
  EXPECT_EQ(ReadAll(victim), "precious\n");
  EXPECT_FALSE(std::filesystem::is_symlink(path));  // the link was replaced, not followed
  EXPECT_EQ(std::filesystem::file_size(path), 28u + 1 + 4);
  std::filesystem::remove_all(directory);
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
