// Temporary files of a run (system/temporary_files.h): created from a pattern
// and registered, removed all at once by the signal handlers' call (with the
// child writing them killed and reaped), and forgotten once committed.
#include <string>

#include <chrono>
#include <set>
#include <fstream>
#include <fcntl.h>
#include <filesystem>
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "support/private_tmpdir.h"
#include "system/temporary_files.h"

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

TEST_CASE("the writer gets SIGTERM first (to remove its own files), SIGKILL when it ignores that") {
  int pipe_fds[2];
  REQUIRE(::pipe(pipe_fds) == 0);
  const pid_t tidy = ::fork();
  REQUIRE(tidy >= 0);
  if (tidy == 0) {
    static int report = -1;
    report = pipe_fds[1];
    ::signal(SIGTERM, [](int) {
      const char done = 't';
      (void)!::write(report, &done, 1);
      ::_exit(3);
    });
    for (;;) ::pause();
  }
  ::close(pipe_fds[1]);
  ::usleep(50000);  // the handler is installed
  SetTemporaryFileWriter(tidy);
  RemoveTemporaryFilesNow();
  char seen = 0;
  CHECK(::read(pipe_fds[0], &seen, 1) == 1);
  CHECK(seen == 't');
  ::close(pipe_fds[0]);

  const pid_t stubborn = ::fork();
  REQUIRE(stubborn >= 0);
  if (stubborn == 0) {
    ::signal(SIGTERM, SIG_IGN);
    for (;;) ::pause();
  }
  ::usleep(50000);
  SetTemporaryFileWriter(stubborn);
  const auto start = std::chrono::steady_clock::now();
  RemoveTemporaryFilesNow();
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(::kill(stubborn, 0) == -1);  // killed and reaped
  CHECK(waited > 0.5);
  CHECK(waited < 5.0);
}

TEST_CASE("an unnamed file is readable and writable, close-on-exec, and adds no name to the temporary folder") {
  const driveid::testing::PrivateTmpdir private_tmpdir;
  const auto listing = [] {
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::temp_directory_path())) {
      names.insert(entry.path().filename().string());
    }
    return names;
  };
  const auto before = listing();
  const int fd = CreateUnnamedFile();
  REQUIRE(fd >= 0);
  CHECK((::fcntl(fd, F_GETFD) & FD_CLOEXEC) != 0);
  CHECK(::write(fd, "abc", 3) == 3);
  CHECK(listing() == before);
  // Reopened through /proc, as a child reaches it.
  std::ifstream again("/proc/self/fd/" + std::to_string(fd));
  std::string text;
  again >> text;
  CHECK(text == "abc");
  ::close(fd);
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
