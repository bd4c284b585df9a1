#include "drivers/command_auth/command_key.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <string>

#include "tests/support/child_process.h"

namespace slammtt {
namespace {

const char kKeyText[] = "00112233445566778899aabbccddeeff00112233445566778899AABBCCDDEEFF";

void WriteFile(const std::string& path, const std::string& text, mode_t mode) {
  std::ofstream(path) << text;
  ASSERT_EQ(chmod(path.c_str(), mode), 0);
}

std::string LoadError(const std::string& path) {
  try {
    LoadCommandKeyFile(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(CommandKeyTest, ParsesSixtyFourHexDigitsWithSurroundingWhiteSpace) {
  const auto key = ParseCommandKey(std::string("  ") + kKeyText + "\n");
  ASSERT_TRUE(key.has_value());
  EXPECT_EQ((*key)[0], 0x00);
  EXPECT_EQ((*key)[1], 0x11);
  EXPECT_EQ((*key)[15], 0xff);
  EXPECT_EQ((*key)[31], 0xff);
  EXPECT_EQ(CommandKeyText(*key),
            "00112233445566778899aabbccddeeff00112233445566778899aabbccddeeff");
  EXPECT_FALSE(ParseCommandKey("").has_value());
  EXPECT_FALSE(ParseCommandKey(std::string(kKeyText).substr(0, 62)).has_value());
  EXPECT_FALSE(ParseCommandKey(std::string(kKeyText) + "00").has_value());
  std::string bad = kKeyText;
  bad[10] = 'g';
  EXPECT_FALSE(ParseCommandKey(bad).has_value());
  bad = kKeyText;
  bad[32] = ' ';
  EXPECT_FALSE(ParseCommandKey(bad).has_value());
}

TEST(CommandKeyTest, NewKeysDifferAndRoundTripThroughTheirText) {
  const CommandKey a = NewCommandKey();
  const CommandKey b = NewCommandKey();
  EXPECT_NE(a, b);
  EXPECT_EQ(ParseCommandKey(CommandKeyText(a)), a);
}

TEST(CommandKeyTest, LoadsAKeyFileTheGroupMayRead) {
  testing::TempDir dir("command-key-test");
  const std::string path = dir.path() + "/command.key";
  WriteFile(path, std::string(kKeyText) + "\n", 0640);
  EXPECT_EQ(CommandKeyText(LoadCommandKeyFile(path)), CommandKeyText(*ParseCommandKey(kKeyText)));
}

TEST(CommandKeyTest, RefusesKeyFilesOthersCanReadOrWriteAndThingsThatAreNoKeyFile) {
  testing::TempDir dir("command-key-test");
  const std::string path = dir.path() + "/command.key";
  WriteFile(path, kKeyText, 0644);
  EXPECT_NE(LoadError(path).find("open to other users (mode 644)"), std::string::npos)
      << LoadError(path);
  ASSERT_EQ(chmod(path.c_str(), 0602), 0);
  EXPECT_NE(LoadError(path).find("open to other users"), std::string::npos);

  EXPECT_NE(LoadError(dir.path()).find("not a regular file"), std::string::npos);
  EXPECT_NE(LoadError("/dev/zero").find("not a regular file"), std::string::npos);
  const std::string fifo = dir.path() + "/fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(LoadError(fifo).find("not a regular file"), std::string::npos);  // and no hang
  EXPECT_NE(LoadError(dir.path() + "/missing").find("cannot open the command key file"),
            std::string::npos);

  const std::string short_key = dir.path() + "/short.key";
  WriteFile(short_key, std::string(kKeyText).substr(0, 40), 0600);
  EXPECT_NE(LoadError(short_key).find("expected 64 hexadecimal digits"), std::string::npos);
  const std::string big = dir.path() + "/big.key";
  WriteFile(big, std::string(100000, 'a'), 0600);
  EXPECT_NE(LoadError(big).find("not a command key file (100000 bytes"), std::string::npos);
  for (const std::string& error : {LoadError(path), LoadError(short_key), LoadError(big)}) {
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

TEST(CommandKeyTest, NewKeyFilesAreExclusivePrivateAndNeverFollowAPlantedLink) {
  testing::TempDir dir("command-key-test");
  const std::string path = dir.path() + "/command.key";
  const CommandKey key = NewCommandKey();
  WriteNewCommandKeyFile(path, key);
  struct stat info {};
  ASSERT_EQ(stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u);
  EXPECT_EQ(LoadCommandKeyFile(path), key);
  EXPECT_THROW(WriteNewCommandKeyFile(path, NewCommandKey()), std::runtime_error);
  EXPECT_EQ(LoadCommandKeyFile(path), key);  // not overwritten

  const std::string target = dir.path() + "/victim";
  WriteFile(target, "precious\n", 0600);
  const std::string link = dir.path() + "/planted.key";
  ASSERT_EQ(symlink(target.c_str(), link.c_str()), 0);
  EXPECT_THROW(WriteNewCommandKeyFile(link, key), std::runtime_error);
  EXPECT_EQ(testing::ReadWholeFile(target), "precious\n");
  const std::string dangling = dir.path() + "/dangling.key";
  ASSERT_EQ(symlink((dir.path() + "/created-through-link").c_str(), dangling.c_str()), 0);
  EXPECT_THROW(WriteNewCommandKeyFile(dangling, key), std::runtime_error);
  EXPECT_NE(access((dir.path() + "/created-through-link").c_str(), F_OK), 0);
}

}  // namespace
}  // namespace slammtt
