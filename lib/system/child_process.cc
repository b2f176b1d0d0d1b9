#include "system/child_process.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <vector>

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "system/temporary_files.h"

// AddressSanitizer reserves its shadow memory up front: an address-space
// cap would make every allocation fail, so the cap is left out there.
#if defined(__SANITIZE_ADDRESS__)
#define DRIVEID_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DRIVEID_ASAN 1
#endif
#endif

namespace driveid {

bool WriteAll(int fd, const char* bytes, std::size_t size) noexcept {
  std::size_t written = 0;
  while (written < size) {
    const ssize_t n = ::write(fd, bytes + written, size - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    written += static_cast<std::size_t>(n);
  }
  return true;
}

ChildOutcome RunInChild(const std::function<void()>& body, const ChildLimits& limits) {
  ChildOutcome outcome;
  int fds[2];
  if (::pipe(fds) != 0) return outcome;
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return outcome;
  }
  if (child == 0) {
    // The child dies with the tool, however the tool ends (SIGKILL too).
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(1);
    ::close(fds[0]);
#if !defined(DRIVEID_ASAN)
    if (limits.address_space_bytes > 0.0) {
      const rlim_t cap = static_cast<rlim_t>(std::min(limits.address_space_bytes, 1e18));
      const struct rlimit limit = {cap, cap};
      ::setrlimit(RLIMIT_AS, &limit);
    }
#endif
    if (fds[1] != STDOUT_FILENO) {
      ::dup2(fds[1], STDOUT_FILENO);
      ::close(fds[1]);
    }
    body();
    ::_exit(0);
  }
  ::close(fds[1]);
  outcome.started = true;
  SetTemporaryFileWriter(child);  // killed by the tools' signal handlers
  std::vector<char> chunk(1 << 16);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(limits.seconds);
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      outcome.timed_out = true;
      break;
    }
    struct pollfd p = {fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1'000'000'000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) {
      outcome.timed_out = ready == 0;
      break;
    }
    const ssize_t n = ::read(fds[0], chunk.data(), chunk.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    outcome.output.append(chunk.data(), static_cast<std::size_t>(n));
    if (outcome.output.size() > limits.max_output_bytes) break;
  }
  ::close(fds[0]);
  // Past the output limit or the deadline the child is of no more use:
  // SIGTERM first (a child may remove its own files then), SIGKILL after 1 s.
  int status = 0;
  bool reaped = false;
  if (outcome.timed_out || outcome.output.size() > limits.max_output_bytes) {
    ::kill(child, SIGTERM);
    for (int tick = 0; tick < 100 && !reaped; ++tick) {
      reaped = ::waitpid(child, &status, WNOHANG) == child;
      if (!reaped) ::usleep(10000);
    }
    if (!reaped) ::kill(child, SIGKILL);
  }
  while (!reaped && ::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  SetTemporaryFileWriter(0);
  outcome.exited = WIFEXITED(status);
  outcome.exit_code = outcome.exited ? WEXITSTATUS(status) : 0;
  outcome.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  return outcome;
}

}  // namespace driveid
