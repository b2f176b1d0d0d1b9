#include <cstdio>
#include <filesystem>

#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/csv_log.h"
#include "io/sha256.h"

TEST_CASE("sha256 matches the FIPS 180-4 examples") {
  CHECK(driveid::Sha256Hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(driveid::Sha256Hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(driveid::Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  // 1,000,000 times 'a' crosses many blocks.
  CHECK(driveid::Sha256Hex(std::string(1000000, 'a')) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // 55 and 56 bytes straddle the one/two padding block boundary.
  CHECK(driveid::Sha256Hex(std::string(56, 'a')) ==
        "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
}

TEST_CASE("atomic write replaces the file whole and leaves no temporary") {
  const auto dir = std::filesystem::temp_directory_path() / "driveid_atomic_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "out.yaml").string();
  driveid::WriteFileAtomically(path, "first\n");
  driveid::WriteFileAtomically(path, "second\n");
  CHECK(driveid::ReadFileToString(path) == "second\n");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files;
  CHECK(files == 1);
  CHECK_THROWS_AS(driveid::WriteFileAtomically((dir / "missing" / "x").string(), "x"), driveid::OutputError);
  std::filesystem::remove_all(dir);
}

namespace {
mode_t ModeOf(const std::string& path) {
  struct stat status {};
  REQUIRE(::stat(path.c_str(), &status) == 0);
  return status.st_mode & 07777;
}
}  // namespace

TEST_CASE("outputs: umask honoured, existing mode kept, read-only and directories refused, links written through") {
  namespace fs = std::filesystem;
  const auto dir = fs::temp_directory_path() / "driveid_output_modes_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const mode_t old_mask = ::umask(027);
  const std::string fresh = (dir / "fresh.yaml").string();
  driveid::WriteFileAtomically(fresh, "x\n");
  CHECK(ModeOf(fresh) == 0640);  // 0666 less the umask
  ::umask(old_mask);

  const std::string secret = (dir / "secret.yaml").string();
  driveid::WriteFileAtomically(secret, "old\n");
  REQUIRE(::chmod(secret.c_str(), 0600) == 0);
  driveid::WriteFileAtomically(secret, "new\n");
  CHECK(ModeOf(secret) == 0600);
  CHECK(driveid::ReadFileToString(secret) == "new\n");

  const std::string locked = (dir / "locked.yaml").string();
  driveid::WriteFileAtomically(locked, "keep\n");
  REQUIRE(::chmod(locked.c_str(), 0444) == 0);
  CHECK_THROWS_AS(driveid::WriteFileAtomically(locked, "lost\n"), driveid::OutputError);
  CHECK(driveid::ReadFileToString(locked) == "keep\n");

  CHECK_THROWS_AS(driveid::WriteFileAtomically(dir.string(), "x"), driveid::OutputError);
  CHECK(fs::is_directory(dir));

  const std::string target = (dir / "target.yaml").string();
  const std::string link = (dir / "link.yaml").string();
  driveid::WriteFileAtomically(target, "before\n");
  fs::create_symlink(target, link);
  driveid::WriteFileAtomically(link, "after\n");
  CHECK(fs::is_symlink(link));
  CHECK(driveid::ReadFileToString(target) == "after\n");
  fs::remove_all(dir);
}

TEST_CASE("outputs: a FIFO is written in place, never replaced; without a reader it is an error, not a hang") {
  namespace fs = std::filesystem;
  const auto dir = fs::temp_directory_path() / "driveid_output_fifo_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string fifo = (dir / "pipe").string();
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_AS(driveid::WriteFileAtomically(fifo, "x\n"), driveid::OutputError);
  CHECK(fs::is_fifo(fifo));
  // /dev/null takes the output and stays a character device.
  driveid::WriteFileAtomically("/dev/null", "discarded\n");
  CHECK(fs::is_character_file("/dev/null"));
  // /dev/full reports the write error.
  if (fs::exists("/dev/full")) CHECK_THROWS_AS(driveid::WriteFileAtomically("/dev/full", "x\n"), driveid::OutputError);
  fs::remove_all(dir);
}
