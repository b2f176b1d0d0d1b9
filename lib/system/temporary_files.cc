#include "system/temporary_files.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cstring>
#include <vector>

#include <filesystem>
#include <system_error>

#include <fcntl.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

namespace driveid {
namespace {

// A fixed table (no allocation in the handler): a slot is free (0), being
// filled or emptied (1), or holds a path (2).
constexpr std::size_t kSlots = 64;
std::array<std::atomic<int>, kSlots> slot_state{};
std::array<std::array<char, PATH_MAX>, kSlots> slot_path{};
std::atomic<pid_t> writer{0};

void Register(const char* path) {
  if (std::strlen(path) >= PATH_MAX) return;  // mkstemp could not have made it anyway
  for (std::size_t i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (slot_state[i].compare_exchange_strong(expected, 1)) {
      std::strcpy(slot_path[i].data(), path);
      slot_state[i].store(2);
      return;
    }
  }
  // More than kSlots temporary files at once: this one is not tracked (the
  // tools never hold more than a handful).
}

sigset_t TerminationSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  sigaddset(&set, SIGPIPE);
  return set;
}

}  // namespace

TerminationSignalsBlocked::TerminationSignalsBlocked() {
  const sigset_t set = TerminationSignals();
  pthread_sigmask(SIG_BLOCK, &set, &saved_);
}

TerminationSignalsBlocked::~TerminationSignalsBlocked() { pthread_sigmask(SIG_SETMASK, &saved_, nullptr); }

int CreateTemporaryFile(std::string& pattern, int suffix_length) {
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  TerminationSignalsBlocked blocked;
  const int fd = ::mkstemps(name.data(), suffix_length);
  if (fd < 0) return -1;
  Register(name.data());
  pattern = name.data();
  return fd;
}

void ForgetTemporaryFile(const std::string& path) {
  for (std::size_t i = 0; i < kSlots; ++i) {
    int expected = 2;
    if (slot_state[i].load() == 2 && path == slot_path[i].data() && slot_state[i].compare_exchange_strong(expected, 1)) {
      slot_state[i].store(0);
      return;
    }
  }
}

void RemoveTemporaryFile(const std::string& path) {
  ::unlink(path.c_str());
  ForgetTemporaryFile(path);
}

void SetTemporaryFileWriter(pid_t child) { writer.store(child); }

void RemoveTemporaryFilesNow() noexcept {
  const int saved_errno = errno;
  const pid_t child = writer.exchange(0);
  if (child > 0) {
    // SIGTERM first, so that the child can remove its own files (the MAT
    // reader's named copy), then SIGKILL after at most a second.
    ::kill(child, SIGTERM);
    bool reaped = false;
    for (int tick = 0; tick < 100 && !reaped; ++tick) {
      reaped = ::waitpid(child, nullptr, WNOHANG) == child;
      const struct timespec pause = {0, 10'000'000};
      if (!reaped) ::nanosleep(&pause, nullptr);
    }
    if (!reaped) ::kill(child, SIGKILL);
    while (!reaped && ::waitpid(child, nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  for (std::size_t i = 0; i < kSlots; ++i) {
    if (slot_state[i].load() == 2) ::unlink(slot_path[i].data());
  }
  errno = saved_errno;
}

int CreateUnnamedFile() {
  std::error_code error;
  const auto folder = std::filesystem::temp_directory_path(error);
  int fd = error ? -1 : ::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd < 0) fd = ::memfd_create("driveid", MFD_CLOEXEC);
  return fd;
}

}  // namespace driveid
