// The key a robot shares with the base stations allowed to drive it: 32 random bytes, kept in a
// text file as 64 hexadecimal digits on one line (so it can be copied to a base station as
// text). HMAC-SHA256 (command_signature.h) takes it as its key; RFC 2104 section 3 asks for a
// key at least as long as the hash output, 32 bytes for SHA-256.
//
// Files: the key is a secret, so a key file must be a regular file that other users can neither
// read nor write (mode & 0007 == 0; the group may read it, so that /etc/slammtt/command.key can
// belong to root:slammtt with mode 0640). New key files are created exclusively (an existing
// file or a planted symlink of that name is an error, never overwritten) with mode 0600.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace slammtt {

inline constexpr size_t kCommandKeyBytes = 32;
using CommandKey = std::array<uint8_t, kCommandKeyBytes>;

// 64 hexadecimal digits (either case), optionally surrounded by white space (a trailing newline).
// nullopt for anything else. Pure.
std::optional<CommandKey> ParseCommandKey(const std::string& text);
// The 64 lower-case hexadecimal digits of `key`, without a newline. Pure.
std::string CommandKeyText(const CommandKey& key);

// Reads a key file. Throws std::runtime_error, one line naming the path and the reason, when it
// cannot be opened, is not a regular file, is readable or writable by others, is larger than a
// key file can be, or does not hold a key.
CommandKey LoadCommandKeyFile(const std::string& path);

// A new key from the operating system's random source (OpenSSL RAND_bytes). Throws
// std::runtime_error when the source fails.
CommandKey NewCommandKey();

// Writes `key` into a new file `path` (O_CREAT | O_EXCL | O_NOFOLLOW, mode 0600), flushed to
// disk. Throws std::runtime_error naming the path when the file exists or cannot be written.
void WriteNewCommandKeyFile(const std::string& path, const CommandKey& key);

}  // namespace slammtt
