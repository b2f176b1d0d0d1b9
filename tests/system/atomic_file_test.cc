// system/atomic_file.h: an output replaced whole or not at all, its mode
// and links honoured, a FIFO written in place.
#include <cstdio>
#include <filesystem>

#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "system/atomic_file.h"
#include "system/file_reading.h"

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
