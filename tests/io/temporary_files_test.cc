// Temporary files of a run (io/temporary_files.h): created from a pattern
// and registered, removed all at once by the signal handlers' call (with the
// child writing them killed and reaped), and forgotten once committed.
#include <string>

#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/temporary_files.h"

namespace driveid {
namespace {

bool Exists(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0;
}

std::string Directory() {
  char pattern[] = "/tmp/driveid-temporary-test-XXXXXX";
  REQUIRE(::mkdtemp(pattern) != nullptr);
  return pattern;
}

TEST_CASE("created from the pattern with its suffix kept; the handler's call removes what is registered") {
  const std::string dir = Directory();
  std::string staged = dir + "/out.yaml.XXXXXX", image = dir + "/plot-XXXXXX.png", committed = dir + "/kept-XXXXXX";
  for (std::string* pattern : {&staged, &image, &committed}) {
    const int suffix = pattern == &image ? 4 : 0;
    const int fd = CreateTemporaryFile(*pattern, suffix);
    REQUIRE(fd >= 0);
    ::close(fd);
    CHECK(pattern->find("XXXXXX") == std::string::npos);
    CHECK(Exists(*pattern));
  }
  CHECK(image.substr(image.size() - 4) == ".png");
  // Committed (renamed into place elsewhere): forgotten, so not removed.
  ForgetTemporaryFile(committed);
  RemoveTemporaryFilesNow();
  CHECK_FALSE(Exists(staged));
  CHECK_FALSE(Exists(image));
  CHECK(Exists(committed));
  // RemoveTemporaryFile removes and forgets one.
  std::string one = dir + "/one-XXXXXX";
  const int fd = CreateTemporaryFile(one);
  REQUIRE(fd >= 0);
  ::close(fd);
  RemoveTemporaryFile(one);
  CHECK_FALSE(Exists(one));
  ::unlink(committed.c_str());
  CHECK(::rmdir(dir.c_str()) == 0);
}

TEST_CASE("a pattern in a directory that does not exist gives -1 and registers nothing") {
  std::string pattern = "/nonexistent-driveid-dir/x-XXXXXX";
  CHECK(CreateTemporaryFile(pattern) == -1);
  RemoveTemporaryFilesNow();  // nothing to remove, nothing to crash on
}

TEST_CASE("the registered writer is killed and reaped by the handler's call") {
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    ::pause();
    ::_exit(0);
  }
  SetTemporaryFileWriter(child);
  RemoveTemporaryFilesNow();
  // Reaped already: no child left to wait for.
  CHECK(::waitpid(child, nullptr, WNOHANG) == -1);
  CHECK(::kill(child, 0) == -1);
}

TEST_CASE("termination signals are held while blocked and delivered at the end") {
  static volatile sig_atomic_t received = 0;
  struct sigaction action {}, saved {};
  action.sa_handler = [](int) { received = 1; };
  sigemptyset(&action.sa_mask);
  REQUIRE(::sigaction(SIGHUP, &action, &saved) == 0);
  {
    TerminationSignalsBlocked blocked;
    ::raise(SIGHUP);
    CHECK(received == 0);
  }
  CHECK(received == 1);
  ::sigaction(SIGHUP, &saved, nullptr);
}

}  // namespace
}  // namespace driveid
